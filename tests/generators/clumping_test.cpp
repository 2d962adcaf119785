// Foliage clumping (generators/leaf_clumps.h): clumping 0 is the even placement exactly;
// with clumping the leaves gather in limb masses (a variance-of-counts statistic) and the crown
// occlusion darkens each mass's inside (render/mesh/crown_occlusion.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>

#include <glm/geometric.hpp>

#include "generators/leaf_clumps.h"
#include "generators/leaves.h"
#include "render/mesh/mesh.h"
#include "render/io/preset.h"

using namespace sylva;

namespace {

struct grown {
  preset p;
  tree_skeleton t;
};

const grown& oak() {   // the oak, grown once: a space-colonization crown filled evenly
  static const grown g = [] {
    grown r;
    EXPECT_TRUE(load_preset_file(SYLVA_SOURCE_DIR "/presets/species_oak.json", r.p).ok);
    r.p.mesh.leaves.clumping = 0;
    r.t = grow(r.p.spec, grow_options{});
    return r;
  }();
  return g;
}

// Index of dispersion (variance / mean) of leaf counts over the cells of a grid of `cell` metres
// that hold any leaf-bearing shoot: 1 for a random (Poisson) spread, higher when the leaves clump.
double dispersion(const std::vector<leaf>& leaves, const tree_skeleton& t, float cell) {
  std::map<std::tuple<int, int, int>, int> count;
  auto key = [&](const glm::vec3& x) {
    return std::make_tuple(int(std::floor(x.x / cell)), int(std::floor(x.y / cell)), int(std::floor(x.z / cell)));
  };
  for (const leaf& l : leaves) count[key(t.position[size_t(l.node)])];  // the cells the shoots reach
  for (const leaf& l : leaves) ++count[key(l.position)];
  double sum = 0, sq = 0;
  for (const auto& [k, c] : count) sum += c, sq += double(c) * c;
  const double n = double(count.size()), mean = sum / n;
  return (sq / n - mean * mean) / mean;
}

}  // namespace

TEST(Clumping, ZeroIsTheEvenPlacementExactly) {
  const grown& g = oak();
  leaf_params even = g.p.mesh.leaves;
  leaf_params zero = even;
  zero.clump_size = 3.5f, zero.clump_variation = 1;   // ignored while clumping is 0
  const foliage a = place_shoot_leaves(g.t, even, 7), b = place_shoot_leaves(g.t, zero, 7);
  ASSERT_GT(a.leaves.size(), size_t(1000));
  ASSERT_EQ(a.leaves.size(), b.leaves.size());
  for (size_t k = 0; k < a.leaves.size(); ++k) {
    ASSERT_EQ(a.leaves[k].position, b.leaves[k].position) << k;
    ASSERT_EQ(a.leaves[k].orientation, b.leaves[k].orientation) << k;
    ASSERT_EQ(a.leaves[k].size, b.leaves[k].size) << k;
  }
  const std::vector<float> ones = clump_density(g.t, std::vector<float>(g.t.size(), 1.0f), clump_settings{0, 2, 1}, 7);
  EXPECT_TRUE(std::all_of(ones.begin(), ones.end(), [](float f) { return f == 1.0f; }));
}

TEST(Clumping, LeavesGatherInLimbMassesAndKeepTheirCount) {
  const grown& g = oak();
  leaf_params p = g.p.mesh.leaves;
  const foliage even = place_shoot_leaves(g.t, p, 7);
  p.clumping = 1, p.clump_size = 2;
  const foliage clumped = place_shoot_leaves(g.t, p, 7);
  // The factors are normalised: the count stays within 15 %.
  EXPECT_NEAR(double(clumped.leaves.size()), double(even.leaves.size()), 0.15 * double(even.leaves.size()));
  // Counts per 1 m cell spread much more widely once the leaves gather.
  const double d_even = dispersion(even.leaves, g.t, 1.0f), d_clumped = dispersion(clumped.leaves, g.t, 1.0f);
  EXPECT_GT(d_clumped, 1.3 * d_even) << d_even << " -> " << d_clumped;
  // Every mass is a connected subtree: a node's mass is its parent's, or it starts one.
  const std::vector<int32_t> mass = limb_masses(g.t, 2);
  size_t starts = 0;
  for (size_t i = 0; i < g.t.size(); ++i) {
    const int32_t par = g.t.parent[i];
    if (mass[i] == int32_t(i)) ++starts;
    else if (mass[i] >= 0) {
      ASSERT_EQ(mass[i], mass[size_t(par)]) << i;
    }
  }
  EXPECT_GT(starts, size_t(10));
  EXPECT_EQ(mass[0], -1);   // the trunk is no clump
}

