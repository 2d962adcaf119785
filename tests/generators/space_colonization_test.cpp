// Space colonization (Runions 2007): influence vs brute force, kill/termination invariants, trunk, widths, envelopes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <string>

#include <glm/geometric.hpp>

#include "generators/space_colonization.h"

using namespace sylva;

namespace {

std::vector<glm::vec3> random_points(int n, glm::vec3 lo, glm::vec3 hi, uint64_t seed) {
  rng r(seed);
  std::vector<glm::vec3> p;
  for (int i = 0; i < n; ++i) p.push_back({r.uniform(lo.x, hi.x), r.uniform(lo.y, hi.y), r.uniform(lo.z, hi.z)});
  return p;
}

float dist2(glm::vec3 a, glm::vec3 b) {
  const glm::vec3 d = a - b;
  return glm::dot(d, d);
}

// A small crown: 400 points in a 4 m box above a 1 m trunk.
space_colonization_params small_params() {
  space_colonization_params p;
  p.segment_length = 0.2f;
  p.influence_radius = 1.0f;
  p.kill_distance = 0.3f;
  p.trunk_length = 1.0f;
  p.steps = 2000;
  return p;
}
std::vector<glm::vec3> small_cloud(uint64_t seed = 3) { return random_points(400, {-2, 1, -2}, {2, 5, 2}, seed); }

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST(SpaceColonization, ParamsAreUniqueAndInRange) {
  space_colonization_params p;
  std::set<std::string> keys;
  visit_params(p, [&](auto& v, const param_info& info) {
    EXPECT_TRUE(keys.insert(info.key).second) << info.key;
    EXPECT_LE(info.min, info.max) << info.key;
    auto copy = v;
    EXPECT_TRUE(clamp_param(copy, info)) << info.key << " default out of range";
  });
}

TEST(SpaceColonization, InfluenceMatchesBruteForce) {
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const auto pts = random_points(300, glm::vec3(-2), glm::vec3(2), seed);
    const auto nodes = random_points(40, glm::vec3(-2), glm::vec3(2), seed + 100);
    const float d_i = 0.8f;
    const auto got = find_influencing_nodes(pts, nodes, d_i);
    ASSERT_EQ(got.size(), pts.size());
    int influenced = 0;
    for (size_t i = 0; i < pts.size(); ++i) {
      int best = -1;
      float best_d2 = 0;
      for (size_t k = 0; k < nodes.size(); ++k) {
        const float d2 = dist2(pts[i], nodes[k]);
        if (d2 < d_i * d_i && (best < 0 || d2 < best_d2)) best = int(k), best_d2 = d2;
      }
      EXPECT_EQ(got[i], best) << "point " << i << " seed " << seed;
      influenced += best >= 0;
    }
    EXPECT_GT(influenced, 0);  // the case is not vacuous
  }
}

TEST(SpaceColonization, InfluenceTiesGoToLowerIndexAndRadiusIsStrict) {
  // The point at the origin is exactly 1 from both nodes: the lower index wins. The point at (5,0,0)
  // is exactly d_i = 1 from node 2 at (4,0,0): "within d_i" is strict, so it is not influenced.
  const std::vector<glm::vec3> pts{{0, 0, 0}, {5, 0, 0}};
  const std::vector<glm::vec3> nodes{{1, 0, 0}, {-1, 0, 0}, {4, 0, 0}};
  const auto got = find_influencing_nodes(pts, nodes, 1.5f);
  EXPECT_EQ(got[0], 0);
  EXPECT_EQ(got[1], 2);
  EXPECT_EQ(find_influencing_nodes(pts, nodes, 1.0f)[1], -1);
}

TEST(SpaceColonization, EveryNodeIsDFromItsParent) {
  const auto p = small_params();
  tree_skeleton t = grow_colonization_from_points(p, small_cloud(), {});
  ASSERT_GT(t.size(), 50u);
  for (size_t i = 1; i < t.size(); ++i)
    EXPECT_NEAR(glm::length(t.position[i] - t.position[size_t(t.parent[i])]), p.segment_length, 1e-5f) << i;
  EXPECT_EQ(validate_skeleton(t), "");
}

