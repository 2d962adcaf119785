// Picking a branch: the first bark tube a ray meets, among the nodes alive at a step.
#include <gtest/gtest.h>

#include "render/mesh/pick.h"

using namespace sylva;

namespace {

// A trunk of two internodes and one lateral: 0 (root) → 1 (0,1,0) → 2 (0,2,0); 1 → 3 (1,1,0).
tree_skeleton tiny() {
  tree_skeleton t;
  t.add_node({0, 0, 0}, -1, 0.1f, 0, 0);
  t.add_node({0, 1, 0}, 0, 0.1f, 1, 0);
  t.add_node({0, 2, 0}, 1, 0.1f, 2, 0);
  t.add_node({1, 1, 0}, 1, 0.05f, 2, 1);
  t.steps = 2;
  return t;
}

}  // namespace

TEST(Pick, RayFindsTheTubeItMeetsFirst) {
  const tree_skeleton t = tiny();
  const std::vector<float> r = t.radius;
  // Straight at the upper trunk internode from +z: enters its tube 0.1 m before the axis.
  pick_hit h = pick_branch(t, r, 2, {0, 1.5f, 5}, {0, 0, -1});
  EXPECT_EQ(h.node, 2);
  EXPECT_NEAR(h.distance, 4.9f, 1e-4f);
  // The lateral, from above, at x = 0.6: its capsule has the larger of its two radii (0.1 at node 1).
  h = pick_branch(t, r, 2, {0.6f, 5, 0}, {0, -2, 0});
  EXPECT_EQ(h.node, 3);
  EXPECT_NEAR(h.distance, 4 - 0.1f, 1e-4f);
  // Along the lateral's line from +x: the lateral is met before the trunk behind it.
  h = pick_branch(t, r, 2, {5, 1, 0}, {-1, 0, 0});
  EXPECT_EQ(h.node, 3);
  // Beside everything: no hit; with slack the thin lateral is caught.
  EXPECT_EQ(pick_branch(t, r, 2, {0.6f, 5, 0.2f}, {0, -1, 0}).node, -1);
  EXPECT_EQ(pick_branch(t, r, 2, {0.6f, 5, 0.2f}, {0, -1, 0}, 0.05f).node, 3);   // 0.1 + 0.05·4 > 0.2
  // Behind the ray's origin nothing counts.
  EXPECT_EQ(pick_branch(t, r, 2, {0, 1.5f, -5}, {0, 0, -1}).node, -1);
}

TEST(Pick, OnlyNodesAliveAtTheStepCount) {
  tree_skeleton t = tiny();
  const std::vector<float> r = t.radius;
  EXPECT_EQ(pick_branch(t, r, 1, {0, 1.5f, 5}, {0, 0, -1}).node, -1);   // node 2 is born at step 2
  t.died[2] = 2;
  EXPECT_EQ(pick_branch(t, r, 2, {0, 1.5f, 5}, {0, 0, -1}).node, -1);   // and here shed at step 2
  EXPECT_EQ(pick_branch(t, r, 2, {0, 0.5f, 5}, {0, 0, -1}).node, 1);
  EXPECT_EQ(pick_branch(t, r, 2, {0, 0.5f, 5}, {0, 0, 0}).node, -1);    // a zero direction picks nothing
}