TEST(Clumping, OcclusionDarkensTheInsideOfEachMass) {
  const grown& g = oak();
  mesh_params mp = g.p.mesh;
  mp.leaves.clumping = 1, mp.leaves.clump_size = 2;
  mp.gnarl = 0;   // leaves stay where they were placed
  const tree_mesh m = mesh_tree(g.t, mp);
  ASSERT_GT(m.leaves.size(), size_t(1000));
  const std::vector<int32_t> mass = limb_masses(g.t, 2);
  // Each mass's leaf centroid and rms radius.
  std::vector<glm::vec3> centre(g.t.size(), glm::vec3(0));
  std::vector<double> count(g.t.size(), 0), sq(g.t.size(), 0);
  for (const leaf_instance& l : m.leaves)
    if (mass[l.node] >= 0) centre[size_t(mass[l.node])] += l.position, ++count[size_t(mass[l.node])];
  for (size_t i = 0; i < centre.size(); ++i) if (count[i] > 0) centre[i] /= float(count[i]);
  for (const leaf_instance& l : m.leaves)
    if (mass[l.node] >= 0) sq[size_t(mass[l.node])] += std::pow(glm::length(l.position - centre[size_t(mass[l.node])]), 2);
  glm::vec3 crown(0);
  for (const leaf_instance& l : m.leaves) crown += l.position;
  crown /= float(m.leaves.size());
  // Within each mass: the leaves on its side toward the crown's centre (its inside) against those
  // on the side that faces out of the crown.
  double inner = 0, outer = 0;
  size_t n_inner = 0, n_outer = 0;
  for (const leaf_instance& l : m.leaves) {
    const size_t k = size_t(mass[l.node] >= 0 ? mass[l.node] : 0);
    if (mass[l.node] < 0 || count[k] < 30) continue;
    const glm::vec3 out = glm::normalize(centre[k] - crown);
    const double along = glm::dot(l.position - centre[k], out) / std::sqrt(sq[k] / count[k]);
    if (along < -0.5) inner += l.occlusion, ++n_inner;
    if (along > 0.5) outer += l.occlusion, ++n_outer;
  }
  ASSERT_GT(n_inner, size_t(50));
  ASSERT_GT(n_outer, size_t(50));
  EXPECT_LT(inner / double(n_inner) + 8, outer / double(n_outer));   // at least 8 of 255 darker
  // And the crown's core is darker than the top of its dome.
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const leaf_instance& l : m.leaves) lo = glm::min(lo, l.position), hi = glm::max(hi, l.position);
  const glm::vec3 c = 0.5f * (lo + hi), half = 0.5f * (hi - lo);
  double core = 0, rim = 0;
  size_t n_core = 0, n_rim = 0;
  for (const leaf_instance& l : m.leaves) {
    const float d = glm::length((l.position - c) / half);
    if (d < 0.5f) core += l.occlusion, ++n_core;
    if (d > 0.85f && l.position.y > c.y + 0.5f * half.y) rim += l.occlusion, ++n_rim;   // the dome's top
  }
  ASSERT_GT(n_core, size_t(20));
  EXPECT_LT(core / double(n_core) + 20, rim / double(n_rim));
}

// A long mass is an ellipsoid, not a ball: a 4 m upright leader that forms one limb mass keeps its
// leaves to its tip. With one radius for every axis its top metre fell past the ball's rim, in the
// "gap" between masses, and the poplar's leader stuck out of its crown bare.
TEST(Clumping, ALongMassKeepsItsEndsLeafy) {
  tree_skeleton t;
  int32_t par = t.add_node(glm::vec3(0), -1, 0.01f, 0, 0);
  for (int k = 1; k <= 40; ++k) par = t.add_node(glm::vec3(0, 0.1f * float(k), 0), par, 0.01f, uint16_t(k), 0);
  const std::vector<float> weight(t.size(), 1.0f);
  const std::vector<float> d = clump_density(t, weight, clump_settings{1.0f, 3.0f, 0.0f}, 7);
  ASSERT_EQ(d.size(), t.size());
  EXPECT_EQ(limb_masses(t, 3.0f)[40], 0);  // the whole leader is one mass
  std::vector<float> inner(d.begin() + 1, d.end());
  std::nth_element(inner.begin(), inner.begin() + inner.size() / 2, inner.end());
  const float median = inner[inner.size() / 2];
  ASSERT_GT(median, 0.0f);
  // Both ends lie in the shell: as dense as the median internode, and denser than the centre.
  EXPECT_GE(d[40], 0.9f * median);
  EXPECT_GE(d[1], 0.9f * median);
  EXPECT_GT(d[40], 2.0f * d[20]);
}
