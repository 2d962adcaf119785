// Growth history (generators/history.h): seasons of unequal vigour, unequal forks and self-pruning
// with stubs, in the shared pass and in the generators that use them.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "tests/fixtures.h"
#include "generators/history.h"
#include "generators/leaves.h"
#include "generators/lsystem.h"
#include "generators/self_organizing.h"
#include "generators/space_colonization.h"

using namespace sylva;

namespace {

float seg_length(const tree_skeleton& t, size_t i) {
  return glm::length(t.position[i] - t.position[size_t(t.parent[i])]);
}

// A trunk of unit internodes, node j at height j born in step j (j = 0..10), and at each trunk node
// j >= 1 a level limb of five 0.2 m internodes, its node m born in step min(j + m, 10).
tree_skeleton whorled_pole() {
  tree_skeleton t;
  t.steps = 10;
  t.add_node({0, 0, 0}, -1, 0.1f, 0, 0);
  for (int j = 1; j <= 10; ++j) t.add_node({0, float(j), 0}, j - 1, 0.1f, uint16_t(j), 0);
  for (int j = 1; j <= 10; ++j) {
    int32_t par = j;
    for (int m = 1; m <= 5; ++m)
      par = t.add_node({0.2f * float(m), float(j), 0}, par, 0.01f, uint16_t(std::min(j + m, 10)), 1);
  }
  return t;
}

}  // namespace

TEST(GrowthHistory, SeasonsAreSeededPersistentAndOffAtZero) {
  const std::vector<float> z = season_anomalies(7, 20000);
  ASSERT_EQ(z.size(), 20001u);
  EXPECT_EQ(z[0], 0.0f);
  EXPECT_EQ(z, season_anomalies(7, 20000));
  EXPECT_NE(z, season_anomalies(8, 20000));
  // A shorter run is the start of the longer one: a step's season does not depend on the step count.
  const std::vector<float> head = season_anomalies(7, 30);
  EXPECT_TRUE(std::equal(head.begin(), head.end(), z.begin()));
  double mean = 0, var = 0, lag = 0;
  for (size_t k = 1; k < z.size(); ++k) mean += z[k];
  mean /= double(z.size() - 1);
  for (size_t k = 1; k < z.size(); ++k) var += (z[k] - mean) * (z[k] - mean);
  for (size_t k = 2; k < z.size(); ++k) lag += (z[k] - mean) * (z[k - 1] - mean);
  EXPECT_NEAR(mean, 0.0, 0.05);
  EXPECT_NEAR(var / double(z.size() - 1), 1.0, 0.06);   // unit variance
  EXPECT_NEAR(lag / var, 0.5, 0.03);                     // ρ = 0.5: good years come in runs
  EXPECT_EQ(season_vigour(0.0f, 2.5f), 1.0f);
  EXPECT_FLOAT_EQ(season_vigour(0.3f, 1.0f), std::exp(0.3f));
}

TEST(GrowthHistory, SpaceColonizationSegmentsFollowTheirStepsSeason) {
  space_colonization_params p = sylva_test::small_colonization_crown(600);
  grow_options o;
  o.seed = 5;
  const tree_skeleton plain = grow_space_colonization(p, o);
  p.season_variation = 0.4f;
  const tree_skeleton t = grow_space_colonization(p, o);
  ASSERT_GT(t.size(), 200u);
  const std::vector<float> z = season_anomalies(o.seed, p.steps);
  const int trunk_steps = int(std::ceil(p.trunk_length / p.segment_length));
  float lo = 1e9f, hi = 0;
  size_t crown = 0;
  for (size_t i = 1; i < t.size(); ++i) {
    const float len = seg_length(t, i);
    if (t.born[i] <= trunk_steps) {
      EXPECT_NEAR(len, p.segment_length, 1e-4f) << i;   // the trunk is not a season's growth
      continue;
    }
    ++crown;
    EXPECT_NEAR(len, p.segment_length * std::exp(0.4f * z[t.born[i]]), 1e-4f) << "node " << i;
    lo = std::min(lo, len), hi = std::max(hi, len);
  }
  EXPECT_GT(crown, 150u);
  EXPECT_GT(hi / lo, 1.5f);   // good and poor years differ visibly
  for (size_t i = 1; i < plain.size(); ++i) EXPECT_NEAR(seg_length(plain, i), p.segment_length, 1e-4f);
  EXPECT_EQ(t.position, grow_space_colonization(p, o).position);   // seeded: the same tree again
}

