// Self-organizing trees: shadow grid, allocation models, bud fate, shedding, pipe radii, whole trees.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

#include "generators/self_organizing.h"
#include "generators/self_organizing_grid.h"

using namespace sylva;

namespace {

// A small tree that grows in well under a second.
self_organizing_params small_params() {
  self_organizing_params p;
  p.steps = 12;
  return p;
}

}  // namespace

TEST(SelfOrganizingGrid, OneBudMakesExactlyThePyramid) {
  shadow_grid g;
  const glm::ivec3 top(0, 3, -1);  // straddles chunk borders on x and z
  add_shadow_pyramid(g, top, 0.2f, 2.0f, 4);
  // Layer q holds (2q+1)² voxels, each a·b^(−q) = 0.2/2^q.
  for (int q = 0; q <= 4; ++q)
    for (int dz = -q; dz <= q; ++dz)
      for (int dx = -q; dx <= q; ++dx)
        EXPECT_FLOAT_EQ(shadow_at(g, top + glm::ivec3(dx, -q, dz)), 0.2f / float(1 << q));
  // Σ_{q=0..4} (2q+1)² = 1 + 9 + 25 + 49 + 81 = 165 voxels, and no others.
  EXPECT_EQ(count_shadowed_voxels(g), 165u);
  EXPECT_EQ(shadow_at(g, top + glm::ivec3(0, 1, 0)), 0.0f);    // above the bud
  EXPECT_EQ(shadow_at(g, top + glm::ivec3(0, -5, 0)), 0.0f);   // below q_max
  EXPECT_EQ(shadow_at(g, top + glm::ivec3(2, -1, 0)), 0.0f);   // outside layer 1's 3×3
  EXPECT_EQ(shadow_at(g, top + glm::ivec3(5, -4, 5)), 0.0f);   // outside layer 4's 9×9
}

TEST(SelfOrganizingGrid, RemovingTheBudRestoresTheGrid) {
  shadow_grid g;
  add_shadow_pyramid(g, {5, 5, 5}, 0.2f, 2.0f, 4);
  add_shadow_pyramid(g, {5, 5, 5}, 0.2f, 2.0f, 4, -1);
  EXPECT_EQ(count_shadowed_voxels(g), 0u);  // x − x is exactly 0 in floating point

  // With a second bud overlapping, removing it leaves the first bud's pyramid.
  shadow_grid a;
  add_shadow_pyramid(a, {0, 0, 0}, 0.3f, 1.5f, 3);
  shadow_grid b = a;
  add_shadow_pyramid(b, {1, -1, 2}, 0.3f, 1.5f, 3);
  add_shadow_pyramid(b, {1, -1, 2}, 0.3f, 1.5f, 3, -1);
  for (int y = -6; y <= 2; ++y)
    for (int z = -6; z <= 6; ++z)
      for (int x = -6; x <= 6; ++x) EXPECT_NEAR(shadow_at(b, {x, y, z}), shadow_at(a, {x, y, z}), 1e-6f);
}

TEST(SelfOrganizingGrid, SparseAndUnbounded) {
  shadow_grid g;
  add_shadow_pyramid(g, {0, 0, 0}, 0.2f, 2.0f, 4);
  add_shadow_pyramid(g, {100000, 50000, -100000}, 0.2f, 2.0f, 4);  // far beyond seed 000's 200³ box
  EXPECT_FLOAT_EQ(shadow_at(g, {100000, 50000, -100000}), 0.2f);
  // A 9×5×9 pyramid spans at most 2 chunks of 8 per axis: 8 chunks each, memory for 16 at most.
  EXPECT_LE(g.chunk_count(), 16u);
  EXPECT_EQ(count_shadowed_voxels(g), 330u);
}

TEST(SelfOrganizingAllocation, BorchertHondaSumsAndSpecialCases) {
  float vm, vl;
  // λQ_m = 0.6·3 = 1.8, (1−λ)Q_l = 0.4·1 = 0.4: v_m = 10·1.8/2.2, v_l = 10·0.4/2.2.
  split_borchert_honda(10, 3, 1, 0.6f, vm, vl);
  EXPECT_NEAR(vm, 10 * 1.8 / 2.2, 1e-5);
  EXPECT_NEAR(vl, 10 * 0.4 / 2.2, 1e-5);
  EXPECT_NEAR(vm + vl, 10, 1e-5);
  split_borchert_honda(7, 2, 2, 0.5f, vm, vl);  // λ = 0.5, Q_m = Q_l: an even split
  EXPECT_FLOAT_EQ(vm, 3.5f);
  EXPECT_FLOAT_EQ(vl, 3.5f);
  split_borchert_honda(4, 1.5f, 0, 0.3f, vm, vl);  // Q_l = 0: everything to the main axis
  EXPECT_FLOAT_EQ(vm, 4);
  EXPECT_FLOAT_EQ(vl, 0);
}

