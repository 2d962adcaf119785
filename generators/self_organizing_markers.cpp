// The self-organizing model's space-colonization environment (self_organizing_markers.h).
#include "generators/self_organizing_markers.h"

#include <atomic>
#include <bit>
#include <cmath>

#include "generators/job_pool.h"

namespace sylva {

void fill_marker_envelopes(marker_state& m, const std::vector<glm::vec3>& roots_at, const self_organizing_params& p, rng& r,
                           std::string& message) {
  const float bottom = std::min(p.envelope_bottom, p.envelope_top), top = std::max(p.envelope_bottom, p.envelope_top);
  const glm::vec3 radii(p.envelope_radius, 0.5f * (top - bottom), p.envelope_radius);
  // Memory cap (memory_bound.h): at most so_marker_cap markers in all, shared by the trees.
  int per_tree = p.marker_count;
  if (int64_t(per_tree) * int64_t(roots_at.size()) > so_marker_cap) {
    per_tree = int(so_marker_cap / int64_t(roots_at.size()));
    message = "markers capped at " + std::to_string(so_marker_cap) + " in all: " + std::to_string(per_tree) +
              " per tree instead of " + std::to_string(p.marker_count);
  }
  m.pos.reserve(size_t(per_tree) * roots_at.size());
  for (const glm::vec3& at : roots_at) {
    const glm::vec3 centre = at + glm::vec3(0, 0.5f * (top + bottom), 0);
    for (int k = 0; k < per_tree; ++k) {
      glm::vec3 u;
      do u = glm::vec3(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1));
      while (glm::dot(u, u) > 1);
      m.pos.push_back(centre + u * radii);
    }
  }
}

void perceive_markers(marker_state& m, size_t buds, const std::function<void(size_t, glm::vec3&, glm::vec3&)>& bud_at,
                      float reach, float cos_theta, marker_scratch& scratch,
                      const std::function<void(size_t, uint32_t)>& perceived) {
  const size_t grain = std::max<size_t>(64, buds / 32 + 1), chunks = (buds + grain - 1) / grain;
  if (scratch.seen.size() < chunks) scratch.seen.resize(chunks);
  parallel_jobs(chunks, [&](size_t c) {
    std::vector<uint32_t>& seen = scratch.seen[c];
    seen.clear();
    for (size_t j = c * grain; j < std::min(buds, (c + 1) * grain); ++j) {
      glm::vec3 pos, def;
      bud_at(j, pos, def);
      m.visit_near(pos, reach, [&](uint32_t k, const glm::vec3& dv) {
        const float d2 = glm::dot(dv, dv);   // ≥ +0, so its bits order as the values do
        if (glm::dot(dv, def) < cos_theta * std::sqrt(d2)) return;
        seen.push_back(k);
        const uint64_t key = (uint64_t(std::bit_cast<uint32_t>(d2)) << 32) | uint64_t(j);
        std::atomic_ref<uint64_t> best(m.best[k]);
        for (uint64_t now = best.load(std::memory_order_relaxed);
             key < now && !best.compare_exchange_weak(now, key, std::memory_order_relaxed);) {
        }
      });
    }
  });
  for (size_t c = 0; c < chunks; ++c)
    for (uint32_t k : scratch.seen[c]) {
      if (m.best[k] == marker_state::no_bud) continue;   // met before: reported there
      perceived(size_t(uint32_t(m.best[k])), k);
      m.best[k] = marker_state::no_bud;
    }
}

}  // namespace sylva
