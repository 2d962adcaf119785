// The perception cone of the self-organizing generator's shadow environment.
#include "generators/self_organizing_cone.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace sylva {

perception_cone make_perception_cone(float perception_distance, float voxel_size, float voxel_metres) {
  perception_cone c;
  const float rv = perception_distance / voxel_size + 0.87f;
  const int R = int(std::ceil(rv));
  for (int z = -R; z <= R; ++z)
    for (int y = -R; y <= R; ++y)
      for (int x = -R; x <= R; ++x)
        if (float(x * x + y * y + z * z) <= rv * rv) {
          c.offset.push_back({x, y, z});
          c.metres.push_back(glm::vec3(x, y, z) * voxel_metres);
          c.x.push_back(c.metres.back().x);
          c.y.push_back(c.metres.back().y);
          c.z.push_back(c.metres.back().z);
        }
  c.radius = R;
  return c;
}

// Palubicki 2009 §4.2: the direction to the least-shadowed voxel in the perception cone.
void scan_cone(const shadow_grid& grid, const perception_cone& cone, float cos_theta, float reach, const glm::vec3& pos,
               const glm::ivec3& v0, const glm::vec3& def, cone_scratch& sc, std::vector<cone_choice>& choices) {
  std::vector<uint8_t>& in_cone = sc.in_cone;
  std::vector<const float*>& near_chunks = sc.near_chunks;
  // The few chunks around the bud, looked up once rather than once per voxel.
  const glm::ivec3 c0 = (v0 - cone.radius) >> shadow_grid::chunk_bits;
  const glm::ivec3 c1 = (v0 + cone.radius) >> shadow_grid::chunk_bits;
  const glm::ivec3 cn = c1 - c0 + 1;
  near_chunks.resize(size_t(cn.x * cn.y * cn.z));
  for (int z = 0; z < cn.z; ++z)
    for (int y = 0; y < cn.y; ++y)
      for (int x = 0; x < cn.x; ++x) near_chunks[(z * cn.y + y) * cn.x + x] = shadow_chunk(grid, c0 + glm::ivec3(x, y, z));
  const glm::vec3 base = voxel_centre(grid, v0) - pos;
  const float reach2 = reach * reach, cos2 = cos_theta * cos_theta;
  float best_s = 0, best_dot = -2;
  int ties = 0;
  // Pass 1, branch-free so that it vectorises: most offsets lie outside the cone, and testing them
  // one by one was a quarter of a default tree's growth. Same operations in the same order as
  // glm::dot, so the same verdicts, NaN included (each test is the negation of a rejection).
  const size_t n = cone.offset.size();
  in_cone.resize(n);
  if (cos_theta >= 0) {
    const float bx = base.x, by = base.y, bz = base.z, ex = def.x, ey = def.y, ez = def.z;
    const float* ox = cone.x.data();
    const float* oy = cone.y.data();
    const float* oz = cone.z.data();
    uint8_t* pass = in_cone.data();
    for (size_t k = 0; k < n; ++k) {
      const float dx = bx + ox[k], dy = by + oy[k], dz = bz + oz[k];
      const float c = dx * ex + dy * ey + dz * ez, len2 = dx * dx + dy * dy + dz * dz;
      pass[k] = uint8_t(!(c <= 0) & !(len2 > reach2) & !(len2 < 1e-12f) & !(c * c < cos2 * len2));
    }
  } else {
    for (size_t k = 0; k < n; ++k) {
      const glm::vec3 d = base + cone.metres[k];
      const float c = glm::dot(d, def), len2 = glm::dot(d, d);
      in_cone[k] = !(len2 > reach2 || len2 < 1e-12f) && !(c < cos_theta * std::sqrt(len2));
    }
  }
  for (size_t k = 0; k < n; ++k) {
    if (!in_cone[k]) continue;
    const glm::vec3 d = base + cone.metres[k];
    const float c = glm::dot(d, def), len2 = glm::dot(d, d);
    const glm::ivec3 v = v0 + cone.offset[k];
    const glm::ivec3 cc = (v >> shadow_grid::chunk_bits) - c0;
    const float* chunk = near_chunks[(cc.z * cn.y + cc.y) * cn.x + cc.x];
    const float s = chunk ? chunk[shadow_cell(v)] : 0.0f;
    constexpr float eps = 1e-6f;
    if (ties > 0 && s > best_s + eps) continue;
    const float len = std::sqrt(len2);
    const float cd = c / len;
    if (ties == 0 || s < best_s - eps) {
      best_s = s, best_dot = cd, ties = 1;
      choices.push_back({1, d / len});
    } else if (cd > best_dot + eps) {
      best_dot = cd, ties = 1;
      choices.push_back({1, d / len});
    } else if (cd >= best_dot - eps) {
      ++ties;
      choices.push_back({ties, d / len});
    }
  }
}

void scan_cones(const shadow_grid& grid, const perception_cone& cone, float cos_theta, float reach, size_t count,
                const std::function<void(size_t, glm::vec3&, glm::ivec3&, glm::vec3&)>& cone_of, cone_scans& out) {
  const size_t grain = std::max<size_t>(16, count / 64 + 1);
  out.scratch.resize(std::max(out.scratch.size(), (count + grain - 1) / grain));
  out.choices.fill(count, grain, [&](size_t c, size_t j, std::vector<cone_choice>& list, size_t n) {
    glm::vec3 pos, def;
    glm::ivec3 voxel;
    cone_of(j, pos, voxel, def);
    list.resize(n);   // (shorter: the chunk's earlier steps left more)
    scan_cone(grid, cone, cos_theta, reach, pos, voxel, def, out.scratch[c], list);
    return list.size();
  });
}

glm::vec3 pick_optimal(rng& r, const cone_choice* c, size_t count, const glm::vec3& def) {
  glm::vec3 best = def;
  for (size_t k = 0; k < count; ++k)
    if (c[k].ties == 1 || r.uniform_int(c[k].ties) == 0) best = c[k].dir;
  return best;
}

}  // namespace sylva