TEST(SelfOrganizingAllocation, PriorityWeightsAndSum) {
  // N = 10, κ = 0.5: ranks 0..4 fall linearly from w_max, ranks ≥ κN = 5 get w_min.
  EXPECT_FLOAT_EQ(priority_weight(0, 10, 1.0f, 0.006f, 0.5f), 1.0f);
  EXPECT_NEAR(priority_weight(2, 10, 1.0f, 0.006f, 0.5f), 1.0 - 0.994 * 2 / 5, 1e-6);
  EXPECT_FLOAT_EQ(priority_weight(5, 10, 1.0f, 0.006f, 0.5f), 0.006f);
  EXPECT_FLOAT_EQ(priority_weight(9, 10, 1.0f, 0.006f, 0.5f), 0.006f);

  std::vector<float> out;
  allocate_priority(7, {3, 2, 2, 1, 0.5f, 0.1f}, 1.0f, 0.006f, 0.5f, out);
  EXPECT_NEAR(std::accumulate(out.begin(), out.end(), 0.0), 7.0, 1e-5);
  // Two buds with equal Q: weights 1 and w_min, so v·1/1.006 and v·0.006/1.006.
  allocate_priority(2, {1, 1}, 1.0f, 0.006f, 0.5f, out);
  EXPECT_NEAR(out[0], 2 / 1.006, 1e-5);
  EXPECT_NEAR(out[1], 2 * 0.006 / 1.006, 1e-6);
}

TEST(SelfOrganizingBudFate, ShootSizes) {
  EXPECT_EQ(plan_shoot(0.99f, 0.1f).metamers, 0);
  EXPECT_EQ(plan_shoot(0, 0.1f).metamers, 0);
  EXPECT_EQ(plan_shoot(std::numeric_limits<float>::quiet_NaN(), 0.1f).metamers, 0);
  shoot_plan s = plan_shoot(1, 0.1f);
  EXPECT_EQ(s.metamers, 1);
  EXPECT_FLOAT_EQ(s.length, 0.1f);
  s = plan_shoot(2.5f, 0.1f);  // ⌊2.5⌋ = 2 metamers of 0.1·2.5/2
  EXPECT_EQ(s.metamers, 2);
  EXPECT_FLOAT_EQ(s.length, 0.125f);
  s = plan_shoot(3, 0.2f);
  EXPECT_EQ(s.metamers, 3);
  EXPECT_FLOAT_EQ(s.length, 0.2f);
}

TEST(SelfOrganizingShedding, RemovesExactlyTheQualifyingBranches) {
  // Node 0 is the root (negative flow, but a root is never shed); 1 and 5 are its children, 2 and
  // 3 those of 1, 4 that of 3, 6 that of 5.
  //   1: flow −1, 3 buds < 10    -> shed, with 2, 3, 4 (positive flow, but carried by 1)
  //   5: flow −0.5, 50 buds      -> kept (enough buds)
  //   6: flow −0.1, 2 buds       -> shed
  const std::vector<int32_t> parent{-1, 0, 1, 1, 3, 0, 5};
  const std::vector<float> flow{-5, -1, 2, 1, 1, -0.5f, -0.1f};
  const std::vector<int32_t> buds{60, 3, 1, 2, 1, 50, 2};
  EXPECT_EQ(select_shed(parent, flow, buds, 10), (std::vector<uint8_t>{0, 1, 1, 1, 1, 0, 1}));
  // Positive flow is never shed, whatever its bud count; n_min = 0 disables shedding.
  EXPECT_EQ(select_shed(parent, {1, 1, 1, 1, 1, 1, 1}, buds, 100), std::vector<uint8_t>(7, 0));
  EXPECT_EQ(select_shed(parent, flow, buds, 0), std::vector<uint8_t>(7, 0));
}

TEST(SelfOrganizingShedding, ShedNodesDisappearFromTheTimeline) {
  self_organizing_params p = small_params();
  p.steps = 16;
  p.bm = 0.1f;
  p.shed_min_buds = 30;
  tree_skeleton t = grow_self_organizing(p, {});
  ASSERT_EQ(validate_skeleton(t), "");
  size_t dead = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    if (t.died[i] == never_died) continue;
    ++dead;
    EXPECT_GT(t.parent[i], -1);
    EXPECT_FALSE(t.alive(i, t.died[i]));
    EXPECT_TRUE(t.alive(i, t.died[i] - 1));
  }
  EXPECT_GT(dead, 0u);
}