TEST(GrowthHistory, UnequalForksKeepTheLeaderCloserToItsCourse) {
  // The mean turn of each fork's first and second shoot off the forked internode's course.
  auto turns = [](float asymmetry) {
    space_colonization_params p = sylva_test::small_colonization_crown(600);
    p.fork_length = 0.8f;
    p.fork_angle = 80;
    p.fork_asymmetry = asymmetry;
    grow_options o;
    o.seed = 2;
    const tree_skeleton t = grow_space_colonization(p, o);
    std::vector<std::vector<int32_t>> kids(t.size());
    for (size_t i = 1; i < t.size(); ++i) kids[size_t(t.parent[i])].push_back(int32_t(i));
    double first = 0, second = 0;
    int forks = 0;
    for (size_t v = 1; v < t.size(); ++v) {
      const auto& k = kids[v];
      if (k.size() != 2 || t.born[size_t(k[0])] != t.born[size_t(k[1])] || k[1] != k[0] + 1) continue;
      const glm::vec3 course = glm::normalize(t.position[v] - t.position[size_t(t.parent[v])]);
      auto angle = [&](int32_t c) {
        const glm::vec3 d = glm::normalize(t.position[size_t(c)] - t.position[v]);
        return std::acos(std::clamp(glm::dot(d, course), -1.0f, 1.0f));
      };
      first += angle(k[0]), second += angle(k[1]), ++forks;
    }
    EXPECT_GT(forks, 10);
    return std::pair{first / forks, second / forks};
  };
  const auto [even1, even2] = turns(0.0f);
  EXPECT_NEAR(even1, even2, glm::radians(8.0));
  const auto [lead, side] = turns(0.7f);
  // Half the fork is 40°: the leader turns about 12° off the pulled direction, the side limb 68°.
  EXPECT_GT(side - lead, glm::radians(35.0));
}

TEST(GrowthHistory, DamagedLeadersForkAtSeededPlaces) {
  // Forks: nodes whose two children were added together (a node grows one child a step otherwise).
  auto forks = [](const tree_skeleton& t) {
    int n = 0;
    for (size_t i = 1; i + 1 < t.size(); ++i)
      if (t.parent[i] >= 0 && t.parent[i + 1] == t.parent[i] && t.born[i + 1] == t.born[i]) ++n;
    return n;
  };
  space_colonization_params p = sylva_test::small_colonization_crown(600);
  grow_options o;
  o.seed = 6;
  EXPECT_EQ(forks(grow_space_colonization(p, o)), 0);   // monopodial without damage or fork length
  p.leader_damage = 0.1f;
  const tree_skeleton t = grow_space_colonization(p, o);
  const int n = forks(t);
  // About one apex in ten forks each step: many forks, far fewer than the apices' growth steps.
  size_t apex_steps = 0;
  for (size_t i = 1; i < t.size(); ++i) apex_steps += t.order[i] == t.order[size_t(t.parent[i])];
  EXPECT_GT(n, 10);
  EXPECT_LT(size_t(n), apex_steps / 4);
  EXPECT_EQ(forks(grow_space_colonization(p, o)), n);   // seeded
  o.seed = 7;
  EXPECT_NE(grow_space_colonization(p, o).position, t.position);
}

