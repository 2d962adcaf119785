// The foliage model (generators/leaves.h): leaves along young shoots, arrangement, retention,
// outer internodes, droop, cluster cards and the leaf cap.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "generators/leaves.h"
#include "render/mesh/mesh.h"

using namespace sylva;

namespace {

// A trunk (order 0) of `n` internodes of 1 m straight up, each born one step after the last, and a
// horizontal lateral (order 1) of one 1 m internode born at the last step.
tree_skeleton shoot(int n) {
  tree_skeleton t;
  int32_t prev = t.add_node({0, 0, 0}, -1, 0.1f, 0, 0);
  for (int k = 1; k <= n; ++k) prev = t.add_node({0, float(k), 0}, prev, 0.05f, uint16_t(k), 0);
  t.add_node({1, float(n), 0}, prev, 0.02f, uint16_t(n), 1);
  t.steps = n;
  return t;
}

leaf_params exact(float spacing) {  // one leaf node every `spacing` metres, no size noise
  leaf_params p;
  p.spacing = spacing;
  p.size_jitter = 0;
  p.retention = 64;
  return p;
}

glm::vec3 blade(const leaf& l) { return l.orientation * glm::vec3(0, 1, 0); }
glm::vec3 face(const leaf& l) { return l.orientation * glm::vec3(0, 0, 1); }

}  // namespace

TEST(Foliage, LeavesGrowAlongEveryShootInTheirArrangement) {
  const tree_skeleton t = shoot(3);   // 4 internodes of 1 m
  leaf_params p = exact(0.25f);       // 4 leaf nodes per metre
  EXPECT_EQ(place_shoot_leaves(t, p, 1).leaves.size(), size_t(4 * 4));
  p.arrangement = leaf_arrangement::opposite;
  EXPECT_EQ(place_shoot_leaves(t, p, 1).leaves.size(), size_t(4 * 4 * 2));
  p.arrangement = leaf_arrangement::whorled;
  p.whorl = 5;
  const foliage f = place_shoot_leaves(t, p, 1);
  EXPECT_EQ(f.leaves.size(), size_t(4 * 4 * 5));
  EXPECT_FALSE(f.capped);
  // Every leaf sits on its own internode, between the node and its parent.
  for (const leaf& l : f.leaves) {
    ASSERT_GE(l.node, 1);
    const glm::vec3 a = t.position[t.parent[l.node]], b = t.position[l.node];
    EXPECT_LT(glm::length(glm::cross(l.position - a, b - a)), 1e-4f);
    EXPECT_LE(glm::dot(l.position - a, b - a), glm::dot(b - a, b - a) + 1e-4f);
    EXPECT_GE(glm::dot(l.position - a, b - a), -1e-4f);
  }
  // min_order 1 keeps them off the trunk: only the lateral's 4 nodes of 5 leaves remain.
  p.min_order = 1;
  EXPECT_EQ(place_shoot_leaves(t, p, 1).leaves.size(), size_t(4 * 5));
}

TEST(Foliage, RetentionDecidesWhenLeavesFall) {
  tree_skeleton t = shoot(6);
  leaf_params p = exact(0.5f);
  p.retention = 2;
  const foliage f = place_shoot_leaves(t, p, 1);
  ASSERT_FALSE(f.leaves.empty());
  for (const leaf& l : f.leaves) {
    EXPECT_EQ(l.born, t.born[l.node]);
    EXPECT_EQ(l.died, t.born[l.node] + 3) << "alive for ages 0, 1 and 2";
  }
  // At the final step only the nodes at most 2 steps old are in leaf: born 4, 5, 6 (and the lateral).
  size_t alive = 0;
  for (const leaf& l : f.leaves) alive += l.born <= 6 && 6 < l.died;
  EXPECT_EQ(alive, size_t(4 * 2));
  // A shed node drops its leaves with it.
  t.died[6] = 6;
  t.died[7] = 6;
  for (const leaf& l : place_shoot_leaves(t, p, 1).leaves)
    if (l.node >= 6) { EXPECT_EQ(l.died, 6); }
}

