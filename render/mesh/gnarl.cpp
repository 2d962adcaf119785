// Gnarl: the wood's random turns per internode, and where they move the nodes and what hangs on
// them (declared in mesh.h).
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "generators/vec_util.h"
#include "render/mesh/mesh.h"
#include "render/mesh/position_hash.h"

namespace sylva {

// Gnarl: each internode turns about a random axis across it by up to `gnarl` degrees, scaled by
// its age (0 for this step's shoots, 1 for the seedling's wood) and by its order (1 + order/2, at
// most 2.5: side branches wander more than the trunk). Zero vectors when gnarl is 0.
std::vector<glm::vec3> gnarl_rotations(const tree_skeleton& t, const mesh_params& p) {
  const size_t n = t.size();
  std::vector<glm::vec3> rot(n, glm::vec3(0));
  const float g = std::isfinite(p.gnarl) ? glm::radians(std::clamp(p.gnarl, 0.0f, 90.0f)) : 0.0f;
  if (!(g > 0) || t.parent.size() != n || t.born.size() != n || t.order.size() != n) return rot;
  const float steps = float(std::max(t.steps, 1));
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    if (par < 0 || size_t(par) >= n) continue;
    const glm::vec3 d = t.position[i] - t.position[par];
    const float len = glm::length(d);
    const float age = std::clamp(float(t.steps - int(t.born[i])) / steps, 0.0f, 1.0f);
    const float scale = age * std::min(1.0f + 0.5f * float(t.order[i]), 2.5f);
    if (!(len > 1e-9f) || !std::isfinite(len) || scale <= 0) continue;
    rng r(position_hash(t.position[i], 0x676e61726cull));
    const float angle = g * scale * r.uniform(-1.0f, 1.0f), phi = r.uniform(0.0f, 6.2831853f);
    const glm::vec3 a = any_perpendicular(d / len), b = glm::cross(d / len, a);
    rot[i] = (a * std::cos(phi) + b * std::sin(phi)) * angle;
  }
  return rot;
}

std::vector<rotation_terms> gnarl_turns(const std::vector<glm::vec3>& rot) {
  std::vector<rotation_terms> turn(rot.size());
  for (size_t i = 0; i < rot.size(); ++i) turn[i] = rotation_terms_of(rot[i]);
  return turn;
}

// Where gnarl moves each node: its internode turned, its parent's offset carried down the tree.
std::vector<glm::vec3> gnarl_offsets(const tree_skeleton& t, const std::vector<rotation_terms>& turn) {
  std::vector<glm::vec3> disp(t.size(), glm::vec3(0));
  for (size_t i = 0; i < t.size() && i < turn.size(); ++i) {
    const int32_t par = t.parent[i];
    if (par < 0) continue;
    const glm::vec3 d = t.position[i] - t.position[par];
    disp[i] = disp[par] + rotate_by(d, turn[i]) - d;
  }
  return disp;
}

// A point hung on node k (a leaf) moves with k's internode: turned about the parent like it.
glm::vec3 gnarled_point(const tree_skeleton& t, const std::vector<rotation_terms>& turn, const std::vector<glm::vec3>& disp,
                        size_t k, const glm::vec3& at) {
  const int32_t par = t.parent[k];
  if (par < 0) return at + disp[k];
  const glm::vec3 d = at - t.position[par];
  return t.position[par] + disp[par] + rotate_by(d, turn[k]);
}

}  // namespace sylva
