// Space colonization (Runions, Lane & Prusinkiewicz 2007): incremental nearest-node search, growth, widths, leaves.
#include "generators/space_colonization.h"

#include <algorithm>
#include <cstdio>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "generators/history.h"
#include "generators/job_pool.h"
#include "generators/keyframes.h"
#include "generators/pruning.h"
#include "generators/resume.h"
#include "generators/vec_util.h"

namespace sylva {
namespace {

constexpr float cell_fraction = 0.5f;
// A killed point's slot position: its squared distance to any node passes every radius (finite:
// (1e18)^2 times 3 is under FLT_MAX).
constexpr float far_away = 1e18f;

// Attraction points in a dense uniform grid over their bounding box, cell size d_i/2, sorted by cell
// once; points never move. A killed point keeps its slot with its position sent far away, so no
// distance test passes it. A node scans, row by row, the cells of its 2·d_i box that come within
// d_i of it: the cells of one row are consecutive in memory, so a row is one run of slots with no
// per-cell lookup. Each point caches its nearest node, and only a new node can change that cache:
// an iteration costs O(new nodes · local points + influenced points), and nodes that nothing
// influences cost nothing.
// Measured grow time (Release, thread CPU time, min of 5, on the 2-core dev box under load ~8), bench
// presets, when each cell was scanned on its own: 10k points 6.7 ms (3,309 nodes), 75k 41 ms (5,001
// nodes), 1M 0.86 s (6,225 nodes). On 75k points with d_i = 3, cells of d_i/2 took 51 ms against 68
// ms for d_i and 52 ms for d_i/3. Rows instead of cells, dead points left in place and the
// branch-free first pass (2026-12-05; `sylva bench P --repeat 31 --threads 1`, medians, three
// alternating rounds): space_colonization_seed_cube grow 4.75 → 3.65 ms, bench/space_colonization_75k
// 24 → 19.4 ms; the seed cube's nodes move by at most 1e-6 m (its active list, and so its pull
// sums, come in another order), every other preset's export is byte-identical. nanoflann was not
// measured: a k-d tree over the nodes would need extending every iteration, while this grid over
// the static points is built once.
struct colonization_state {
  const std::vector<glm::vec3>* pts = nullptr;
  float di2 = 0, dk2 = -1;
  glm::vec3 origin{0};
  float inv_cell = 1;
  glm::ivec3 dim{1};
  std::vector<int32_t> cell_begin, slots, slot_of;
  std::vector<glm::vec3> slot_pos;  // pts[slots[j]] while alive, far_away once killed; scans read it in order
  std::vector<int32_t> nearest;   // by slot: the nearest node within d_i, or -1
  std::vector<float> nearest_d2;  // by slot: its squared distance, d_i² while there is none
  std::vector<int32_t> killed;    // step a point was removed in, or -1 while alive
  std::vector<int32_t> dropped_by;   // a point dropped unreached: the node it was nearest to (else -1)
  std::vector<int32_t> active;    // points with a nearest node (may hold dead ones until compacted)
  std::vector<int32_t> hits;      // visit_new_node's scratch: the slots within reach of the node
  size_t alive = 0;
};

void init_state(colonization_state& s, const std::vector<glm::vec3>& pts, float d_i, float d_k) {
  s.pts = &pts;
  s.di2 = d_i * d_i;
  s.dk2 = d_k >= 0 ? d_k * d_k : -1.0f;
  const size_t n = pts.size();
  s.killed.assign(n, -1);
  s.dropped_by.assign(n, -1);
  s.slot_of.assign(n, -1);
  glm::vec3 lo(0), hi(0);
  bool any = false;
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3& q = pts[i];
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) {
      s.killed[i] = 0;  // bad input: never part of the cloud
      continue;
    }
    lo = any ? glm::min(lo, q) : q;
    hi = any ? glm::max(hi, q) : q;
    any = true;
    ++s.alive;
  }
  // Cells of size d_i/2: a query box of 2·d_i then scans (2.5·d_i)^3 on average instead of (3·d_i)^3
  // for cells of size d_i. Enlarged when that would make more than ~4 cells per point (tiny d_i).
  float cell = std::max(d_i * cell_fraction, 1e-6f);
  const double max_cells = std::max<double>(4096.0, 4.0 * double(n));
  for (;;) {
    const glm::vec3 d = (hi - lo) / cell;
    const double cells = (double(d.x) + 1) * (double(d.y) + 1) * (double(d.z) + 1);
    if (cells <= max_cells) break;
    cell *= float(std::cbrt(cells / max_cells)) * 1.01f;
  }
  s.origin = lo;
  s.inv_cell = 1.0f / cell;
  s.dim = glm::ivec3(glm::floor((hi - lo) * s.inv_cell)) + 1;
  const size_t cells = size_t(s.dim.x) * size_t(s.dim.y) * size_t(s.dim.z);
  s.cell_begin.assign(cells + 1, 0);
  std::vector<int32_t> cell_of(n, -1), fill(cells, 0);
  for (size_t i = 0; i < n; ++i) {
    if (s.killed[i] >= 0) continue;
    const glm::ivec3 c = glm::clamp(glm::ivec3((pts[i] - lo) * s.inv_cell), glm::ivec3(0), s.dim - 1);
    cell_of[i] = (c.z * s.dim.y + c.y) * s.dim.x + c.x;
    ++fill[size_t(cell_of[i])];
  }
  for (size_t c = 0; c < cells; ++c) s.cell_begin[c + 1] = s.cell_begin[c] + fill[c];
  s.slots.assign(size_t(s.cell_begin[cells]), -1);
  s.slot_pos.resize(s.slots.size());
  s.nearest.assign(s.slots.size(), -1);
  s.nearest_d2.assign(s.slots.size(), s.di2);
  std::copy(s.cell_begin.begin(), s.cell_begin.end() - 1, fill.begin());
  for (size_t i = 0; i < n; ++i)
    if (s.killed[i] < 0) {
      const int32_t slot = fill[size_t(cell_of[i])]++;
      s.slots[size_t(slot)] = int32_t(i);
      s.slot_pos[size_t(slot)] = pts[i];
      s.slot_of[i] = slot;
    }
}