TEST(Foliage, OuterInternodesKeepLeavesNearTheTips) {
  const tree_skeleton t = shoot(5);
  leaf_params p = exact(0.5f);
  p.outer_internodes = 2;
  const foliage f = place_shoot_leaves(t, p, 1);
  // The trunk axis ends at node 5: its internodes 4 and 5, plus the lateral (6): 3 internodes of 2 leaf nodes.
  EXPECT_EQ(f.leaves.size(), size_t(3 * 2));
  for (const leaf& l : f.leaves) EXPECT_TRUE(l.node == 4 || l.node == 5 || l.node == 6) << l.node;
}

TEST(Foliage, InsertionAngleDroopAndFacing) {
  const tree_skeleton t = shoot(2);
  leaf_params p = exact(0.1f);
  p.spread = 40;
  p.droop = 0;
  for (const leaf& l : place_shoot_leaves(t, p, 3).leaves) {
    const glm::vec3 d = glm::normalize(t.position[l.node] - t.position[t.parent[l.node]]);
    EXPECT_NEAR(glm::degrees(std::acos(std::clamp(glm::dot(blade(l), d), -1.0f, 1.0f))), 40.0f, 0.5f);
    EXPECT_NEAR(glm::length(l.orientation), 1.0f, 1e-4f);
    EXPECT_GE(face(l).y, -1e-4f) << "blades turn their upper face to the sky";
  }
  p.droop = 1;
  p.spread = 90;
  for (const leaf& l : place_shoot_leaves(t, p, 3).leaves) EXPECT_LT(blade(l).y, -0.8f) << "hanging leaves";
}

TEST(Foliage, ClusterCardsStandForSeveralLeaves) {
  const tree_skeleton t = shoot(3);
  leaf_params p = exact(0.05f);   // 20 leaf nodes a metre
  const size_t single = place_shoot_leaves(t, p, 1).leaves.size();
  p.clusters = true;
  p.cluster_size = 5;
  const foliage f = place_shoot_leaves(t, p, 1);
  EXPECT_EQ(single, size_t(80));
  EXPECT_EQ(f.leaves.size(), size_t(16));
  for (const leaf& l : f.leaves) {
    EXPECT_EQ(l.archetype, uint8_t(leaf_archetype::twig_cluster));
    EXPECT_NEAR(l.size, p.size * 0.9f * std::sqrt(5.0f), 1e-4f);
  }
  // The mesh keeps the cluster card's archetype; single leaves take the mesh's archetype.
  mesh_params mp;
  mp.leaves = p;
  mp.leaves.archetype = leaf_archetype::lobed;
  EXPECT_EQ(mesh_tree(t, mp).leaves[0].texture, uint8_t(leaf_archetype::twig_cluster));
  mp.leaves.clusters = false;
  EXPECT_EQ(mesh_tree(t, mp).leaves[0].texture, uint8_t(leaf_archetype::lobed));
}

TEST(Foliage, CrossedCardsTurnAboutTheBladeAndKeepTheOneCardLeaves) {
  const tree_skeleton t = shoot(3);
  leaf_params p = exact(0.25f);
  p.arrangement = leaf_arrangement::opposite;
  p.size_jitter = 0.3f;   // the size draw is shared by a leaf's cards
  const foliage one = place_shoot_leaves(t, p, 7);
  ASSERT_EQ(one.leaves.size(), size_t(32));
  for (int planes : {2, 3}) {
    p.planes = planes;
    const foliage many = place_shoot_leaves(t, p, 7);
    ASSERT_EQ(many.leaves.size(), one.leaves.size() * size_t(planes));
    const float turn = 3.14159265f / float(planes);
    for (size_t k = 0; k < one.leaves.size(); ++k) {
      const leaf& a = one.leaves[k];
      for (int c = 0; c < planes; ++c) {
        const leaf& b = many.leaves[k * size_t(planes) + size_t(c)];
        // The same leaf (place, size, life, node), its card turned c·pi/planes about the blade.
        EXPECT_EQ(b.position, a.position);
        EXPECT_EQ(b.size, a.size);
        EXPECT_EQ(b.born, a.born);
        EXPECT_EQ(b.died, a.died);
        EXPECT_EQ(b.node, a.node);
        EXPECT_NEAR(glm::dot(blade(a), blade(b)), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(face(a), face(b)), std::cos(turn * float(c)), 1e-5f) << planes << " planes, card " << c;
        if (c == 0) {
          EXPECT_EQ(b.orientation, a.orientation);
        }
      }
    }
  }
  // Out of range asks clamp to 1-3 cards; the cap counts cards.
  p.planes = 9;
  EXPECT_EQ(place_shoot_leaves(t, p, 7).leaves.size(), size_t(96));
  p.planes = 0;
  EXPECT_EQ(place_shoot_leaves(t, p, 7).leaves.size(), size_t(32));
  p.planes = 2;
  p.cap = 5;
  const foliage capped = place_shoot_leaves(t, p, 7);
  EXPECT_EQ(capped.leaves.size(), size_t(5));
  EXPECT_TRUE(capped.capped);
}

