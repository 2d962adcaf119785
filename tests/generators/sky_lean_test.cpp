// Growth history, continued (generators/history.h): the crown's lean towards open sky (Loehle 1986).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "tests/fixtures.h"
#include "generators/history.h"
#include "generators/self_organizing.h"
#include "generators/space_colonization.h"

using namespace sylva;

namespace {

// The mean horizontal offset of a tree's nodes along `dir`, in metres.
float mean_offset(const tree_skeleton& t, const glm::vec3& dir) {
  double s = 0;
  for (const glm::vec3& q : t.position) s += double(glm::dot(glm::vec3(q.x, 0, q.z), dir));
  return t.size() ? float(s / double(t.size())) : 0.0f;
}

}  // namespace

TEST(SkyLean, HelpersLeanTowardsTheOpenSideAndAreOffAtZero) {
  const glm::vec3 east = open_side_direction(0), south = open_side_direction(90);
  EXPECT_NEAR(east.x, 1, 1e-6f);
  EXPECT_NEAR(south.z, 1, 1e-6f);
  EXPECT_NEAR(south.x, 0, 1e-6f);
  const glm::vec3 up(0, 1, 0);
  EXPECT_EQ(lean_to_sky(up, 0, east), up);
  const glm::vec3 d = lean_to_sky(up, 0.5f, east);   // normalize((0,1,0) + 0.5·(1,0,0))
  EXPECT_NEAR(glm::length(d), 1, 1e-6f);
  EXPECT_NEAR(d.x / d.y, 0.5f, 1e-5f);
  // Points are all kept without a lean; with ψ = 0.6 all on the open rim, 0.7 across the axis,
  // 0.4 on the shaded rim.
  EXPECT_EQ(sky_keep_chance({-1, 0, 0}, 0, east), 1.0f);
  EXPECT_NEAR(sky_keep_chance({1, 0, 0}, 0.6f, east), 1.0f, 1e-6f);
  EXPECT_NEAR(sky_keep_chance({0, 0.5f, 1}, 0.6f, east), 0.7f, 1e-6f);
  EXPECT_NEAR(sky_keep_chance({-1, 0, 0}, 0.6f, east), 0.4f, 1e-6f);
}

TEST(SkyLean, SpaceColonizationCrownGrowsOutTowardsTheOpenSide) {
  space_colonization_params p = sylva_test::small_colonization_crown(800);
  grow_options o;
  o.seed = 3;
  const tree_skeleton plain = grow_space_colonization(p, o);
  p.open_side = 90;   // +z
  const tree_skeleton off = grow_space_colonization(p, o);   // the azimuth alone changes nothing
  EXPECT_EQ(off.position, plain.position);
  EXPECT_EQ(off.radius, plain.radius);
  // The envelope keeps its point count; the shaded side's share falls.
  const envelope_sample even = sample_envelope(p, o.seed);
  p.sky_lean = 0.6f;
  const envelope_sample leaning = sample_envelope(p, o.seed);
  ASSERT_EQ(leaning.points.size(), even.points.size());
  auto shaded = [&](const envelope_sample& e) {
    int n = 0;
    for (const glm::vec3& q : e.points) n += q.z < p.offset.z;
    return n;
  };
  EXPECT_LT(shaded(leaning), 0.85 * shaded(even));
  const tree_skeleton t = grow_space_colonization(p, o);
  EXPECT_EQ(validate_skeleton(t), "");
  const glm::vec3 open = open_side_direction(90);
  // The points' centroid moves by about (ψ/2)·E[u²]/(1 − ψ/2)·R = 0.3·0.2/0.7·2 m = 0.17 m towards
  // the open side (E[u²] = 1/5 across a ball), and the crown's wood follows it.
  EXPECT_NEAR(mean_offset(plain, open), 0, 0.1f);
  EXPECT_GT(mean_offset(t, open), mean_offset(plain, open) + 0.12f);
}

TEST(SkyLean, SelfOrganizingShootsLeanTowardsTheOpenSide) {
  self_organizing_params p;
  p.steps = 14;
  grow_options o;
  o.seed = 2;
  const tree_skeleton plain = grow_self_organizing(p, o);
  p.open_side = 180;   // −x
  EXPECT_EQ(grow_self_organizing(p, o).position, plain.position);   // no lean: the azimuth changes nothing
  p.sky_lean = 0.4f;
  const tree_skeleton t = grow_self_organizing(p, o);
  EXPECT_EQ(validate_skeleton(t), "");
  const glm::vec3 open = open_side_direction(180);
  EXPECT_GT(mean_offset(t, open), mean_offset(plain, open) + 0.3f);
  // The top of the tree stands out on the open side.
  size_t top = 0;
  for (size_t i = 0; i < t.size(); ++i)
    if (t.position[i].y > t.position[top].y) top = i;
  EXPECT_GT(glm::dot(t.position[top], open), 0.2f);
}