TEST(SpaceColonization, NoPointWithinKillDistanceAfterAnyStep) {
  const auto p = small_params();
  const auto pts = small_cloud();
  growth_debug dbg;
  tree_skeleton t = grow_colonization_from_points(p, pts, {}, nullptr, &dbg);
  ASSERT_EQ(dbg.point_value.size(), pts.size());
  ASSERT_GT(t.steps, 10);
  // After step s the alive points are those removed later (value > s) or never (-1); the nodes are
  // those born at or before s.
  const float dk2 = p.kill_distance * p.kill_distance;
  for (int s = 0; s <= t.steps; ++s)
    for (size_t i = 0; i < pts.size(); ++i) {
      if (dbg.point_value[i] >= 0 && dbg.point_value[i] <= float(s)) continue;
      for (size_t k = 0; k < t.size(); ++k)
        if (t.born[k] <= s) {
          ASSERT_GT(dist2(pts[i], t.position[k]), dk2) << "step " << s << " point " << i;
        }
    }
}

TEST(SpaceColonization, TerminationLeavesNoReachablePoint) {
  for (uint64_t seed : {3u, 4u, 5u}) {
    const auto p = small_params();
    const auto pts = small_cloud(seed);
    growth_debug dbg;
    grow_report rep;
    tree_skeleton t = grow_colonization_from_points(p, pts, {}, &rep, &dbg);
    EXPECT_TRUE(rep.stop_reason == "no attraction points left" || rep.stop_reason == "no node influenced")
        << rep.stop_reason;
    EXPECT_FALSE(rep.error);
    for (size_t i = 0; i < pts.size(); ++i) {
      if (dbg.point_value[i] >= 0) continue;
      for (size_t k = 0; k < t.size(); ++k)
        ASSERT_GE(dist2(pts[i], t.position[k]), p.influence_radius * p.influence_radius);
    }
    EXPECT_GT(t.size(), 50u);
  }
}

TEST(SpaceColonization, PointCountNeverIncreasesAndStepsArePrefixes) {
  const auto p = small_params();
  const auto pts = small_cloud();
  tree_skeleton full = grow_colonization_from_points(p, pts, {});
  size_t previous = pts.size() + 1;
  for (int s = 0; s <= full.steps; s += 3) {
    grow_options o;
    o.steps = s;
    growth_debug dbg;
    tree_skeleton part = grow_colonization_from_points(p, pts, o, nullptr, &dbg);
    size_t alive = 0;
    for (float v : dbg.point_value) alive += v < 0;
    EXPECT_LE(alive, previous) << "step " << s;
    previous = alive;
    // Growing s steps gives exactly the nodes of the full run born at or before s.
    size_t born = 0;
    for (size_t i = 0; i < full.size(); ++i) born += full.born[i] <= s;
    ASSERT_EQ(part.size(), born);
    for (size_t i = 0; i < part.size(); ++i) ASSERT_EQ(part.position[i], full.position[i]);
  }
}

TEST(SpaceColonization, TreeHasNMinusOneEdgesAndNoCycle) {
  tree_skeleton t = grow_colonization_from_points(small_params(), small_cloud(), {});
  size_t roots = 0, edges = 0;
  for (size_t i = 0; i < t.size(); ++i) (t.parent[i] < 0 ? roots : edges) += 1;
  EXPECT_EQ(roots, 1u);
  EXPECT_EQ(edges, t.size() - 1);
  for (size_t i = 0; i < t.size(); ++i) {  // every walk up reaches the root within n hops
    int32_t k = int32_t(i);
    size_t hops = 0;
    while (k > 0 && hops <= t.size()) k = t.parent[size_t(k)], ++hops;
    ASSERT_EQ(k, 0) << i;
  }
}

TEST(SpaceColonization, RootRadiusFollowsPipeModel) {
  for (float n : {2.0f, 2.5f}) {
    auto p = small_params();
    p.pipe_exponent = n;
    p.min_width = 0.004f;
    p.max_width = 1000;  // the cap cannot bind: L^(1/n) stays far below 1000
    tree_skeleton t = grow_colonization_from_points(p, small_cloud(), {});
    std::vector<int> children(t.size(), 0);
    for (size_t i = 1; i < t.size(); ++i) ++children[size_t(t.parent[i])];
    int tips = 0;
    for (int c : children) tips += c == 0;
    ASSERT_GT(tips, 5);
    // r_root^n = Σ over the L tips of r0^n, so r_root = r0·L^(1/n).
    EXPECT_NEAR(t.radius[0], p.min_width * std::pow(float(tips), 1.0f / n), 1e-5f);
    EXPECT_EQ(t.pipe_exponent, n);  // radii_at_step thickens the tree over time
  }
}

