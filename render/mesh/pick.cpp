// Picking a branch under the mouse: ray against capsules, nearest hit.
#include "render/mesh/pick.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace sylva {

pick_hit pick_branch(const tree_skeleton& t, const std::vector<float>& radii, int step, const glm::vec3& origin,
                     const glm::vec3& dir_in, float slack) {
  pick_hit best;
  const float len = glm::length(dir_in);
  if (!(len > 0) || !std::isfinite(len)) return best;
  const glm::vec3 u = dir_in / len;
  best.distance = INFINITY;
  for (size_t i = 0; i < t.size(); ++i) {
    const int32_t par = t.parent[i];
    if (par < 0 || !t.alive(i, step)) continue;
    // Closest approach of the ray o + s·u (s ≥ 0) and the segment a + τ·v (τ ∈ [0, 1]).
    const glm::vec3 a = t.position[size_t(par)], v = t.position[i] - a, w = origin - a;
    const float b = glm::dot(u, v), c = glm::dot(v, v), d = glm::dot(u, w), e = glm::dot(v, w);
    const float den = c - b * b;   // |u| = 1
    // Parallel: the segment's end nearer along the ray (where the ray enters the tube).
    float tau = den > 1e-12f * c ? std::clamp((e - b * d) / den, 0.0f, 1.0f) : b > 0 ? 0.0f : 1.0f;
    float s = std::max(glm::dot(a + tau * v - origin, u), 0.0f);
    if (c > 0 && den > 1e-12f * c) {   // refine once where the clamp moved tau
      tau = std::clamp(glm::dot(origin + s * u - a, v) / c, 0.0f, 1.0f);
      s = std::max(glm::dot(a + tau * v - origin, u), 0.0f);
    }
    const glm::vec3 gap = origin + s * u - (a + tau * v);
    const float r = std::max(i < radii.size() ? radii[i] : 0.0f, size_t(par) < radii.size() ? radii[size_t(par)] : 0.0f) +
                    slack * s;
    if (glm::dot(gap, gap) > r * r) continue;
    // The entry into the tube lies before the closest approach by about the half chord.
    const float entry = s - std::sqrt(std::max(r * r - glm::dot(gap, gap), 0.0f));
    if (entry < best.distance) best = {int32_t(i), entry};
  }
  if (best.node < 0) best.distance = 0;
  return best;
}

}  // namespace sylva