// Point i's nearest node within d_i (-1: none) and its squared distance.
int32_t nearest_of(const colonization_state& s, int32_t i) { return s.nearest[size_t(s.slot_of[size_t(i)])]; }
float nearest_d2_of(const colonization_state& s, int32_t i) { return s.nearest_d2[size_t(s.slot_of[size_t(i)])]; }

// Removes point i: its slot stays, out of every node's reach.
void kill_point(colonization_state& s, int32_t i, int step) {
  s.slot_pos[size_t(s.slot_of[size_t(i)])] = glm::vec3(far_away);
  s.killed[size_t(i)] = step;
  --s.alive;
}

// The slots within reach (max(d_i, d_k)) of pos, as the grid holds them now, in scan order, written
// to hits from n on; returns the new count. Reads the grid only.
size_t slots_in_reach(const colonization_state& s, const glm::vec3& pos, std::vector<int32_t>& hits, size_t n) {
  const float d_i = std::sqrt(s.di2);
  const glm::vec3 a = (pos - d_i - s.origin) * s.inv_cell, b = (pos + d_i - s.origin) * s.inv_cell;
  glm::ivec3 lo, hi;
  for (int k = 0; k < 3; ++k) {
    // Clamp in float first: a node far outside the cloud must not overflow the int conversion.
    lo[k] = int(std::clamp(std::floor(a[k]), -1.0f, float(s.dim[k])));
    hi[k] = int(std::clamp(std::floor(b[k]), -1.0f, float(s.dim[k])));
    lo[k] = std::max(lo[k], 0);
    hi[k] = std::min(hi[k], s.dim[k] - 1);
    if (lo[k] > hi[k]) return n;
  }
  // Squared distance from pos to a cell's slab along one axis; rows wholly beyond d_i are skipped,
  // and a row's run is trimmed to the cells within d_i along x, which keeps the scan near the
  // sphere of radius d_i.
  const float cell = 1.0f / s.inv_cell;
  auto gap2 = [&](int k, int c) {
    const float a0 = s.origin[k] + float(c) * cell, a1 = a0 + cell;
    const float g = pos[k] < a0 ? a0 - pos[k] : pos[k] > a1 ? pos[k] - a1 : 0.0f;
    return g * g;
  };
  const float di2 = s.di2, dk2 = s.dk2, reach2 = std::max(di2, dk2);
  const glm::vec3* sp = s.slot_pos.data();
  // First the slots within reach, without a branch per slot (about half the slots scanned pass, at
  // random, which a branch mispredicts); then those in slot order. nearest_d2 starts at d_i², so
  // "closer" is also "within d_i", and a point's first nearest node puts it on the active list.
  for (int z = lo.z; z <= hi.z; ++z) {
    const float gz = gap2(2, z);
    for (int y = lo.y; y <= hi.y; ++y) {
      const float gzy = gz + gap2(1, y);
      if (gzy >= reach2) continue;
      const float w = std::sqrt(reach2 - gzy);
      const int x0 = std::max(lo.x, int(std::floor((pos.x - w - s.origin.x) * s.inv_cell)));
      const int x1 = std::min(hi.x, int(std::floor((pos.x + w - s.origin.x) * s.inv_cell)));
      if (x0 > x1) continue;
      const int32_t row = (z * s.dim.y + y) * s.dim.x;
      const int32_t begin = s.cell_begin[size_t(row + x0)], end = s.cell_begin[size_t(row + x1 + 1)];
      if (hits.size() < n + size_t(end - begin)) hits.resize(2 * (n + size_t(end - begin)));
      int32_t* out = hits.data();
      for (int32_t j = begin; j < end; ++j) {
        const glm::vec3 d = sp[j] - pos;
        out[n] = j;
        n += size_t(glm::dot(d, d) < reach2);
      }
    }
  }
  return n;
}

