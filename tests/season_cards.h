// Small trees for the season tests (CPU and GL): a grid of leaf cards of one archetype, and render
// settings in a season.
#pragma once

#include <algorithm>
#include <cstdint>

#include "render/mesh/mesh.h"
#include "render/mesh/render_params.h"

namespace sylva_test {

// A grid of n x n leaf cards of one archetype facing +Z, spread over [-1, 1] x [0, 2]; leaves are
// born at step i % 3 so that the mesh has a scrub table.
inline sylva::tree_mesh card_grid(uint8_t archetype, int n = 6) {
  sylva::tree_mesh m;
  for (int born = 0; born < 3; ++born)
    for (int k = 0; k < n * n; ++k) {
      if (k % 3 != born) continue;
      sylva::leaf_instance l{};
      l.position = glm::vec3(-1 + (k % n + 0.5f) * 2.0f / n, (k / n) * 2.0f / n, 0);
      l.orientation = glm::vec4(0, 0, 0, 1);
      l.size = 1.8f / n;
      l.born = uint16_t(born);
      l.died = 0xffff;
      l.texture = archetype;
      m.leaves.push_back(l);
    }
  for (int s = 0; s < 3; ++s)
    m.leaf_end.push_back(uint32_t(
        std::count_if(m.leaves.begin(), m.leaves.end(), [&](const sylva::leaf_instance& l) { return l.born <= s; })));
  m.index_end = {0, 0, 0};
  m.steps = 2;
  m.bounds_min = glm::vec3(-1, 0, -0.1f);
  m.bounds_max = glm::vec3(1, 2, 0.1f);
  return m;
}

inline sylva::render_params with_season(sylva::leaf_season s) {
  sylva::render_params rp;
  rp.season = s;
  return rp;
}

}  // namespace sylva_test
