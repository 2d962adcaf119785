// Cones and fruit (generators/fruits.h): which tips bear them, how they hang or stand, that a
// higher count keeps the fruit already placed, the ground, and the mesher carrying them.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "generators/fruits.h"
#include "render/mesh/mesh.h"
#include "render/mesh/season.h"

using namespace sylva;

namespace {

// A trunk of 10 internodes of 1 m (order 0), each with a 1 m horizontal lateral (order 1) whose
// end is a tip, and a last half-metre of trunk (node 21, y = 10.5) whose top is a tip too.
tree_skeleton comb() {
  tree_skeleton t;
  int32_t prev = t.add_node({0, 0, 0}, -1, 0.2f, 0, 0);
  for (int k = 1; k <= 10; ++k) {
    prev = t.add_node({0, float(k), 0}, prev, 0.1f, uint16_t(k), 0);
    t.add_node({1, float(k), 0}, prev, 0.02f, uint16_t(k), 1);
  }
  t.add_node({0, 10.5f, 0}, prev, 0.05f, 10, 0);
  t.steps = 10;
  return t;
}

glm::vec3 along(const leaf& l) { return l.orientation * glm::vec3(0, 1, 0); }

}  // namespace

TEST(Fruits, TheCountOfTipsBearFruitOfTheirOrderAndCrown) {
  const tree_skeleton t = comb();
  fruit_params p;
  p.count = 4;
  p.cards = 2;
  std::vector<leaf> out;
  place_fruits(t, p, 7, -10, out);
  ASSERT_EQ(out.size(), size_t(4 * 2));
  std::set<int> nodes;
  for (const leaf& l : out) {
    nodes.insert(l.node);
    EXPECT_EQ(t.order[size_t(l.node)], 1) << "min_order 1 leaves the trunk's top bare";
    EXPECT_EQ(l.archetype, uint8_t(leaf_archetype::cone_hanging));
    EXPECT_EQ(l.position, t.position[size_t(l.node)]);
    EXPECT_GE(l.born, 9) << "fruit comes with the last steps";
  }
  EXPECT_EQ(nodes.size(), size_t(4)) << "one fruit per tip";
  // More than there are tips: every order-1 tip, once.
  p.count = 100;
  out.clear();
  place_fruits(t, p, 7, -10, out);
  EXPECT_EQ(out.size(), size_t(10 * 2));
  // The top 30 % of the height (y from 0 to 10.5: y >= 7.35) holds 3 laterals' tips.
  p.crown_top = 0.3f;
  out.clear();
  place_fruits(t, p, 7, -10, out);
  EXPECT_EQ(out.size(), size_t(3 * 2));
  for (const leaf& l : out) EXPECT_GE(l.position.y, 8.0f);
  // min_order 0 and max_order 0: the trunk's top alone.
  p.min_order = 0, p.max_order = 0, p.crown_top = 1;
  out.clear();
  place_fruits(t, p, 7, -10, out);
  ASSERT_EQ(out.size(), size_t(2));
  EXPECT_EQ(out[0].node, 21);
}

// A self-pruned limb's dead stub (generators/history.h) is a tip but bears no fruit: before, the
// hazel's nuts hung on the bare stubs low on its stems, read as stray leaves under the crown.
TEST(Fruits, DeadStubsBearNoFruit) {
  tree_skeleton t = comb();
  t.dead.assign(t.size(), never_died);
  for (int k = 1; k <= 5; ++k) t.dead[size_t(2 * k)] = 8;   // the lowest five laterals' ends, dead from step 8
  fruit_params p;
  p.count = 100;
  p.min_order = 1;
  std::vector<leaf> out;
  place_fruits(t, p, 7, -10, out);
  std::set<int32_t> nodes;
  for (const leaf& l : out) nodes.insert(l.node);
  EXPECT_EQ(nodes.size(), size_t(5));   // the five upper laterals only
  for (int32_t i : nodes) EXPECT_GT(t.position[size_t(i)].y, 5.5f);
  // Before its death a stub was a living tip and bore fruit.
  t.steps = 7;
  std::vector<leaf> young;
  place_fruits(t, p, 7, -10, young);
  std::set<int32_t> young_nodes;
  for (const leaf& l : young) young_nodes.insert(l.node);
  EXPECT_EQ(young_nodes.size(), size_t(7));   // laterals born by step 7
}