TEST(GrowthHistory, SelfPruningLeavesStubsOfBoundedLength) {
  tree_skeleton t = whorled_pole();
  const tree_skeleton before = t;
  EXPECT_TRUE(self_prune(t, 1.0f, 0.3f).empty());   // 1: no limb dies
  EXPECT_EQ(t.position, before.position);
  EXPECT_TRUE(t.dead.empty());

  const std::vector<int32_t> kept = self_prune(t, 0.5f, 0.3f);
  ASSERT_FALSE(kept.empty());
  EXPECT_EQ(validate_skeleton(t), "");
  ASSERT_EQ(t.dead.size(), t.size());
  // H(k) = k, so the limb at height j dies in step 2j + 1: j = 1..4 die (steps 3, 5, 7, 9), j >= 5 live.
  // Of a dying limb the internodes starting within 0.3 m stay as dead stubs (the first two), the rest
  // falls at the death step or, born later, is gone.
  for (size_t i = 0; i < t.size(); ++i) {
    const glm::vec3 q = t.position[i];
    const int j = int(std::lround(q.y));
    if (q.x == 0.0f || j >= 5) {   // trunk and upper limbs: untouched
      EXPECT_EQ(t.died[i], never_died) << i;
      EXPECT_EQ(t.dead[i], never_died) << i;
      continue;
    }
    const uint16_t death = uint16_t(2 * j + 1);
    EXPECT_LT(t.born[i], death) << i;   // nothing grows on a dead limb
    if (q.x < 0.45f) {
      EXPECT_EQ(t.dead[i], death) << i;
      EXPECT_EQ(t.died[i], never_died) << i;
    } else {
      EXPECT_EQ(t.died[i], death) << i;
    }
  }
  // Limb j's node m is born in step j + m, so limbs 1-4 keep j nodes and lose 5 - j: the lowest keeps
  // only its first, a stub.
  int stub_nodes = 0, lowest = 0;
  for (size_t i = 0; i < t.size(); ++i)
    if (t.position[i].x > 0 && std::lround(t.position[i].y) == 1) ++lowest, stub_nodes += t.dead[i] != never_died;
  EXPECT_EQ(lowest, 1);
  EXPECT_EQ(stub_nodes, 1);
  EXPECT_EQ(t.size(), before.size() - 4 - 3 - 2 - 1);
  // The old index of each kept node.
  for (size_t j = 0; j < kept.size(); ++j) EXPECT_EQ(t.position[j], before.position[size_t(kept[j])]);
  // A stub is bare: no shoot leaf is alive on dead wood after it died.
  leaf_params lp;
  lp.retention = 64;
  lp.spacing = 0.05f;
  lp.min_order = 1;
  const foliage f = place_shoot_leaves(t, lp, 1);
  ASSERT_FALSE(f.leaves.empty());
  int on_stubs = 0;
  for (const leaf& l : f.leaves) {
    if (t.dead[size_t(l.node)] == never_died) continue;
    ++on_stubs;   // grown while the limb lived, fallen when it died
    EXPECT_LE(l.died, t.dead[size_t(l.node)]);
  }
  EXPECT_GT(on_stubs, 0);
}

TEST(GrowthHistory, LsystemSeasonsAndSelfPruningShapeAWhorledTree) {
  lsystem_params p;
  p.mode = lsystem_mode::text;
  p.scale = 1.0f;
  p.derivations = 12;
  // A leader of one 1 m internode a derivation with a pair of level limbs at each node, each limb
  // growing 0.4 m a derivation.
  p.source = "#axiom A\nA -> F(1)[&(85)B][/(180)&(85)B]A\nB -> F(0.4)B\n";
  grow_options o;
  o.seed = 3;
  const tree_skeleton plain = grow_lsystem(p, o);
  p.season_variation = 0.3f;
  const tree_skeleton seasons = grow_lsystem(p, o);
  ASSERT_EQ(plain.size(), seasons.size());
  const std::vector<float> z = season_anomalies(o.seed, p.derivations);
  int trunk = 0;
  for (size_t i = 1; i < seasons.size(); ++i) {
    if (seasons.order[i] != 0) continue;
    EXPECT_NEAR(seg_length(plain, i), 1.0f, 1e-4f);
    EXPECT_NEAR(seg_length(seasons, i), std::exp(0.3f * z[seasons.born[i]]), 1e-4f) << "derivation " << seasons.born[i];
    ++trunk;
  }
  EXPECT_EQ(trunk, 12);

  p.season_variation = 0;
  p.live_crown = 0.5f;
  p.stub_length = 0.5f;
  const tree_skeleton pruned = grow_lsystem(p, o);
  EXPECT_EQ(validate_skeleton(pruned), "");
  EXPECT_LT(pruned.size(), plain.size());
  // The tree is 12 m tall: limbs below 6 m have died, each leaving a stub of at most 0.5 m plus one
  // internode (0.4 m) on the trunk; the limbs above stay alive whole.
  int stubs = 0;
  for (size_t i = 1; i < pruned.size(); ++i) {
    if (pruned.order[i] == 0) continue;
    const float y = pruned.position[i].y;
    if (y >= 6.0f + 1e-3f) {
      EXPECT_EQ(pruned.dead_from(i), never_died);
      EXPECT_EQ(pruned.died[i], never_died);
    }
    if (pruned.dead_from(i) != never_died) {
      ++stubs;
      EXPECT_LT(y, 6.0f + 1e-3f);
      EXPECT_LE(std::hypot(pruned.position[i].x, pruned.position[i].z), 0.9f + 1e-3f);
    }
  }
  EXPECT_GE(stubs, 2 * 5);   // both limbs of each of the lower five nodes
}

