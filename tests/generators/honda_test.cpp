// Honda's parametric tree (Prusinkiewicz et al. 1996): counts, width rule, history, determinism.
#include <gtest/gtest.h>

#include <cmath>

#include "generators/lsystem.h"

using namespace sylva;

TEST(Honda, InternodeCountForMinZero) {
  // With min = 0 every apex rewrites at every derivation: derivation k turns 2^(k-1) apices into
  // internodes, so n derivations give 1 + 2 + ... + 2^(n-1) = 2^n - 1 internodes (+ the root node).
  lsystem_params p;
  p.min_length = 0;
  for (int n : {0, 1, 2, 5, 10}) {
    p.derivations = n;
    tree_skeleton t = grow_honda(p, {});
    EXPECT_EQ(t.size(), size_t(1) << n) << "n = " << n;
    EXPECT_EQ(t.steps, n);
    EXPECT_EQ(validate_skeleton(t), "");
  }
}

TEST(Honda, WidthRuleAtBranchPoints) {
  lsystem_params p;  // tree a: e = 0.4
  p.q = 0.53f;
  tree_skeleton t = grow_honda(p, {});
  std::vector<std::vector<int>> children(t.size());
  for (size_t i = 1; i < t.size(); ++i) children[t.parent[i]].push_back(int(i));
  int checked = 0;
  const float inv_e = 1.0f / p.e;
  for (size_t i = 1; i < t.size(); ++i) {
    if (children[i].size() != 2) continue;
    const float lhs = std::pow(t.radius[i], inv_e);
    const float rhs = std::pow(t.radius[children[i][0]], inv_e) + std::pow(t.radius[children[i][1]], inv_e);
    EXPECT_NEAR(lhs / rhs, 1.0f, 1e-4f);
    ++checked;
  }
  EXPECT_EQ(checked, (1 << (p.derivations - 1)) - 1);  // every internode but the last generation
}

TEST(Honda, MinLengthStopsGrowth) {
  lsystem_params p;
  p.s0 = 100;
  p.r1 = p.r2 = 0.5f;
  p.min_length = 30;  // 100 and 50 grow; 25 < 30 does not
  p.derivations = 10;
  tree_skeleton t = grow_honda(p, {});
  EXPECT_EQ(t.size(), 1u + 1u + 2u);
}

TEST(Honda, StepViewIsPrefixOfFullGrowth) {
  lsystem_params p;
  p.alpha1 = 30; p.alpha2 = -30; p.phi1 = 137; p.phi2 = 137; p.r1 = p.r2 = 0.8f;  // tree g
  tree_skeleton full = grow_honda(p, {});
  for (int s = 0; s <= p.derivations; ++s) {
    grow_options o;
    o.steps = s;
    tree_skeleton part = grow_honda(p, o);
    size_t alive = 0;
    for (size_t i = 0; i < full.size(); ++i) alive += full.alive(i, s);
    ASSERT_EQ(part.size(), alive);
    for (size_t i = 0; i < part.size(); ++i) {
      EXPECT_EQ(part.position[i], full.position[i]);
      EXPECT_EQ(part.parent[i], full.parent[i]);
    }
  }
}