TEST(SpaceColonization, MaxWidthCapsRadii) {
  auto p = small_params();
  p.min_width = 0.01f;
  p.max_width = 2;
  tree_skeleton t = grow_colonization_from_points(p, small_cloud(), {});
  EXPECT_FLOAT_EQ(t.radius[0], 0.02f);
  for (float r : t.radius) EXPECT_LE(r, 0.02f);
  EXPECT_EQ(t.pipe_exponent, 0.0f);  // stored capped radii
  EXPECT_EQ(validate_skeleton(t), "");
}

TEST(SpaceColonization, OppositePointsKeepPreviousDirection) {
  EXPECT_EQ(growth_direction(glm::vec3(0), {0, 1, 0}, {0, -1, 0}, 0.0f), glm::vec3(0, 1, 0));
  // Pull zero, tropism exactly against the previous direction at weight ½: still no NaN.
  EXPECT_EQ(growth_direction(glm::vec3(0), {0, 1, 0}, {0, -1, 0}, 0.5f), glm::vec3(0, 1, 0));
  // Root at the origin, no trunk, points at (±1,0,0): the pulls cancel, so the root keeps its
  // direction (up) and grows (0,0.25,0). Both points are farther from it (√1.0625 > 1), so the root's
  // set is unchanged in step 2 and would stack a node onto node 1: both points are removed then.
  auto p = small_params();
  p.trunk_length = 0;
  p.segment_length = 0.25f;
  p.influence_radius = 2;
  p.kill_distance = 0.1f;
  grow_report rep;
  growth_debug dbg;
  tree_skeleton t = grow_colonization_from_points(p, {{1, 0, 0}, {-1, 0, 0}}, {}, &rep, &dbg);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.position[1], glm::vec3(0, 0.25f, 0));
  EXPECT_EQ(t.steps, 2);
  EXPECT_EQ(dbg.point_value, (std::vector<float>{2, 2}));
  EXPECT_EQ(rep.stop_reason, "no attraction points left");
  EXPECT_EQ(validate_skeleton(t), "");
}

TEST(SpaceColonization, TrunkLengthNeedNotBeMultipleOfD) {
  // 1.0 / 0.3 = 3.33 internodes: rounded up to 4, each exactly 0.3 long, straight up.
  auto p = small_params();
  p.trunk_length = 1.0f;
  p.segment_length = 0.3f;
  grow_report rep;
  tree_skeleton t = grow_colonization_from_points(p, random_points(300, {-2, 2, -2}, {2, 5, 2}, 9), {}, &rep);
  EXPECT_FALSE(rep.error) << rep.message;
  ASSERT_GT(t.size(), 10u);
  for (int k = 1; k <= 4; ++k) {
    EXPECT_EQ(t.parent[size_t(k)], k - 1);
    EXPECT_EQ(t.born[size_t(k)], k);
    EXPECT_NEAR(t.position[size_t(k)].y, 0.3f * float(k), 1e-5f);
    EXPECT_EQ(t.position[size_t(k)].x, 0.0f);
    EXPECT_EQ(t.order[size_t(k)], 0);
  }
  EXPECT_EQ(validate_skeleton(t), "");
}

TEST(SpaceColonization, UnreachableCloudIsAnErrorNamingDi) {
  // A cloud 50 m to the side: going up never brings it within d_i = 1.
  auto p = small_params();
  grow_report rep;
  tree_skeleton t = grow_colonization_from_points(p, random_points(100, {49, 1, -1}, {51, 3, 1}, 2), {}, &rep);
  EXPECT_TRUE(rep.error);
  EXPECT_EQ(rep.stop_reason, "no point within reach");
  EXPECT_NE(rep.message.find("influence_radius"), std::string::npos) << rep.message;
  EXPECT_EQ(validate_skeleton(t), "");
  // It gave up once the tip was d_i above the highest point (at most 3 m): a finite trunk.
  EXPECT_LT(t.position.back().y, 3.0f + 1.0f + 2 * p.segment_length);
}

