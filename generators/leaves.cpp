// Shared leaf placement on the tips of a skeleton.
#include "generators/leaves.h"

#include <cmath>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/quaternion.hpp>

namespace sylva {

std::vector<leaf> place_tip_leaves(const tree_skeleton& t, const leaf_params& p, uint64_t seed) {
  const size_t n = t.size();
  // A node stops being a tip when its first child appears.
  std::vector<uint16_t> first_child(n, never_died);
  for (size_t i = 0; i < n; ++i)
    if (t.parent[i] >= 0) first_child[t.parent[i]] = std::min(first_child[t.parent[i]], t.born[i]);
  std::vector<leaf> out;
  rng r(seed ^ 0x1eafull);
  const float spread = glm::radians(p.spread);
  for (size_t i = 0; i < n; ++i) {
    if (t.parent[i] < 0 || t.order[i] < p.min_order) continue;
    const uint16_t died = std::min(t.died[i], first_child[i]);
    if (died <= t.born[i]) continue;
    glm::vec3 dir = t.position[i] - t.position[t.parent[i]];
    const float len = glm::length(dir);
    dir = len > 1e-12f ? dir / len : glm::vec3(0, 1, 0);
    int count = int(p.density);
    if (r.uniform() < p.density - float(count)) ++count;
    for (int k = 0; k < count; ++k) {
      // Phyllotaxis: successive leaves 137.5° apart around the twig, tilted away by `spread`.
      const float az = glm::radians(137.5f) * float(k) + r.uniform(0, 0.5f);
      glm::quat along = glm::rotation(glm::vec3(0, 1, 0), dir);
      glm::quat q = along * glm::angleAxis(az, glm::vec3(0, 1, 0)) * glm::angleAxis(spread, glm::vec3(1, 0, 0));
      leaf l;
      l.position = t.position[i] - dir * (len * 0.4f * float(k) / float(std::max(count, 1)));
      l.orientation = glm::normalize(q);
      l.size = p.size * (1 + p.size_jitter * r.uniform(-1, 1));
      l.born = t.born[i];
      l.died = died;
      l.node = int32_t(i);
      out.push_back(l);
    }
  }
  return out;
}

}  // namespace sylva