// Node `node` at pos takes the slots `hits` found within its reach: kills those within d_k and
// becomes the nearest node of those it is closer to. A slot killed since it was found lies far
// away now, so it is out of both reaches: found before earlier nodes' kills, the hits still give
// what a scan after them would.
void take_hits(colonization_state& s, const glm::vec3& pos, int32_t node, int step, const int32_t* hits, size_t n) {
  const glm::vec3* sp = s.slot_pos.data();
  const float dk2 = s.dk2;
  float* near_d2 = s.nearest_d2.data();
  int32_t* near = s.nearest.data();
  for (size_t h = 0; h < n; ++h) {
    const int32_t j = hits[h];
    const glm::vec3 d = sp[j] - pos;
    const float d2 = glm::dot(d, d);
    if (d2 <= dk2) {  // Runions 2007 §3: kill within d_k
      kill_point(s, s.slots[size_t(j)], step);
      continue;
    }
    if (d2 < near_d2[j]) {
      if (near[j] < 0) s.active.push_back(s.slots[size_t(j)]);
      near[j] = node;
      near_d2[j] = d2;
    }
  }
}

// A new node kills the points within d_k and becomes the nearest node of those it is closer to.
// Runions 2007 §3: a point influences only its closest node, and only within d_i.
void visit_new_node(colonization_state& s, const glm::vec3& pos, int32_t node, int step) {
  if (s.alive == 0) return;
  const size_t n = slots_in_reach(s, pos, s.hits, 0);
  take_hits(s, pos, node, step, s.hits.data(), n);
}

// visit_new_node for nodes first .. t.size() - 1 in order, stopping after a node whose index is
// a multiple of 1024 when the growth is cancelled. A step of many new nodes (a crown's) finds
// the slots of a window of them at a time, in chunks on the shared pool (job_pool.h), from the
// grid as the nodes before left it, and then takes them node by node: take_hits gives the bits
// one visit after another does, kills in between included.
constexpr size_t parallel_visits = 96;   // new nodes from which a step's slots are found on the pool
constexpr size_t visit_window = 256;     // nodes whose slots are found at once

void visit_new_nodes(colonization_state& s, const tree_skeleton& t, size_t first, int step, const grow_options& o,
                     chunked_results<int32_t>& found) {
  if (t.size() - std::min(first, t.size()) < parallel_visits) {
    for (size_t k = first; k < t.size(); ++k) {
      visit_new_node(s, t.position[k], int32_t(k), step);
      if ((k & 1023) == 0 && o.cancelled()) break;  // the next iteration reports it
    }
    return;
  }
  // Windows of visit_window nodes, so the lists found never hold more than that many nodes' points.
  for (size_t w = first; w < t.size(); w += visit_window) {
    const size_t count = std::min(visit_window, t.size() - w);
    if (s.alive == 0) return;   // (no slot left to find or take)
    found.fill(count, std::max<size_t>(16, count / 16 + 1), [&](size_t, size_t j, std::vector<int32_t>& hits, size_t n) {
      return slots_in_reach(s, t.position[w + j], hits, n);
    });
    for (size_t j = 0; j < count; ++j) {
      const size_t k = w + j;
      if (s.alive > 0) take_hits(s, t.position[k], int32_t(k), step, found.first(j), found.count(j));
      if ((k & 1023) == 0 && o.cancelled()) return;  // the next iteration reports it
    }
  }
}

void compact_active(colonization_state& s) {
  size_t w = 0;
  for (int32_t i : s.active)
    if (s.killed[size_t(i)] < 0) s.active[w++] = i;
  s.active.resize(w);
}

