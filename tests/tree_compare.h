// Comparing two skeletons as they stood at a step (growth phases and pruning tests).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <type_traits>

#include "generators/tree_spec.h"

namespace sylva {

// Small trees of each generator, each grown in a fraction of a second.
inline tree_spec small_spec(int generator, bool markers = false) {
  tree_spec s;
  s.seed = 7;
  s.params = default_params(generator);
  std::visit(
      [&](auto& p) {
        using P = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<P, self_organizing_params>) {
          p.steps = 10;
          if (markers) {
            p.environment = so_environment::markers;
            p.marker_count = 3000, p.envelope_radius = 0.5f, p.envelope_top = 2;
          }
        } else if constexpr (std::is_same_v<P, space_colonization_params>) {
          p.points = 1500;
          p.steps = 40;
        } else if constexpr (std::is_same_v<P, guiding_vectors_params>) {
          p.steps = 4;
        } else {
          p.derivations = 8;
        }
      },
      s.params);
  return s;
}

// The tree as it stood at `step`: the same nodes (node order follows the steps in every generator),
// positions, parents, orders, births and, for the deaths, whether a node was still alive.
inline void expect_same_up_to(const tree_skeleton& a, const tree_skeleton& b, int step, const std::string& what) {
  auto count = [&](const tree_skeleton& t) {
    size_t n = 0;
    while (n < t.size() && t.born[n] <= step) ++n;
    for (size_t i = n; i < t.size(); ++i) EXPECT_GT(t.born[i], step) << what << ": births out of step order";
    return n;
  };
  const size_t n = count(a);
  ASSERT_EQ(n, count(b)) << what;
  for (size_t i = 0; i < n; ++i) {
    ASSERT_EQ(std::memcmp(&a.position[i], &b.position[i], sizeof(glm::vec3)), 0) << what << " node " << i;
    ASSERT_EQ(a.parent[i], b.parent[i]) << what << " node " << i;
    ASSERT_EQ(a.order[i], b.order[i]) << what << " node " << i;
    ASSERT_EQ(a.born[i], b.born[i]) << what << " node " << i;
    ASSERT_EQ(std::min<int>(a.died[i], step + 1), std::min<int>(b.died[i], step + 1)) << what << " node " << i;
  }
  if (a.pipe_exponent > 0 && a.pipe_exponent == b.pipe_exponent) {
    const std::vector<float> ra = radii_at_step(a, step), rb = radii_at_step(b, step);
    for (size_t i = 0; i < n; ++i) ASSERT_EQ(ra[i], rb[i]) << what << " radius of node " << i;
  }
}

inline bool same_tree(const tree_skeleton& a, const tree_skeleton& b) {
  return a.position == b.position && a.parent == b.parent && a.born == b.born && a.died == b.died &&
         a.radius == b.radius;
}

}  // namespace sylva