TEST(SpaceColonization, MaxBranchesStopsCleanly) {   // the node cap: generator_suite_test.cpp
  space_colonization_params p;  // the default tree has over 2,000 nodes
  p.max_branches = 100;
  grow_report rep;
  tree_skeleton t = grow_space_colonization(p, {}, &rep);
  EXPECT_EQ(t.size(), 101u);
  EXPECT_EQ(rep.stop_reason, "max branches");
  EXPECT_FALSE(rep.hit_node_cap);
}

TEST(SpaceColonization, DefaultTreeIsValidWithLeaves) {
  space_colonization_params p;
  grow_report rep;
  growth_debug dbg;
  tree_skeleton t = grow_space_colonization(p, {}, &rep, &dbg);
  EXPECT_EQ(validate_skeleton(t), "");
  EXPECT_FALSE(rep.error) << rep.message;
  EXPECT_GT(t.leaves.size(), 0u);
  for (const leaf& l : t.leaves) {
    EXPECT_GE(l.size, p.leaf_size_min);
    EXPECT_LE(l.size, p.leaf_size_max);
  }
  EXPECT_EQ(dbg.points.size(), size_t(p.points));
  EXPECT_EQ(dbg.lines.size() % 2, 0u);
  EXPECT_EQ(dbg.lines.size() / 2, dbg.line_color.size());
}

TEST(SpaceColonization, EnvelopeShapesHoldTheirPoints) {
  space_colonization_params p;
  p.points = 2000;
  p.size = {4, 2, 6};
  p.offset = {1, 5, -1};
  auto check = [&](envelope_shape s, auto inside) {
    p.envelope = s;
    const envelope_sample e = sample_envelope(p, 11, true);
    EXPECT_EQ(e.error, "");
    EXPECT_EQ(e.points.size(), 2000u);
    EXPECT_GT(e.outline.size(), 0u);
    for (const glm::vec3& q : e.points) ASSERT_TRUE(inside(q - p.offset)) << int(s);
  };
  const float eps = 1e-4f;
  check(envelope_shape::box, [&](glm::vec3 d) { return std::fabs(d.x) <= 2 && std::fabs(d.y) <= 1 && std::fabs(d.z) <= 3; });
  check(envelope_shape::sphere, [&](glm::vec3 d) { return glm::length(d) <= 2 + eps; });  // diameter size.x
  check(envelope_shape::ellipsoid, [&](glm::vec3 d) { return d.x * d.x / 4 + d.y * d.y + d.z * d.z / 9 <= 1 + eps; });
  check(envelope_shape::cylinder, [&](glm::vec3 d) { return d.x * d.x / 4 + d.z * d.z / 9 <= 1 + eps && std::fabs(d.y) <= 1; });
  // Hemisphere: flat base at the bottom (y = -1), dome of height 2.
  check(envelope_shape::hemisphere, [&](glm::vec3 d) { return d.y >= -1 && d.x * d.x / 4 + (d.y + 1) * (d.y + 1) / 4 + d.z * d.z / 9 <= 1 + eps; });
  // Cone: apex at the top; at height y the cross-section shrinks by (1 - y)/2.
  check(envelope_shape::cone, [&](glm::vec3 d) { const float f = (1 - d.y) / 2; return d.x * d.x / 4 + d.z * d.z / 9 <= f * f + eps; });
  // Flame: as wide as the box a quarter of the way up (y = -0.5), an ogive to a point at the top.
  check(envelope_shape::flame, [&](glm::vec3 d) {
    const float t = (d.y + 1) / 2;
    const float r = t < 0.25f ? std::sqrt(std::max(0.0f, 1 - (0.25f - t) * (0.25f - t) / 0.0625f)) : std::pow((1 - t) / 0.75f, 0.6f);
    return std::fabs(d.y) <= 1 && d.x * d.x / 4 + d.z * d.z / 9 <= r * r + eps;
  });
  p.slab_thickness = 0.1f;
  check(envelope_shape::slab, [&](glm::vec3 d) { return std::fabs(d.z) <= 0.05f + eps && std::fabs(d.x) <= 2; });
}

