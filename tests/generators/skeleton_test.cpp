// Skeleton invariants and pipe-model radii.
#include <gtest/gtest.h>

#include "generators/skeleton.h"

using namespace sylva;

TEST(Skeleton, PipeModelHoldsAtBranchPoint) {
  tree_skeleton t;
  t.add_node({0, 0, 0}, -1, 0, 0, 0);
  t.add_node({0, 1, 0}, 0, 0, 1, 0);
  t.add_node({1, 2, 0}, 1, 0, 2, 1);
  t.add_node({-1, 2, 0}, 1, 0, 2, 1);
  t.add_node({-1, 3, 0}, 3, 0, 3, 1);
  t.steps = 3;
  apply_pipe_radii(t, 2.0f, 0.01f);
  // Two tips of 0.01 under node 1: r1^2 = 2 * 0.01^2.
  EXPECT_NEAR(t.radius[1], 0.01f * std::sqrt(2.0f), 1e-6);
  EXPECT_NEAR(t.radius[0], t.radius[1], 1e-6);
  EXPECT_EQ(validate_skeleton(t), "");
  // At step 1 only nodes 0 and 1 are alive: node 1 is a tip.
  auto r1 = radii_at_step(t, 1);
  EXPECT_NEAR(r1[1], 0.01f, 1e-6);
  EXPECT_EQ(r1[2], 0.0f);
}

TEST(Skeleton, ValidateCatchesBadParent) {
  tree_skeleton t;
  t.add_node({0, 0, 0}, -1, 0.1f, 0, 0);
  t.add_node({0, 1, 0}, 0, 0.1f, 0, 0);
  EXPECT_EQ(validate_skeleton(t), "");
  t.parent[1] = 1;
  EXPECT_NE(validate_skeleton(t), "");
}