TEST(SelfOrganizingRadii, PipeModelAtEveryBranchPointAtEveryStep) {
  self_organizing_params p = small_params();
  p.pipe_exponent = 2.5f;
  tree_skeleton t = grow_self_organizing(p, {});
  ASSERT_EQ(validate_skeleton(t), "");
  ASSERT_GT(t.steps, 5);
  int checked = 0;
  for (int s = 0; s <= t.steps; ++s) {
    const std::vector<float> r = radii_at_step(t, s);
    std::vector<double> sum(t.size(), 0.0);
    std::vector<int> kids(t.size(), 0);
    for (size_t i = 0; i < t.size(); ++i)
      if (t.parent[i] >= 0 && t.alive(i, s)) {
        sum[t.parent[i]] += std::pow(double(r[i]), p.pipe_exponent);
        ++kids[t.parent[i]];
      }
    for (size_t i = 0; i < t.size(); ++i) {
      if (!t.alive(i, s)) continue;
      if (kids[i] == 0) {
        EXPECT_NEAR(r[i], p.tip_radius, 1e-6f);
      } else {
        EXPECT_NEAR(std::pow(double(r[i]), p.pipe_exponent) / sum[i], 1.0, 1e-3);
        checked += kids[i] > 1;
      }
    }
  }
  EXPECT_GT(checked, 100);
}

TEST(SelfOrganizingTree, NoLeanWithSymmetricSettings) {
  // No tropism: only the shadows and the default directions steer. Averaged over 20 seeds, the
  // crown's horizontal centre of mass stays within 5% of the tree height from the trunk axis.
  self_organizing_params p = small_params();
  p.w_tropism = 0;
  p.w_optimal = 1;
  glm::dvec2 com(0);
  double height = 0;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    grow_options o;
    o.seed = seed;
    const tree_skeleton t = grow_self_organizing(p, o);
    glm::dvec2 c(0);
    size_t n = 0;
    float top = 0;
    for (size_t i = 0; i < t.size(); ++i) {
      top = std::max(top, t.position[i].y);
      if (t.order[i] == 0) continue;  // the crown: every branch off the trunk
      c += glm::dvec2(t.position[i].x, t.position[i].z);
      ++n;
    }
    ASSERT_GT(n, 0u);
    com += c / double(n) / 20.0;
    height += top / 20.0;
  }
  EXPECT_LT(glm::length(com), 0.05 * height) << "centre of mass " << com.x << ", " << com.y << " height " << height;
}

TEST(SelfOrganizingTree, EnvironmentsAllocationsAndForests) {
  for (int env = 0; env < 2; ++env)
    for (int alloc = 0; alloc < 2; ++alloc) {
      self_organizing_params p = small_params();
      p.environment = so_environment(env);
      p.allocation = so_allocation(alloc);
      p.marker_count = 3000;
      p.envelope_radius = 1;
      p.envelope_bottom = 0;
      p.perception_distance = 4;
      p.envelope_top = 2;
      growth_debug dbg;
      grow_report rep;
      const tree_skeleton t = grow_self_organizing(p, {}, &rep, &dbg);
      EXPECT_EQ(validate_skeleton(t), "") << env << alloc;
      EXPECT_GT(t.size(), 30u) << env << alloc;
      EXPECT_EQ(dbg.node_fate.size(), t.size());
      EXPECT_EQ(dbg.node_flow.size(), t.size());
      EXPECT_EQ(dbg.points.size(), dbg.point_value.size());
      EXPECT_FALSE(dbg.points.empty());
    }
  self_organizing_params p = small_params();
  p.tree_count = 9;
  p.steps = 8;
  tree_skeleton t = grow_self_organizing(p, {});
  EXPECT_EQ(t.tree_count, 9);
  EXPECT_EQ(std::count(t.parent.begin(), t.parent.end(), -1), 9);
  EXPECT_EQ(validate_skeleton(t), "");
  p.placement = so_placement::explicit_positions;
  p.positions = {{0, 0, 0}, {3, 0, 1}};
  t = grow_self_organizing(p, {});
  EXPECT_EQ(t.tree_count, 2);
  EXPECT_EQ(t.position[1], glm::vec3(3, 0, 1));
}