TEST(Fruits, AHigherCountKeepsTheFruitAlreadyPlacedAndZeroPlacesNone) {
  const tree_skeleton t = comb();
  fruit_params p;
  p.cards = 1;
  std::vector<leaf> none;
  place_fruits(t, p, 3, -10, none);   // count 0 by default
  EXPECT_TRUE(none.empty());
  std::set<int> before, after;
  p.count = 3;
  std::vector<leaf> a, b;
  place_fruits(t, p, 3, -10, a);
  p.count = 6;
  place_fruits(t, p, 3, -10, b);
  for (const leaf& l : a) before.insert(l.node);
  for (const leaf& l : b) after.insert(l.node);
  EXPECT_EQ(before.size(), size_t(3));
  EXPECT_EQ(after.size(), size_t(6));
  EXPECT_TRUE(std::includes(after.begin(), after.end(), before.begin(), before.end()));
  // Another seed chooses other tips (for this comb at least one differs).
  std::vector<leaf> c;
  p.count = 3;
  place_fruits(t, p, 4, -10, c);
  std::set<int> other;
  for (const leaf& l : c) other.insert(l.node);
  EXPECT_NE(other, before);
}

TEST(Fruits, HangingFruitPointsDownUprightUpWithinTheTiltAndCardsCross) {
  const tree_skeleton t = comb();
  fruit_params p;
  p.count = 10;
  p.cards = 2;
  p.tilt = 20;
  const float cos_tilt = std::cos(glm::radians(20.0f)) - 1e-4f;
  std::vector<leaf> hang, stand;
  place_fruits(t, p, 5, -10, hang);
  p.pose = fruit_pose::upright;
  place_fruits(t, p, 5, -10, stand);
  ASSERT_EQ(hang.size(), size_t(20));
  ASSERT_EQ(stand.size(), size_t(20));
  for (size_t k = 0; k < hang.size(); ++k) {
    EXPECT_LE(along(hang[k]).y, -cos_tilt) << k;
    EXPECT_GE(along(stand[k]).y, cos_tilt) << k;
  }
  // A fruit's two cards share the axis and face 90 degrees apart.
  for (size_t k = 0; k + 1 < hang.size(); k += 2) {
    ASSERT_EQ(hang[k].node, hang[k + 1].node);
    EXPECT_NEAR(glm::dot(along(hang[k]), along(hang[k + 1])), 1.0f, 1e-4f);
    const glm::vec3 n0 = hang[k].orientation * glm::vec3(0, 0, 1), n1 = hang[k + 1].orientation * glm::vec3(0, 0, 1);
    EXPECT_NEAR(glm::dot(n0, n1), 0.0f, 1e-4f);
  }
}