// Logarithmic-spiral leaves on the terminal segments (seed 003): leaf j of m sits at angle
// θ = 2π·rounds·(j+½)/m around the segment, at distance r = a·e^(kθ) from it, and (j+½)/m along it.
void place_spiral_leaves(tree_skeleton& t, const std::vector<uint8_t>& has_child, const space_colonization_params& p,
                         uint64_t seed) {
  const int lo = std::min(p.leaves_min, p.leaves_max), hi = std::max(p.leaves_min, p.leaves_max);
  if (hi == 0) return;
  const float smin = std::min(p.leaf_size_min, p.leaf_size_max), smax = std::max(p.leaf_size_min, p.leaf_size_max);
  rng r(seed ^ 0x5b1a1ea7e5ull);
  for (size_t i = 1; i < t.size(); ++i) {
    if (has_child[i]) continue;
    const glm::vec3 base = t.position[size_t(t.parent[i])];
    const glm::vec3 seg = t.position[i] - base;
    const glm::vec3 dir = glm::normalize(seg);
    // A frame around the segment; the helper axis is the world axis least aligned with it.
    const glm::vec3 helper = std::fabs(dir.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 u = glm::normalize(glm::cross(helper, dir)), w = glm::cross(dir, u);
    const int m = lo + r.uniform_int(hi - lo + 1);
    for (int j = 0; j < m; ++j) {
      const float f = (float(j) + 0.5f) / float(m);
      const float theta = 2.0f * 3.14159265f * p.spiral_rounds * f;
      const float rad = p.spiral_a * std::pow(p.spiral_e, p.spiral_k * theta);  // seed 003: r = a·e^(kθ)
      const glm::vec3 radial = std::cos(theta) * u + std::sin(theta) * w;
      // The blade points outward and a little forward; its petiole faces the twig.
      const glm::vec3 ly = glm::normalize(radial + 0.5f * dir);
      const glm::vec3 lx = glm::normalize(glm::cross(dir, radial));
      leaf l;
      l.position = base + f * seg + rad * radial;
      l.orientation = glm::normalize(glm::quat_cast(glm::mat3(lx, ly, glm::cross(lx, ly))));
      l.size = r.uniform(smin, smax);
      l.born = t.born[i];
      l.died = t.died[i];   // a cut (pruning) takes the leaves with the branch
      l.node = int32_t(i);
      t.leaves.push_back(l);
    }
  }
}

}  // namespace

std::vector<int32_t> find_influencing_nodes(const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& nodes,
                                            float d_i) {
  colonization_state s;
  init_state(s, points, d_i, -1.0f);
  for (size_t k = 0; k < nodes.size(); ++k) visit_new_node(s, nodes[k], int32_t(k), 0);
  std::vector<int32_t> out(points.size(), -1);
  for (size_t i = 0; i < points.size(); ++i)
    if (s.killed[i] < 0) out[i] = nearest_of(s, int32_t(i));
  return out;
}

glm::vec3 growth_direction(const glm::vec3& pull_sum, const glm::vec3& previous, const glm::vec3& tropism,
                           float weight) {
  // Runions 2007 §3: n̂ = n/|n|. Exactly opposite pulls give n = 0; then keep the previous direction.
  const float len = glm::length(pull_sum);
  const glm::vec3 n = len > 1e-5f ? pull_sum / len : previous;
  const float tl = glm::length(tropism);
  const glm::vec3 g = tl > 1e-12f ? tropism / tl : glm::vec3(0);
  const glm::vec3 d = (1.0f - weight) * n + weight * g;  // tropism blend (Runions 2007, tropisms)
  const float dl = glm::length(d);
  return dl > 1e-5f ? d / dl : n;
}

glm::vec3 limit_turn(const glm::vec3& from, const glm::vec3& to, float max_angle) {
  const float c = std::clamp(glm::dot(from, to), -1.0f, 1.0f);
  if (!(c < std::cos(max_angle))) return to;   // within the limit (or NaN: left alone)
  glm::vec3 side = to - c * from;                 // the turn's direction, across `from`
  const float sl = glm::length(side);
  if (!(sl > 1e-6f)) side = any_perpendicular(from);   // straight back: any side
  else side /= sl;
  return std::cos(max_angle) * from + std::sin(max_angle) * side;
}

// Everything the crown loop reads at the top of step k, after its stop checks and before its
// keyframes and cuts (generators/resume.h). The points are not in it: they are sampled again from
// the unchanged base params and seed. acc, acc_count and stuck are zero at the top of a step.
struct sc_snapshot {
  tree_skeleton t;
  std::vector<uint8_t> has_child;
  std::vector<int32_t> last_count;
  colonization_state s;
  space_colonization_params p;   // the working params, keyframes up to k − 1 applied
  float D = 0;
  int32_t tip = 0;
  grow_report rep;
  std::vector<uint8_t> forked;
  size_t bytes = 0;
};

size_t sc_recorded_bytes(const growth_resume& r) {
  size_t n = 0;
  for (const auto& x : r.space_colonization)
    if (x) n += x->bytes;
  return n;
}