TEST(Foliage, CapStopsPlacementAndTheMeshSaysSo) {
  const tree_skeleton t = shoot(50);
  leaf_params p = exact(0.005f);  // 200 leaf nodes a metre: 10,200 leaves uncapped
  p.cap = 1000;
  const foliage f = place_shoot_leaves(t, p, 1);
  EXPECT_TRUE(f.capped);
  EXPECT_EQ(f.leaves.size(), size_t(1000));
  EXPECT_LE(f.leaves.capacity(), size_t(1016)) << "reserved no more than the cap allows";
  // The cap drops the oldest history, never the final crown: the newest nodes keep their leaves.
  int32_t oldest_kept = int32_t(t.size());
  for (const leaf& l : f.leaves) oldest_kept = std::min(oldest_kept, l.node);
  EXPECT_GE(oldest_kept, int32_t(t.size()) - 6) << "1000 leaves at 200 a metre fill the newest 5 internodes";
  size_t on_newest = 0;
  for (const leaf& l : f.leaves) on_newest += l.node == int32_t(t.size()) - 1;
  EXPECT_EQ(on_newest, size_t(200));
  mesh_params mp;
  mp.leaves = p;
  const tree_mesh m = mesh_tree(t, mp);
  EXPECT_EQ(m.leaves.size(), size_t(1000));
  EXPECT_NE(m.message.find("leaf cap"), std::string::npos);
  EXPECT_EQ(validate_mesh(m), "");
  mp.leaves.cap = 2000000;
  EXPECT_TRUE(mesh_tree(t, mp).message.empty());
  // Non-finite settings never produce non-finite leaves.
  p.cap = 300000;
  p.spread = NAN;
  p.droop = INFINITY;
  p.size = NAN;
  for (const leaf& l : place_shoot_leaves(t, p, 1).leaves) {
    ASSERT_TRUE(std::isfinite(l.size));
    ASSERT_TRUE(std::isfinite(l.orientation.x) && std::isfinite(l.orientation.w));
  }
}

TEST(Foliage, ModesChooseTheSource) {
  tree_skeleton t = shoot(2);
  t.leaves.push_back({{0, 1, 0}, {1, 0, 0, 0}, 0.2f, 1, never_died, 1});
  leaf_params p = exact(0.5f);
  p.mode = leaf_mode::generator;
  EXPECT_EQ(place_leaves(t, p, 1).leaves.size(), size_t(1));
  p.mode = leaf_mode::shoots;
  EXPECT_EQ(place_leaves(t, p, 1).leaves.size(), size_t(3 * 2));
  p.mode = leaf_mode::tips;
  p.density = 2;
  p.min_order = 0;
  EXPECT_EQ(place_leaves(t, p, 1).leaves.size(), size_t(2 * 2));   // the trunk tip and the lateral
  // Generator mode without generator leaves falls back to shoots.
  t.leaves.clear();
  p.mode = leaf_mode::generator;
  EXPECT_EQ(place_leaves(t, p, 1).leaves.size(), size_t(3 * 2));
}

TEST(Foliage, LeafInstancesStaySmall) {
  EXPECT_LT(sizeof(leaf_instance), size_t(64));
}
