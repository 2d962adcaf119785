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
  auto carries_leaves = [&](size_t i) {
    return t.parent[i] >= 0 && t.order[i] >= p.min_order && std::min(t.died[i], first_child[i]) > t.born[i];
  };
  // Reserve once: a tree of 20,000 nodes otherwise regrows this vector a dozen times.
  size_t tips = 0;
  for (size_t i = 0; i < n; ++i) tips += carries_leaves(i);
  std::vector<leaf> out;
  out.reserve(tips * (p.density > 0 ? size_t(std::min(p.density, 64.0f)) + 1 : 1));
  rng r(seed ^ 0x1eafull);
  const float spread = glm::radians(p.spread);
  const glm::quat tilt = glm::angleAxis(spread, glm::vec3(1, 0, 0));   // the same for every leaf
  for (size_t i = 0; i < n; ++i) {
    if (!carries_leaves(i)) continue;
    const uint16_t died = std::min(t.died[i], first_child[i]);
    glm::vec3 dir = t.position[i] - t.position[t.parent[i]];
    const float len = glm::length(dir);
    dir = len > 1e-12f ? dir / len : glm::vec3(0, 1, 0);
    int count = int(p.density);
    if (r.uniform() < p.density - float(count)) ++count;
    const glm::quat along = glm::rotation(glm::vec3(0, 1, 0), dir);   // per node, not per leaf
    for (int k = 0; k < count; ++k) {
      // Phyllotaxis: successive leaves 137.5° apart around the twig, tilted away by `spread`.
      const float az = glm::radians(137.5f) * float(k) + r.uniform(0, 0.5f);
      glm::quat q = along * glm::angleAxis(az, glm::vec3(0, 1, 0)) * tilt;
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
