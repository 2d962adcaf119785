// Pruning: a cut leaves the tree before its step untouched, removes its branch from
// then on, and each generator answers it (Palubicki 2009's bud break, freed points and vertices).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include <cstdio>

#include "render/io/preset.h"
#include "tests/generators/generator_cases.h"
#include "generators/pruning.h"
#include "generators/tree_spec.h"
#include "tests/tree_compare.h"

using namespace sylva;

namespace {

using sylva_test::case_t;
using sylva_test::cases;

// The lateral branch with the most nodes alive at `step`: a cut worth making.
int32_t biggest_lateral(const tree_skeleton& t, int step) {
  std::vector<int> below(t.size(), 0);
  for (size_t i = t.size(); i-- > 0;)
    if (t.alive(i, step)) {
      ++below[i];
      if (t.parent[i] >= 0) below[size_t(t.parent[i])] += below[i];
    }
  int32_t best = -1;
  for (size_t i = 0; i < t.size(); ++i) {
    if (!t.alive(i, step) || t.parent[i] < 0 || t.order[i] == t.order[size_t(t.parent[i])]) continue;
    if (best < 0 || below[i] > below[size_t(best)]) best = int32_t(i);
  }
  return best;
}

// Per node: 1 when it is `root` or below it.
std::vector<uint8_t> subtree(const tree_skeleton& t, int32_t root) {
  std::vector<uint8_t> in(t.size(), 0);
  for (size_t i = size_t(root); i < t.size(); ++i)
    in[i] = int32_t(i) == root || (t.parent[i] >= 0 && in[size_t(t.parent[i])]);
  return in;
}

}  // namespace

TEST(Pruning, CutLeavesEarlierStepsAndRemovesItsBranchInEveryGenerator) {
  for (const case_t& c : cases) {
    tree_spec s = small_spec(c.generator, c.markers);
    const tree_skeleton plain = grow(s, {});
    const int k = std::max(2, plain.steps / 2 + 1);
    const int32_t victim = biggest_lateral(plain, k - 1);
    ASSERT_GE(victim, 0) << c.name;
    prune_cut cut;
    cut.step = k;
    cut.point = plain.position[size_t(victim)];
    cut.reach = 1e-3f;
    ASSERT_EQ(add_cut(s, cut), "") << c.name;
    grow_report rep;
    const tree_skeleton pruned = grow(s, {}, &rep);
    EXPECT_TRUE(rep.missed_cuts.empty()) << c.name << ": " << rep.message;
    EXPECT_EQ(validate_skeleton(pruned), "") << c.name;
    expect_same_up_to(plain, pruned, k - 1, std::string(c.name) + " cut at step " + std::to_string(k));
    // The branch and everything on it died at step k, and nothing grows from it later
    // (validate_skeleton: no node outlives its parent).
    const std::vector<uint8_t> in = subtree(pruned, victim);
    for (size_t i = 0; i < pruned.size(); ++i)
      if (in[i]) {
        ASSERT_LE(int(pruned.died[i]), k) << c.name << " node " << i;
      }
    EXPECT_EQ(int(pruned.died[size_t(victim)]), k) << c.name;
    // Leaves go with their nodes.
    for (const leaf& l : pruned.leaves)
      if (in[size_t(l.node)]) {
        EXPECT_LE(int(l.died), k) << c.name;
      }
  }
}

// Palubicki et al. 2009 (§7): with its shadow and its share of resource gone, the buds near the cut
// break: more shoots start near the cut than in the uncut tree.
TEST(Pruning, SelfOrganizingBudsNearTheCutBreak) {
  tree_spec s = small_spec(0);
  std::get<self_organizing_params>(s.params).steps = 14;
  const tree_skeleton plain = grow(s, {});
  const int k = 9;
  const int32_t victim = biggest_lateral(plain, k - 1);
  ASSERT_GE(victim, 0);
  const glm::vec3 at = plain.position[size_t(victim)];
  ASSERT_EQ(add_cut(s, {k, prune_shape::branch, at, glm::vec3(1), 1e-3f}), "");
  const tree_skeleton pruned = grow(s, {});
  const std::vector<uint8_t> gone = subtree(plain, victim);
  // New shoots from k on whose parent was alive before the cut, off the cut branch, within 1.5 m.
  auto breaks = [&](const tree_skeleton& t) {
    int n = 0;
    for (size_t i = 0; i < t.size(); ++i) {
      const int32_t par = t.parent[i];
      if (t.born[i] < k || par < 0 || t.born[size_t(par)] >= k || (size_t(par) < gone.size() && gone[size_t(par)])) continue;
      if (glm::length(t.position[size_t(par)] - at) < 1.5f) ++n;
    }
    return n;
  };
  EXPECT_GT(breaks(pruned), breaks(plain));
}