// Pyramids added as one batch (one chunk-index cache shared by them) give the cells, and the
// chunk layout, of one pyramid after another.
TEST(ShadowGrid, PyramidsInOneBatchAreOneAfterAnother) {
  rng r(7);
  std::vector<glm::ivec3> voxels;
  for (int k = 0; k < 3000; ++k) voxels.push_back({r.uniform_int(40) - 20, r.uniform_int(30) - 5, r.uniform_int(40) - 20});
  for (float sign : {1.0f, -1.0f}) {
    shadow_grid one, many;
    for (const glm::ivec3& v : voxels) add_shadow_pyramid(one, v, 0.2f, 2.0f, 5, sign);
    add_shadow_pyramids(many, voxels, 0.2f, 2.0f, 5, sign);
    ASSERT_GT(one.chunk_count(), 8u);
    EXPECT_EQ(one.chunk_pos, many.chunk_pos);
    ASSERT_EQ(one.cells.size(), many.cells.size());
    EXPECT_EQ(0, std::memcmp(one.cells.data(), many.cells.data(), one.cells.size() * sizeof(float)));
  }
  shadow_grid capped;   // past the memory cap the writes go nowhere, as one at a time
  capped.chunk_cap = 5;
  add_shadow_pyramids(capped, voxels, 0.2f, 2.0f, 5);
  EXPECT_TRUE(capped.full);
  EXPECT_EQ(capped.chunk_count(), 5u);
}

// Opposite phyllotaxis: each node carries two lateral buds on opposite sides, each pair turned by
// φ from the last. With only the default directions steering, a node's two laterals leave exactly
// opposite each other, and the pairs of a node and of the next node on its axis are crossed
// (φ = 90°, decussate); a spiral tree never has two laterals on one node.
TEST(SelfOrganizingTree, OppositePhyllotaxisGrowsCrossedPairsOfLaterals) {
  auto laterals_of = [](const tree_skeleton& t) {
    std::vector<std::vector<int32_t>> lat(t.size());
    for (size_t c = 0; c < t.size(); ++c) {
      const int32_t par = t.parent[c];
      if (par >= 0 && t.order[c] == t.order[par] + 1) lat[size_t(par)].push_back(int32_t(c));
    }
    return lat;
  };
  // The first internode's direction off the parent's axis.
  auto across = [](const tree_skeleton& t, int32_t par, int32_t c) {
    const glm::vec3 axis = glm::normalize(t.position[size_t(par)] - t.position[size_t(t.parent[size_t(par)])]);
    const glm::vec3 d = t.position[size_t(c)] - t.position[size_t(par)];
    return glm::normalize(d - glm::dot(d, axis) * axis);
  };
  self_organizing_params p = small_params();
  p.w_optimal = 0;
  p.w_tropism = 0;
  p.divergence = 90;
  {
    const tree_skeleton t = grow_self_organizing(p, {});
    for (const auto& l : laterals_of(t)) EXPECT_LE(l.size(), 1u) << "spiral: one lateral bud per node";
  }
  p.phyllotaxis = so_phyllotaxis::opposite;
  const tree_skeleton t = grow_self_organizing(p, {});
  EXPECT_EQ(validate_skeleton(t), "");
  const auto lat = laterals_of(t);
  size_t pairs = 0, crossed = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    ASSERT_LE(lat[i].size(), 2u);
    if (lat[i].size() != 2 || t.parent[i] < 0) continue;
    ++pairs;
    EXPECT_LT(glm::dot(across(t, int32_t(i), lat[i][0]), across(t, int32_t(i), lat[i][1])), -0.999f) << i;
    for (size_t c = i + 1; c < t.size(); ++c)   // the next node of the same axis, with its own pair
      if (t.parent[c] == int32_t(i) && t.order[c] == t.order[i] && lat[c].size() == 2) {
        EXPECT_LT(std::abs(glm::dot(across(t, int32_t(i), lat[i][0]), across(t, int32_t(c), lat[c][0]))), 0.02f) << i;
        ++crossed;
      }
  }
  EXPECT_GT(pairs, 20u);
  EXPECT_GT(crossed, 5u);
  // Both environments, both allocation models and the per-node light count grow pairs too.
  for (int env = 0; env < 2; ++env)
    for (int alloc = 0; alloc < 2; ++alloc) {
      self_organizing_params q = small_params();
      q.phyllotaxis = so_phyllotaxis::opposite;
      q.environment = so_environment(env);
      q.allocation = so_allocation(alloc);
      q.light_count = alloc ? so_light_count::per_node : so_light_count::per_bud;
      q.marker_count = 3000, q.envelope_radius = 1, q.envelope_top = 2, q.perception_distance = 4;
      const tree_skeleton u = grow_self_organizing(q, {});
      EXPECT_EQ(validate_skeleton(u), "") << env << alloc;
      const auto l = laterals_of(u);
      EXPECT_GT(std::count_if(l.begin(), l.end(), [](const auto& v) { return v.size() == 2; }), 3) << env << alloc;
    }
}