TEST(Fruits, AxilFruitHangsWhereABranchLeavesItsParentOrReachesOutAlongIt) {
  // A two-node branch (order 1) leaving the comb's trunk at y = 4, 0.5 m per internode along +x,
  // besides the comb's one-node laterals.
  tree_skeleton t = comb();
  const int32_t b1 = t.add_node({0.5f, 4, 0}, 4 * 2 - 1, 0.02f, 4, 1);
  t.add_node({1.0f, 4, 0}, b1, 0.02f, 5, 1);
  ASSERT_EQ(t.position[size_t(4 * 2 - 1)], glm::vec3(0, 4, 0));
  fruit_params p;
  p.count = 100;
  p.cards = 1;
  p.site = fruit_site::axils;
  p.min_order = 0;   // the trunk's own nodes are no axils: only branch starts count
  std::vector<leaf> out;
  place_fruits(t, p, 5, -10, out);
  ASSERT_EQ(out.size(), size_t(11)) << "ten laterals and the new branch, once each";
  for (const leaf& l : out) {
    EXPECT_EQ(t.order[size_t(l.node)], 1);
    EXPECT_EQ(l.position.x, 0.0f) << "reach 0: at the junction on the trunk";
    EXPECT_EQ(l.position, t.position[size_t(t.parent[size_t(l.node)])]);
  }
  // Reach 0.8 m: the one-node laterals end at 1 m, so 0.8 m along them; the new branch's first
  // internode is 0.5 m, so the walk goes on into its second.
  p.reach = 0.8f;
  out.clear();
  place_fruits(t, p, 5, -10, out);
  ASSERT_EQ(out.size(), size_t(11));
  for (const leaf& l : out) EXPECT_NEAR(l.position.x, 0.8f, 1e-5f) << l.node;
  // Past a branch's end the fruit stays at its tip.
  p.reach = 5;
  out.clear();
  place_fruits(t, p, 5, -10, out);
  for (const leaf& l : out) EXPECT_NEAR(l.position.x, 1.0f, 1e-5f) << l.node;
  // The tips setting ignores reach: the ten laterals', the branch's and the trunk's tips.
  p.site = fruit_site::tips;
  out.clear();
  place_fruits(t, p, 5, -10, out);
  ASSERT_EQ(out.size(), size_t(12));
  for (const leaf& l : out) EXPECT_EQ(l.position, t.position[size_t(l.node)]);
}

TEST(Fruits, FruitReachingBelowTheGroundIsDropped) {
  const tree_skeleton t = comb();   // the lowest lateral's tip is 1 m up
  fruit_params p;
  p.count = 100;
  p.cards = 1;
  p.tilt = 0;
  p.size = 1.5f;
  p.size_jitter = 0;
  std::vector<leaf> out;
  place_fruits(t, p, 5, 0, out);   // a 1.5 m card hanging from y = 1 reaches y = -0.5
  EXPECT_EQ(out.size(), size_t(9));
  for (const leaf& l : out) EXPECT_GE(l.position.y, 2.0f);
}

TEST(Fruits, TheMesherCarriesThemAsUntintedEvergreenCardsBesideAnyLeafMode) {
  const tree_skeleton t = comb();
  mesh_params mp;
  mp.fruits.count = 5;
  mp.fruits.archetype = leaf_archetype::samaras;
  const size_t leaves = mesh_tree(t, mesh_params{}).leaves.size();
  const tree_mesh m = mesh_tree(t, mp);
  EXPECT_EQ(m.leaves.size(), leaves + 5 * 2);
  EXPECT_EQ(std::count_if(m.leaves.begin(), m.leaves.end(), [](const leaf_instance& l) { return l.texture == uint8_t(leaf_archetype::samaras); }), 10);
  EXPECT_EQ(m.leaf_end.back(), m.leaves.size());
  // A generator's own leaves are kept (copied) and the fruit added.
  tree_skeleton own = t;
  own.leaves.push_back(leaf{{0, 5, 0}, {1, 0, 0, 0}, 0.1f, 1, never_died, 5, 255});
  mp.leaves.mode = leaf_mode::generator;
  EXPECT_EQ(mesh_tree(own, mp).leaves.size(), size_t(1 + 10));
  // Fruit is never deciduous and takes no leaf tint.
  render_params rp;
  rp.habit = leaf_habit::deciduous;
  const season_look s = season_leaf_look(rp);
  for (int k = 0; k < leaf_archetype_count; ++k) {
    const bool fruit = archetype_is_fruit(leaf_archetype(k));
    EXPECT_EQ(season_deciduous(s, k), !fruit) << leaf_archetype_names[k];
    EXPECT_EQ(bool((fruit_archetype_mask() >> k) & 1u), fruit) << leaf_archetype_names[k];
  }
}