// Space colonization: the points the cut branch had killed come back, and other branches grow
// into the space it held.
TEST(Pruning, SpaceColonizationRegrowsIntoTheFreedPoints) {
  tree_spec s = small_spec(1);
  const tree_skeleton plain = grow(s, {});
  const int k = std::max(2, plain.steps / 2);
  const int32_t victim = biggest_lateral(plain, k - 1);
  ASSERT_GE(victim, 0);
  ASSERT_EQ(add_cut(s, {k, prune_shape::branch, plain.position[size_t(victim)], glm::vec3(1), 1e-3f}), "");
  const tree_skeleton pruned = grow(s, {});
  const std::vector<uint8_t> gone = subtree(pruned, victim);
  const float near = 0.5f * std::get<space_colonization_params>(s.params).influence_radius;
  int regrown = 0;
  for (size_t i = 0; i < pruned.size(); ++i) {
    if (pruned.born[i] < k || gone[i]) continue;
    for (size_t j = 0; j < pruned.size(); ++j)
      if (gone[j] && pruned.born[j] < k && glm::length(pruned.position[i] - pruned.position[j]) < near) {
        ++regrown;
        break;
      }
  }
  EXPECT_GT(regrown, 0);
}

TEST(Pruning, CutThatFindsNoBranchIsReportedAndChangesNothing) {
  for (const case_t& c : cases) {
    tree_spec s = small_spec(c.generator, c.markers);
    const tree_skeleton plain = grow(s, {});
    ASSERT_EQ(add_cut(s, {2, prune_shape::branch, glm::vec3(500, 500, 500), glm::vec3(1), 0.25f}), "");
    grow_report rep;
    const tree_skeleton t = grow(s, {}, &rep);
    EXPECT_EQ(rep.missed_cuts, std::vector<int>{0}) << c.name;
    EXPECT_NE(rep.message.find("finds no branch"), std::string::npos) << rep.message;
    EXPECT_TRUE(same_tree(plain, t)) << c.name;
  }
}

// The brush shears at the shape's surface: at step k every node outside the shape whose path from
// the root passed through the shape is gone; what never entered it (the trunk below) stays.
TEST(Pruning, BrushCutsEverythingOutsideTheShape) {
  for (const case_t& c : cases) {
    tree_spec s = small_spec(c.generator, c.markers);
    const tree_skeleton plain = grow(s, {});
    const int k = std::max(2, plain.steps / 2 + 1);
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (size_t i = 0; i < plain.size(); ++i)
      if (plain.alive(i, k - 1)) lo = glm::min(lo, plain.position[i]), hi = glm::max(hi, plain.position[i]);
    prune_cut brush;
    brush.step = k;
    brush.shape = prune_shape::outside_box;
    brush.point = 0.5f * (lo + hi);   // the middle half of the crown in every direction
    brush.size = 0.25f * (hi - lo) + glm::vec3(1e-3f);
    ASSERT_EQ(add_cut(s, brush), "") << c.name;
    std::vector<uint8_t> removed;
    ASSERT_TRUE(select_cut(plain, brush, removed));
    const tree_skeleton& t = plain;
    auto out = [&](size_t i) {
      const glm::vec3 q = glm::abs(t.position[i] - brush.point) / brush.size;
      return q.x > 1 || q.y > 1 || q.z > 1;
    };
    // Expected: internodes leaving the shape, with their subtrees; nothing that never entered it.
    std::vector<uint8_t> entered(t.size(), 0), want(t.size(), 0);
    int cut = 0;
    for (size_t i = 0; i < t.size(); ++i) {
      const int32_t par = t.parent[i];
      entered[i] = !out(i) || (par >= 0 && entered[size_t(par)]);
      if (par < 0 || !t.alive(i, k - 1)) continue;
      want[i] = want[size_t(par)] || (out(i) && !out(size_t(par)));
      EXPECT_EQ(bool(removed[i]), bool(want[i])) << c.name << " node " << i;
      if (!entered[i]) {
        EXPECT_FALSE(removed[i]) << c.name << " node " << i << " never entered the shape";
      }
      cut += want[i];
    }
    // Grown with the brush: those nodes die at step k and the tree stays valid.
    const tree_skeleton g = grow(s, {});
    EXPECT_EQ(validate_skeleton(g), "") << c.name;
    expect_same_up_to(plain, g, k - 1, c.name);
    for (size_t i = 0; i < removed.size(); ++i)
      if (removed[i]) {
        ASSERT_EQ(int(g.died[i]), k) << c.name << " node " << i;
      }
    EXPECT_GT(cut, 0) << c.name;
  }
}

// A cut names its branch by a point, so it still finds it after an earlier change moves the
// branch a little.
TEST(Pruning, CutSurvivesAnEarlierChange) {
  tree_spec s = small_spec(3);
  const tree_skeleton plain = grow(s, {});
  const int32_t victim = biggest_lateral(plain, 4);
  ASSERT_EQ(add_cut(s, {5, prune_shape::branch, plain.position[size_t(victim)], glm::vec3(1), 0.25f}), "");
  auto& l = std::get<lsystem_params>(s.params);
  l.alpha1 += 1;   // every branch turns a degree more
  grow_report rep;
  const tree_skeleton t = grow(s, {}, &rep);
  EXPECT_TRUE(rep.missed_cuts.empty()) << rep.message;
  int cut = 0;
  for (size_t i = 0; i < t.size(); ++i) cut += t.died[i] == 5;
  EXPECT_GT(cut, 0);
}