TEST(GrowthHistory, SelfOrganizingLowerLimbsDieAsTheCrownRises) {
  self_organizing_params p;
  p.steps = 18;
  grow_options o;
  o.seed = 4;
  const tree_skeleton plain = grow_self_organizing(p, o);
  p.live_crown = 0.5f;
  p.stub_length = 0.2f;
  const tree_skeleton t = grow_self_organizing(p, o);
  EXPECT_EQ(validate_skeleton(t), "");
  ASSERT_EQ(t.dead.size(), t.size());
  // Every limb leaving the trunk below half the final height has died (its base stands as a stub);
  // without the pass most of them were alive.
  auto low_limbs = [](const tree_skeleton& s, bool living) {
    float top = 0;
    for (const glm::vec3& q : s.position) top = std::max(top, q.y);
    int n = 0;
    for (size_t i = 1; i < s.size(); ++i) {
      const int32_t par = s.parent[i];
      if (par < 0 || s.order[size_t(par)] != 0 || s.order[i] == 0 || s.position[size_t(par)].y >= 0.5f * top) continue;
      n += living == (s.died[i] == never_died && s.dead_from(i) == never_died);
    }
    return n;
  };
  EXPECT_GT(low_limbs(plain, true), 5);
  EXPECT_EQ(low_limbs(t, true), 0);
  EXPECT_GT(low_limbs(t, false), 5);
}

// Self-pruned limbs leave stubs as thick as the limb was when it died, never thicker than the
// stem that carries them; before, the pipe model made them as thin as twig tips.
TEST(GrowthHistory, DeadStubsKeepTheGirthOfTheLimbThatDied) {
  space_colonization_params p = sylva_test::small_colonization_crown(600);
  p.live_crown = 0.6f;
  p.stub_length = 0.3f;
  grow_options o;
  o.seed = 3;
  const tree_skeleton t = grow_space_colonization(p, o);
  ASSERT_EQ(t.dead.size(), t.size());
  int stubs = 0, thick = 0;
  for (size_t i = 1; i < t.size(); ++i) {
    if (t.dead[i] == never_died) continue;
    const int32_t par = t.parent[size_t(i)];
    EXPECT_LE(t.radius[i], t.radius[size_t(par)] * 1.0001f) << i;
    if (t.dead[size_t(par)] != never_died) continue;   // a stub's base, on its living stem
    ++stubs;
    thick += t.radius[i] > 2.0f * p.min_width;
  }
  ASSERT_GT(stubs, 2);
  EXPECT_GT(thick, stubs / 2);
  // The per-step view agrees: at the final step the stubs are as thick as in the final radii, and
  // before a stub's death it is a live limb with its own pipe radius.
  const std::vector<float> final_r = radii_at_step(t, t.steps);
  for (size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(final_r[i], t.radius[i], 1e-5f + 1e-4f * t.radius[i]) << i;
  // Nothing changes without dead wood.
  tree_skeleton live = t;
  live.dead.clear();
  std::vector<float> r = live.radius;
  thicken_stubs(live, live.steps, 2, p.min_width, r);
  EXPECT_EQ(r, live.radius);
}
