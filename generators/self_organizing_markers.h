// The self-organizing model's space-colonization environment (Palubicki et al. 2009 §4.1): its
// markers in a hashed uniform grid, for the growth loop in generators/self_organizing.cpp.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "generators/self_organizing.h"
#include "generators/skeleton.h"

namespace sylva {

// Space-colonization markers in a hashed uniform grid (cell = perception distance).
struct marker_state {
  std::vector<glm::vec3> pos;
  std::vector<uint8_t> alive;
  // Per marker, this step: the closest perceiving bud (nb·node + k: k = 0 the main bud, 1 and 2
  // the laterals) in the low 32 bits, its squared distance's bits in the high ones; no_bud between
  // steps.
  static constexpr uint64_t no_bud = ~uint64_t(0);
  std::vector<uint64_t> best;
  float cell = 1;
  std::vector<uint64_t> cell_key;    // sorted cell keys, with [cell_start[k], cell_start[k+1]) markers
  std::vector<uint32_t> cell_start;
  std::vector<uint32_t> order;       // marker indices grouped by cell

  static uint64_t key(const glm::ivec3& c) {
    return (uint64_t(uint32_t(c.x + (1 << 20)) & 0x1FFFFF) << 42) |
           (uint64_t(uint32_t(c.y + (1 << 20)) & 0x1FFFFF) << 21) | uint64_t(uint32_t(c.z + (1 << 20)) & 0x1FFFFF);
  }
  glm::ivec3 cell_of(const glm::vec3& p) const {
    const glm::vec3 f = glm::clamp(glm::floor(p / cell), glm::vec3(-1e6f), glm::vec3(1e6f));
    return glm::ivec3(f);
  }
  void build() {
    std::vector<std::pair<uint64_t, uint32_t>> kv(pos.size());
    for (size_t i = 0; i < pos.size(); ++i) kv[i] = {key(cell_of(pos[i])), uint32_t(i)};
    std::sort(kv.begin(), kv.end());
    order.resize(kv.size());
    cell_key.clear();
    cell_start.clear();
    for (size_t i = 0; i < kv.size(); ++i) {
      if (i == 0 || kv[i].first != kv[i - 1].first) {
        cell_key.push_back(kv[i].first);
        cell_start.push_back(uint32_t(i));
      }
      order[i] = kv[i].second;
    }
    cell_start.push_back(uint32_t(kv.size()));
    alive.assign(pos.size(), 1);
    best.assign(pos.size(), no_bud);
  }
  // Calls f(marker) for the live markers (all when dead_too) within distance d of p, cell by cell
  // (z, then y, then x) and in each cell in index order.
  // Cell keys sort x first, then y, then z, so a column of cells (x, y, lo.z .. hi.z) is one run
  // of keys: one binary search per column finds its start, and a cursor per column then steps to
  // each z in turn (a query of 3 × 3 × 3 cells makes 9 searches instead of 27).
  template <class F>
  void visit_near(const glm::vec3& p, float d, F&& f, bool dead_too = false) const {
    const glm::ivec3 lo = cell_of(p - d), hi = cell_of(p + d);
    const float d2 = d * d;
    constexpr int most = 8;   // columns a side searched once each; wider queries search per cell
    const int nx = hi.x - lo.x + 1, ny = hi.y - lo.y + 1;
    const bool columns = nx >= 1 && ny >= 1 && nx <= most && ny <= most;
    size_t at[most][most];
    if (columns)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x)
          at[y - lo.y][x - lo.x] = size_t(std::lower_bound(cell_key.begin(), cell_key.end(), key({x, y, lo.z})) - cell_key.begin());
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
          const uint64_t k = key({x, y, z});
          size_t c;
          if (columns) {
            size_t& a = at[y - lo.y][x - lo.x];
            while (a < cell_key.size() && cell_key[a] < k) ++a;
            if (a == cell_key.size() || cell_key[a] != k) continue;
            c = a;
          } else {
            const auto it = std::lower_bound(cell_key.begin(), cell_key.end(), k);
            if (it == cell_key.end() || *it != k) continue;
            c = size_t(it - cell_key.begin());
          }
          for (uint32_t j = cell_start[c]; j < cell_start[c + 1]; ++j) {
            const uint32_t m = order[j];
            if (!alive[m] && !dead_too) continue;
            const glm::vec3 dv = pos[m] - p;
            if (glm::dot(dv, dv) <= d2) f(m, dv);
          }
        }
  }
};

// Markers in an ellipsoidal crown envelope above each tree (Palubicki 2009 §4.1), from the params'
// envelope and count, at most so_marker_cap in all (shared by the trees; message says so then).
// Fills pos only: the caller sets the cell and builds the grid.
void fill_marker_envelopes(marker_state& m, const std::vector<glm::vec3>& roots_at, const self_organizing_params& p, rng& r,
                           std::string& message);

// Scratch of perceive_markers: each chunk's markers in the order its buds met them.
struct marker_scratch {
  std::vector<std::vector<uint32_t>> seen;
};
// Palubicki 2009 §4.1: each live marker is perceived by the closest bud that holds it in its cone
// (within reach, at most acos(cos_theta) off the bud's default direction), the earliest bud where
// two are as close. Buds 0 .. buds - 1, in bud order, from bud_at(j, pos, def); perceived(j, m)
// for each perceived marker m and its bud j, in the order the buds, scanned in order, first met
// the markers (so sums over a bud's markers are the same bits however the scan ran). m.best is
// no_bud for every marker on entry and on return.
// The buds are scanned in chunks on the shared pool (job_pool.h): each marker keeps the least key
// (d², bud) any chunk offers, which is the closest bud and the earliest on a tie, as one scan in
// order finds; the chunks' lists of markers met, taken in chunk order, meet each marker first
// where one scan in order does.
void perceive_markers(marker_state& m, size_t buds, const std::function<void(size_t, glm::vec3&, glm::vec3&)>& bud_at,
                      float reach, float cos_theta, marker_scratch& scratch,
                      const std::function<void(size_t, uint32_t)>& perceived);

}  // namespace sylva