tree_skeleton grow_colonization_from_points(const space_colonization_params& p_in, const std::vector<glm::vec3>& pts,
                                            const grow_options& o, grow_report* report, growth_debug* debug) {
  grow_report local;
  grow_report& rep = report ? *report : local;
  space_colonization_params p = p_in;
  clamp_all_params(p);  // bad input (NaN, out of range) never reaches the loop
  const int steps = std::min(o.steps >= 0 ? o.steps : p.steps, int(never_died) - 1);
  float D = p.segment_length;
  const float d_i = p.influence_radius;
  // Seasons (generators/history.h): crown step k grows segments of Dk = D·exp(a·z_k).
  const std::vector<float> season = season_anomalies(o.seed, steps);
  float Dk = D;

  tree_skeleton t;
  std::vector<uint8_t> has_child;
  std::vector<uint8_t> forked;      // 1: the node's apex forked sympodially (it grows no more)
  std::vector<int32_t> last_count;  // influence count when the node last grew, -1 never
  std::vector<int32_t> acc_count;
  std::vector<glm::vec3> acc;
  auto add = [&](const glm::vec3& pos, int32_t par, int step) {
    uint8_t ord = 0;
    if (par >= 0) {
      ord = uint8_t(std::min(255, t.order[size_t(par)] + (has_child[size_t(par)] ? 1 : 0)));
      has_child[size_t(par)] = 1;
    }
    t.add_node(pos, par, 0.0f, uint16_t(step), ord);
    has_child.push_back(0);
    forked.push_back(0);
    last_count.push_back(-1);
    acc_count.push_back(0);
    acc.push_back(glm::vec3(0));
  };
  std::string stop;
  // Both caps stop growth before the node that would break them.
  auto room = [&]() {
    if (int64_t(t.size()) >= int64_t(p.node_cap)) {
      rep.hit_node_cap = true;
      stop = "node cap";
      return false;
    }
    if (int64_t(t.size()) - 1 >= int64_t(p.max_branches)) {
      stop = "max branches";
      return false;
    }
    return true;
  };

  colonization_state s;
  // Runions 2007 §3 needs d_k < d_i: a point must be able to attract before a node kills it. A
  // larger d_k (its range reaches past d_i's default) is used as 0.9·d_i, and the report says so.
  const float d_k = std::min(p.kill_distance, 0.9f * d_i);
  init_state(s, pts, d_i, d_k);
  add(glm::vec3(0), -1, 0);
  visit_new_node(s, t.position[0], 0, 0);
  float top = -1e30f;  // highest point: above it + d_i the trunk can never reach the cloud
  for (size_t i = 0; i < pts.size(); ++i)
    if (s.killed[i] < 0) top = std::max(top, pts[i].y);

  int step = 0;
  // Trunk: straight up in internodes of exactly D, at least trunk_length (rounded up to whole
  // internodes, so any length works), then on until some point is within d_i of the tree.
  const int trunk_min = int(std::ceil(p.trunk_length / D - 1e-4f));
  int32_t tip = 0;
  // The top of each step: growth phases (new segment length or tropism from this step on), then
  // cuts. A cut gives back the points its branch had killed: the point state is rebuilt from the
  // remaining nodes, so other branches take the freed points (Runions 2007's competition for space).
  // Only those: a point the rest of the tree had dropped unreached (nearest to a stuck node, old
  // wood or a forked apex that survives the cut) stays dropped, so a cut does not hand the rest of
  // the crown its dropped points again.
  auto key_step = [&](int k) {
    if (apply_keyframes(p, o.keyframes, k)) clamp_all_params(p), D = p.segment_length;
    if (apply_cuts(t, o.cuts, k, rep).empty()) return;
    const std::vector<int32_t> was_dropped_by = std::move(s.dropped_by), was_killed = std::move(s.killed);
    s = colonization_state{};
    init_state(s, pts, d_i, d_k);
    for (size_t j = 0; j < t.size(); ++j)
      if (t.died[j] == never_died) visit_new_node(s, t.position[j], int32_t(j), k);
    for (size_t i = 0; i < was_dropped_by.size() && i < s.killed.size(); ++i) {
      const int32_t by = was_dropped_by[i];
      if (by < 0 || s.killed[i] >= 0 || size_t(by) >= t.size() || t.died[size_t(by)] != never_died) continue;
      s.dropped_by[i] = by;
      kill_point(s, int32_t(i), was_killed[i]);
    }
    while (t.died[size_t(tip)] != never_died) tip = t.parent[size_t(tip)];   // a cut trunk regrows from below
  };
  // Resuming (generators/resume.h): the crown loop starts at the recorded step.
  growth_resume* const resume = o.resume;
  std::vector<std::shared_ptr<const sc_snapshot>>* const snaps = resume ? &resume->space_colonization : nullptr;
  bool resumed = false;
  if (resume && resume->from_step >= 1 && resume->from_step <= steps && size_t(resume->from_step) < snaps->size() &&
      (*snaps)[size_t(resume->from_step)]) {
    const sc_snapshot& x = *(*snaps)[size_t(resume->from_step)];
    t = x.t;
    has_child = x.has_child;
    forked = x.forked;
    last_count = x.last_count;
    acc_count.assign(t.size(), 0);
    acc.assign(t.size(), glm::vec3(0));
    s = x.s;
    s.pts = &pts;
    p = x.p;
    D = x.D;
    tip = x.tip;
    rep = x.rep;
    step = resume->from_step - 1;
    resume->resumed_at = resume->from_step;
    resumed = true;
  }
  // What is recorded from here on is replaced; the state resumed from stays (it is this state).
  if (resume && resume->record) snaps->resize(resumed ? size_t(step) + 2 : 1);
  for (int k = 0; stop.empty() && !resumed; ++k) {
    compact_active(s);
    const bool reached = !s.active.empty();
    if (s.alive == 0 && k >= trunk_min) stop = "no attraction points left";
    else if (reached && k >= trunk_min) break;
    else if (s.alive > 0 && !reached && t.position[size_t(tip)].y > top + d_i) {
      // No point can ever come within d_i: say so instead of showing a stump.
      float nearest = 1e30f;
      const float h = t.position[size_t(tip)].y;
      for (size_t i = 0; i < pts.size(); ++i)
        if (s.killed[i] < 0)
          nearest = std::min(nearest, glm::length(pts[i] - glm::vec3(0, std::clamp(pts[i].y, 0.0f, h), 0)));
      stop = "no point within reach";
      rep.error = true;
      rep.message = "no attraction point is within the influence radius dᵢ = " + std::to_string(d_i) +
                    " m of the trunk (the nearest is " + std::to_string(nearest) +
                    " m away); raise influence_radius above that or move the envelope closer";
    } else if (step >= steps) stop = "step limit";
    else if (o.cancelled()) rep.cancelled = true, stop = "cancelled";
    else if (room()) {
      ++step;
      key_step(step);
      add(t.position[size_t(tip)] + glm::vec3(0, D, 0), tip, step);
      tip = int32_t(t.size() - 1);
      visit_new_node(s, t.position[size_t(tip)], tip, step);
      if (o.progress) o.progress(float(step) / float(std::max(steps, 1)));
    }
  }

  // Sympodial forking: the length an apex's axis has grown since its last fork (or the
  // root), walked down at most fork_length / D nodes; and the fork itself, where the apex stops and
  // two shoots fork_angle apart, in a seeded plane through its course, take over, each turned off
  // course by up to `crook` (Hallé, Oldeman & Tomlinson 1978: sympodial growth, the leader's
  // apex ends and laterals continue the axis).
  auto axis_since_fork = [&](int32_t v) {
    float len = 0;
    // Enough nodes to cover fork_length in the shortest segments any season grows.
    const float shortest = p.season_variation > 0 ? D * season_vigour(p.season_variation, -4.0f) : D;
    const int most = int(p.fork_length / shortest) + 2;
    for (int k = 0; k < most && v > 0 && !forked[size_t(t.parent[size_t(v)])]; ++k) {
      len += glm::length(t.position[size_t(v)] - t.position[size_t(t.parent[size_t(v)])]);
      v = t.parent[size_t(v)];
    }
    return len;
  };
  auto fork_apex = [&](int32_t v, const glm::vec3& dir, int k) {
    rng r(o.seed * 0x9E3779B97F4A7C15ull ^ (uint64_t(v) * 0xD1B54A32D192ED03ull + 0x666f726bull));
    const glm::vec3 side = rotate_by(any_perpendicular(dir), dir * r.uniform(0.0f, 6.2831853f));
    const float half = 0.5f * glm::radians(p.fork_angle), crook = glm::radians(p.crook);
    forked[size_t(v)] = 1;
    for (float sgn : {1.0f, -1.0f}) {
      if (!room()) return;
      // An unequal fork: the first shoot (which keeps the axis' order) turns less, the second more.
      const float turn = p.fork_asymmetry > 0 ? half * (1.0f - sgn * p.fork_asymmetry) : half;
      glm::vec3 d = rotate_by(dir, side * (sgn * turn));
      if (crook > 0) {
        const glm::vec3 across = rotate_by(any_perpendicular(d), d * r.uniform(0.0f, 6.2831853f));
        d = rotate_by(d, across * (crook * r.uniform(-1.0f, 1.0f)));
      }
      add(t.position[size_t(v)] + Dk * glm::normalize(d), v, k);
    }
  };

  // Leader damage (frost, browsing, insects): an apex dies in a step with probability leader_damage,
  // seeded by node and step, and the buds below it take over as a fork (reiteration: Hallé,
  // Oldeman & Tomlinson 1978). No draw at all while it is 0.
  auto damaged = [&](int32_t v, int k) {
    if (!(p.leader_damage > 0)) return false;
    rng r(o.seed * 0xA24BAED4963EE407ull ^ (uint64_t(v) * 0x9FB21C651E98DF25ull + uint64_t(k)));
    return r.uniform() < p.leader_damage;
  };

  // Crown: Runions 2007 §3, one iteration per growth step.
  std::vector<int32_t> touched;
  std::vector<uint8_t> stuck;
  chunked_results<int32_t> found;   // visit_new_nodes' scratch
  const glm::vec3 up(0, 1, 0);
  const glm::vec3 open = open_side_direction(p.open_side);
  while (stop.empty()) {
    compact_active(s);
    if (s.alive == 0) { stop = "no attraction points left"; break; }
    if (s.active.empty()) { stop = "no node influenced"; break; }
    if (step >= steps) { stop = "step limit"; break; }
    if (o.cancelled()) { rep.cancelled = true; stop = "cancelled"; break; }
    if (resume && resume->record && !(resumed && step + 1 == resume->resumed_at)) {
      const int k = step + 1;
      const std::vector<int>& only = resume->record_steps;
      snaps->resize(size_t(k) + 1);
      if (only.empty() || std::find(only.begin(), only.end(), k) != only.end()) {
        // Bounded as the self-organizing snapshots are (growth_resume::byte_cap).
        const size_t bytes = sizeof(sc_snapshot) + vec_bytes(t.position) + vec_bytes(t.parent) + vec_bytes(t.radius) +
                             vec_bytes(t.born) + vec_bytes(t.died) + vec_bytes(t.order) + vec_bytes(has_child) + vec_bytes(forked) +
                             vec_bytes(last_count) + vec_bytes(s.cell_begin) +
                             vec_bytes(s.slots) + vec_bytes(s.slot_of) + vec_bytes(s.slot_pos) +
                             vec_bytes(s.nearest) + vec_bytes(s.nearest_d2) + vec_bytes(s.killed) + vec_bytes(s.active);
        if (recorded_bytes(*resume) + bytes <= resume->byte_cap)
          (*snaps)[size_t(k)] = std::make_shared<const sc_snapshot>(sc_snapshot{t, has_child, last_count, s, p, D, tip, rep, forked, bytes});
        else
          ++resume->skipped;
      }
    }
    ++step;
    key_step(step);
    Dk = D * season_vigour(p.season_variation, season[size_t(step)]);
    if (debug) debug->lines.clear(), debug->line_color.clear(), debug->line_kind.clear();
    touched.clear();
    for (int32_t i : s.active) {
      const int32_t v = nearest_of(s, i);
      if (acc_count[size_t(v)]++ == 0) touched.push_back(v);
      // Runions 2007 §3: n = Σ (s − v)/|s − v| over the points S(v) that v is nearest to.
      acc[size_t(v)] += (pts[size_t(i)] - t.position[size_t(v)]) / std::sqrt(nearest_d2_of(s, i));
      if (debug)
        debug->add_line(pts[size_t(i)], t.position[size_t(v)], glm::vec3(1.0f, 0.75f, 0.2f), debug_kind::influence_link);
    }
    std::sort(touched.begin(), touched.end());  // new nodes in parent order: deterministic
    const size_t first_new = t.size();
    bool any_stuck = false;
    stuck.resize(t.size(), 0);
    for (int32_t v : touched) {
      // S(v) only shrinks after v's birth, so an unchanged count means the same points: v would
      // grow a second node onto the first. Those points cannot be reached; they are removed below.
      if (acc_count[size_t(v)] == last_count[size_t(v)]) {
        stuck[size_t(v)] = 1;
        any_stuck = true;
        continue;
      }
      // Apical control: a forked apex grows no more, and old wood sprouts no laterals; the points
      // only they are nearest to are dropped like a stuck node's (other nodes may take them first).
      const bool apex = !has_child[size_t(v)];
      if (forked[size_t(v)] || (!apex && p.bud_life > 0 && step - int(t.born[size_t(v)]) > p.bud_life)) {
        stuck[size_t(v)] = 1;
        any_stuck = true;
        continue;
      }
      if (!stop.empty() || !room()) continue;
      const int32_t par = t.parent[size_t(v)];
      const glm::vec3 prev = par >= 0 ? glm::normalize(t.position[size_t(v)] - t.position[size_t(par)]) : up;
      // Pendulous twigs: the new segment's order (a lateral one past its parent's) sets its tropism.
      float w = p.tropism_weight;
      if (p.twig_droop > 0) {
        const int ord = int(t.order[size_t(v)]) + (apex ? 0 : 1);
        if (ord >= 2) w = std::min(w + p.twig_droop * float(std::min(ord - 1, 3)) / 3.0f, 0.95f);
      }
      glm::vec3 dir = growth_direction(acc[size_t(v)], prev, p.tropism, w);
      dir = lean_to_sky(dir, p.sky_lean, open);   // phototropism towards the open side (Loehle 1986)
      // An apex continuing its axis turns at most max_turn off its last segment: turned further,
      // it is turned back towards the segment in the plane of the two (a shoot that keeps chasing
      // points beside it would otherwise curl round into a loop). Laterals branch off freely.
      if (apex && par >= 0 && p.max_turn < 180.0f) dir = limit_turn(prev, dir, glm::radians(std::max(p.max_turn, 1.0f)));
      last_count[size_t(v)] = acc_count[size_t(v)];
      if (apex && ((p.fork_length > 0 && axis_since_fork(v) + Dk >= p.fork_length) || damaged(v, step))) {
        fork_apex(v, dir, step);
        continue;
      }
      add(t.position[size_t(v)] + Dk * dir, v, step);  // Runions 2007 §3: v' = v + D·n̂
    }
    if (any_stuck)
      for (int32_t i : s.active)
        if (s.killed[size_t(i)] < 0 && stuck[size_t(nearest_of(s, i))]) {
          s.dropped_by[size_t(i)] = nearest_of(s, i);
          kill_point(s, i, step);
        }
    for (int32_t v : touched) acc[size_t(v)] = glm::vec3(0), acc_count[size_t(v)] = 0, stuck[size_t(v)] = 0;
    visit_new_nodes(s, t, first_new, step, o, found);
    if (o.progress) o.progress(float(step) / float(std::max(steps, 1)));
  }
  t.steps = step;
  rep.stop_reason = stop;
  rep.stop = rep.hit_node_cap ? grow_stop::node_cap : rep.cancelled ? grow_stop::cancelled : grow_stop::finished;
  if (rep.hit_node_cap)
    rep.message = "node cap reached (" + std::to_string(p.node_cap) + " nodes) at step " + std::to_string(step) +
                  "; raise node_cap or lower the point count";
  else if (pts.empty())
    rep.message = "no attraction points: only the trunk grew; raise the point count N";
  else if (!rep.error && p.kill_distance > d_k) {
    char used[32];
    std::snprintf(used, sizeof used, "%.3g", double(d_k));
    rep.message = "kill distance dₖ ≥ influence radius dᵢ: points would die before they could attract, so dₖ = 0.9·dᵢ = " +
                  std::string(used) + " m was used; lower dₖ below dᵢ";
  }

  // Lower limbs shaded out by the crown above die and leave stubs (generators/history.h).
  if (!self_prune(t, p.live_crown, p.stub_length).empty()) {
    has_child.assign(t.size(), 0);
    for (size_t i = 1; i < t.size(); ++i)
      if (t.parent[i] >= 0) has_child[size_t(t.parent[i])] = 1;
  }

  // Widths: pipe model r^n = Σ rᵢ^n, tips at W (seed 003's Da Vinci rule; Shinozaki 1964), capped at
  // max_width·W. While the cap does not bind, the radii stay time-varying pipe radii
  // (radii_at_step thickens the trunk as the tree grows); when it binds the capped final radii are
  // stored (pipe_exponent = 0), since radii_at_step cannot apply the cap.
  compute_pipe_radii(t.parent, t.born, t.died, t.steps, p.pipe_exponent, p.min_width, t.radius, &t.position,
                     p.pipe_taper);
  thicken_stubs(t, t.steps, p.pipe_exponent, p.min_width, t.radius);   // stubs keep their girth (history.h)
  const float rmax = p.max_width * p.min_width;
  bool capped = false;
  for (float& r : t.radius)
    if (r > rmax) r = rmax, capped = true;
  if (!capped) t.pipe_exponent = p.pipe_exponent, t.pipe_tip_radius = p.min_width, t.pipe_taper = p.pipe_taper;

  place_spiral_leaves(t, has_child, p, o.seed);

  if (debug) {
    debug->points = pts;
    debug->point_value.resize(pts.size());
    for (size_t i = 0; i < pts.size(); ++i) debug->point_value[i] = float(s.killed[i]);
    debug->point_kind.assign(pts.size(), debug_kind::marker);
  }
  return t;
}

tree_skeleton grow_space_colonization(const space_colonization_params& p_in, const grow_options& o,
                                      grow_report* report, growth_debug* debug) {
  space_colonization_params p = p_in;
  clamp_all_params(p);
  grow_report local;
  grow_report& rep = report ? *report : local;
  envelope_sample e = sample_envelope(p, o.seed, debug != nullptr);
  if (e.points.empty() && !e.error.empty()) {
    tree_skeleton t;
    t.add_node(glm::vec3(0), -1, p.min_width, 0, 0);
    rep.error = true;
    rep.message = e.error;
    rep.stop = grow_stop::bad_input;
    rep.stop_reason = "envelope error";
    return t;
  }
  tree_skeleton t = grow_colonization_from_points(p, e.points, o, &rep, debug);
  if (!e.error.empty() && rep.message.empty()) rep.message = e.error;
  if (debug) {
    debug->lines.insert(debug->lines.end(), e.outline.begin(), e.outline.end());
    debug->line_color.insert(debug->line_color.end(), e.outline.size() / 2, glm::vec3(0.35f, 0.6f, 1.0f));
    debug->line_kind.insert(debug->line_kind.end(), e.outline.size() / 2, debug_kind::envelope_edge);
  }
  return t;
}

}  // namespace sylva