TEST(SpaceColonization, ObjEnvelopeRejectsMissingAndOpenMeshes) {
  space_colonization_params p;
  p.envelope = envelope_shape::mesh;
  p.envelope_mesh = testing::TempDir() + "sc_no_such_file.obj";
  grow_report rep;
  tree_skeleton t = grow_space_colonization(p, {}, &rep);
  EXPECT_TRUE(rep.error);
  EXPECT_NE(rep.message.find("cannot open"), std::string::npos) << rep.message;
  EXPECT_EQ(validate_skeleton(t), "");
  // A tetrahedron missing a face: three edges have one face each.
  p.envelope_mesh = write_temp("sc_open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n");
  rep = {};
  grow_space_colonization(p, {}, &rep);
  EXPECT_TRUE(rep.error);
  EXPECT_NE(rep.message.find("not closed"), std::string::npos) << rep.message;
}

TEST(SpaceColonization, ObjEnvelopeSamplesInsideClosedMesh) {
  // The corner tetrahedron, mapped onto the box [-1,1]^3 (size 2, offset 0): inside means
  // x' + y' + z' <= 1 with x' = (x+1)/2 >= 0 and so on.
  space_colonization_params p;
  p.envelope = envelope_shape::mesh;
  p.envelope_mesh = write_temp("sc_tet.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  p.size = glm::vec3(2);
  p.offset = glm::vec3(0);
  p.points = 1000;
  const envelope_sample e = sample_envelope(p, 5, true);
  ASSERT_EQ(e.error, "");
  ASSERT_EQ(e.points.size(), 1000u);
  EXPECT_EQ(e.outline.size(), 12u);  // 6 edges
  for (const glm::vec3& q : e.points) {
    const glm::vec3 b = (q + 1.0f) * 0.5f;
    ASSERT_GE(std::min({b.x, b.y, b.z}), -1e-4f);
    ASSERT_LE(b.x + b.y + b.z, 1 + 1e-4f);
  }
}

// Dents cut seeded bays into the envelope: with none the points are exactly the plain shape's; with
// some, every point still lies in the plain shape, the count is kept, and the crown's outline is
// uneven (points reach the full radius in some directions and stop well short in others).
TEST(SpaceColonization, EnvelopeDentsCutBaysAndKeepThePointCount) {
  space_colonization_params p;
  p.envelope = envelope_shape::ellipsoid;
  p.points = 6000;
  p.size = {10, 8, 10};
  p.offset = {0, 7, 0};
  const envelope_sample plain = sample_envelope(p, 3);
  p.envelope_dents = 0;
  p.envelope_dent_depth = 0.8f;
  EXPECT_EQ(sample_envelope(p, 3).points, plain.points) << "no dents: the plain shape's points";
  p.envelope_dents = 8;
  const envelope_sample dented = sample_envelope(p, 3);
  ASSERT_EQ(dented.error, "");
  ASSERT_EQ(dented.points.size(), 6000u);
  EXPECT_EQ(sample_envelope(p, 3).points, dented.points) << "seeded";
  EXPECT_NE(sample_envelope(p, 4).points, dented.points);
  const glm::vec3 h = p.size * 0.5f;
  // The outermost normalised radius per direction bin (16 azimuths x 8 heights).
  auto reach = [&](const std::vector<glm::vec3>& pts) {
    std::vector<float> r(128, 0.0f);
    for (const glm::vec3& x : pts) {
      const glm::vec3 q = (x - p.offset) / h;
      EXPECT_LE(glm::dot(q, q), 1.0f + 1e-4f);
      const float len = glm::length(q);
      const int az = std::clamp(int((std::atan2(q.z, q.x) + 3.14159265f) / 6.2831853f * 16), 0, 15);
      const int el = std::clamp(int((q.y / std::max(len, 1e-6f) + 1) * 4), 0, 7);
      r[size_t(el * 16 + az)] = std::max(r[size_t(el * 16 + az)], len);
    }
    return r;
  };
  const std::vector<float> a = reach(plain.points), b = reach(dented.points);
  int shallow_plain = 0, shallow_dented = 0;
  for (size_t i = 0; i < a.size(); ++i) shallow_plain += a[i] < 0.8f, shallow_dented += b[i] < 0.8f;
  EXPECT_EQ(shallow_plain, 0) << "the plain ellipsoid is filled to its rim in every direction";
  EXPECT_GE(shallow_dented, 8) << "dents leave directions whose points stop short of the rim";
  EXPECT_GE(*std::max_element(b.begin(), b.end()), 0.97f) << "undented directions still reach the rim";
}

namespace {

// The largest turn, in degrees, from a node's internode to its first child's (the apex that grew
// on from it; later children are laterals).
float largest_continuation_turn(const tree_skeleton& t) {
  std::vector<int32_t> first(t.size(), -1);
  for (size_t i = 0; i < t.size(); ++i)
    if (t.parent[i] >= 0 && first[size_t(t.parent[i])] < 0) first[size_t(t.parent[i])] = int32_t(i);
  float worst = 0;
  for (size_t v = 0; v < t.size(); ++v) {
    const int32_t par = t.parent[v], c = first[v];
    if (par < 0 || c < 0) continue;
    const glm::vec3 a = glm::normalize(t.position[v] - t.position[size_t(par)]);
    const glm::vec3 b = glm::normalize(t.position[size_t(c)] - t.position[v]);
    worst = std::max(worst, glm::degrees(std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f))));
  }
  return worst;
}

}  // namespace