TEST(Pruning, BadCutsAreRefusedAndLeaveTheSpecAsItWas) {
  tree_spec s = small_spec(0);
  ASSERT_EQ(add_cut(s, {3, prune_shape::branch, glm::vec3(0, 1, 0), glm::vec3(1), 0.25f}), "");
  const tree_spec before = s;
  auto refused = [&](const prune_cut& c, const char* words) {
    const std::string e = add_cut(s, c);
    EXPECT_NE(e.find(words), std::string::npos) << e;
    EXPECT_EQ(s, before);
  };
  refused({201, prune_shape::branch, glm::vec3(0), glm::vec3(1), 0.25f}, "beyond the most steps a growth can have (200)");
  refused({0, prune_shape::branch, glm::vec3(0), glm::vec3(1), 0.25f}, "steps start at 1");
  refused({3, prune_shape::branch, glm::vec3(NAN, 0, 0), glm::vec3(1), 0.25f}, "finite");
  refused({3, prune_shape::branch, glm::vec3(0), glm::vec3(1), 0}, "reach");
  refused({3, prune_shape::outside_box, glm::vec3(0), glm::vec3(1, 0, 1), 0.25f}, "brush size");
  refused({3, prune_shape::branch, glm::vec3(0, 1, 0), glm::vec3(1), 0.25f}, "already in the list");
  tree_spec text;
  lsystem_params l;
  l.mode = lsystem_mode::text;
  text.params = l;
  EXPECT_NE(add_cut(text, {1, prune_shape::branch, glm::vec3(0), glm::vec3(1), 0.25f}).find("text L-systems"),
            std::string::npos);
}

// One small cut on the oak (space colonization) takes an order-3 branch and the tree regrows into
// the points that branch had killed. The regrowth is bounded: at most a fifth more nodes than the
// uncut tree. (The leaves rise much more, by about 84%: the new shoots are short and each ends in
// a leaf-bearing tip; the Pruning panel says so.) The points given back can keep the growth going
// a few steps past the uncut tree's last one (64 against 62 on the oak with its 3.6 m trunk), never
// more than five.
TEST(Pruning, OneSmallCutOnTheOakRegrowsBoundedly) {
  preset oak;
  ASSERT_TRUE(load_preset_file(SYLVA_SOURCE_DIR "/presets/species_oak.json", oak).ok);
  const tree_skeleton plain = grow(oak.spec, {});
  const int k = std::min(45, plain.steps - 2);
  int32_t victim = -1;
  std::vector<int> below(plain.size(), 0);
  for (size_t i = plain.size(); i-- > 0;)
    if (plain.alive(i, k - 1)) {
      ++below[i];
      if (plain.parent[i] >= 0) below[size_t(plain.parent[i])] += below[i];
    }
  for (size_t i = 0; i < plain.size(); ++i)   // the biggest order-3 branch alive before the cut
    if (plain.alive(i, k - 1) && plain.order[i] == 3 && plain.parent[i] >= 0 && plain.order[size_t(plain.parent[i])] == 2 &&
        (victim < 0 || below[i] > below[size_t(victim)]))
      victim = int32_t(i);
  ASSERT_GE(victim, 0);
  tree_spec cut = oak.spec;
  // As the editor's "Cut here" makes it: the reach is 1.5 internodes.
  const float reach = std::clamp(
      1.5f * glm::length(plain.position[size_t(victim)] - plain.position[size_t(plain.parent[size_t(victim)])]), 0.02f, 1.0f);
  ASSERT_EQ(add_cut(cut, {k, prune_shape::branch, plain.position[size_t(victim)], glm::vec3(1), reach}), "");
  grow_report rep;
  const tree_skeleton pruned = grow(cut, {}, &rep);
  ASSERT_TRUE(rep.missed_cuts.empty()) << rep.message;
  auto nodes_alive = [](const tree_skeleton& t) {
    size_t n = 0;
    for (size_t i = 0; i < t.size(); ++i) n += t.alive(i, t.steps);
    return n;
  };
  auto leaves_alive = [](const tree_skeleton& t) {
    size_t n = 0;
    for (const leaf& l : t.leaves) n += l.died > t.steps;
    return n;
  };
  const size_t plain_nodes = nodes_alive(plain), pruned_nodes = nodes_alive(pruned);
  std::printf("oak: %zu nodes and %zu leaves uncut; %zu and %zu after cutting an order-3 branch of %d nodes at step %d\n",
              plain_nodes, leaves_alive(plain), pruned_nodes, leaves_alive(pruned), below[size_t(victim)], k);
  EXPECT_GT(pruned_nodes + size_t(below[size_t(victim)]), plain_nodes);   // it regrows
  EXPECT_LT(pruned_nodes, plain_nodes + plain_nodes / 5);                 // boundedly
  // The oak's seasons give each step its own segment length, so the regrown crown may use up its
  // points a step before the uncut one does.
  EXPECT_GE(pruned.steps, plain.steps - 2);
  EXPECT_LE(pruned.steps, plain.steps + 5);
}