TEST(SpaceColonization, LimitTurnKeepsTheTurnWithinTheLimit) {
  const glm::vec3 up(0, 1, 0), side = glm::normalize(glm::vec3(1, 0.2f, 0)), back(0, -1, 0);
  EXPECT_EQ(limit_turn(up, glm::normalize(glm::vec3(0.1f, 1, 0)), glm::radians(20.0f)), glm::normalize(glm::vec3(0.1f, 1, 0)));
  for (const glm::vec3& to : {side, back}) {
    const glm::vec3 d = limit_turn(up, to, glm::radians(20.0f));
    EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::degrees(std::acos(glm::dot(d, up))), 20.0f, 0.01f);
  }
  EXPECT_GT(limit_turn(up, side, glm::radians(20.0f)).x, 0.3f);   // towards `to`, in the plane of the two
}

// An apex turns at most max_turn per segment; without the limit the same cloud turns some apex far
// more (so the check can fail), and laterals still branch off at their own angles.
TEST(SpaceColonization, MaxTurnBoundsEveryApexTurn) {
  space_colonization_params p = small_params();
  const std::vector<glm::vec3> cloud = small_cloud();
  const tree_skeleton free = grow_colonization_from_points(p, cloud, {});
  EXPECT_GT(largest_continuation_turn(free), 30.0f);
  p.max_turn = 20;
  const tree_skeleton held = grow_colonization_from_points(p, cloud, {});
  EXPECT_EQ(validate_skeleton(held), "");
  EXPECT_GT(held.size(), free.size() / 2);
  EXPECT_LE(largest_continuation_turn(held), 20.05f);
}

// Pendulous twigs (twig_droop): the finer orders blend more of the downward tropism, so their
// segments point lower on average, while 0 changes nothing at all.
TEST(SpaceColonization, TwigDroopHangsTheFinerOrdersOnly) {
  space_colonization_params p = small_params();
  p.points = 800;
  p.tropism = {0, -1, 0};
  p.tropism_weight = 0.05f;
  grow_options o;
  o.seed = 5;
  const tree_skeleton plain = grow_space_colonization(p, o);
  // Mean vertical component of the unit segments of orders in [lo, hi], and their count.
  auto mean_dy = [](const tree_skeleton& t, int lo, int hi, int& n) {
    double s = 0;
    n = 0;
    for (size_t i = 1; i < t.size(); ++i) {
      if (t.parent[i] < 0 || int(t.order[i]) < lo || int(t.order[i]) > hi) continue;
      const glm::vec3 d = t.position[i] - t.position[size_t(t.parent[i])];
      const float l = glm::length(d);
      if (l > 0) s += double(d.y / l), ++n;
    }
    return n ? float(s / n) : 0.0f;
  };
  p.twig_droop = 0.5f;
  const tree_skeleton hanging = grow_space_colonization(p, o);
  int n0 = 0, n1 = 0;
  const float fine_plain = mean_dy(plain, 2, 255, n0), fine_hanging = mean_dy(hanging, 2, 255, n1);
  ASSERT_GT(n0, 50);
  ASSERT_GT(n1, 50);
  EXPECT_LT(fine_hanging, fine_plain - 0.05f);
  // The trunk's straight run and the first segments of the order-0 axis do not feel it.
  EXPECT_EQ(hanging.position[1], plain.position[1]);
  p.twig_droop = 0;
  EXPECT_EQ(grow_space_colonization(p, o).position, plain.position);
}
