// Bark mesher and leaf instances: counts derived by hand, ring geometry, twist, step tables.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "generators/lsystem.h"
#include "render/mesh.h"

using namespace sylva;

namespace {

// A trunk 0-1-2 straight up and a lateral 3 leaving node 1 sideways.
tree_skeleton small_tree() {
  tree_skeleton t;
  t.add_node({0, 0, 0}, -1, 0.2f, 0, 0);
  t.add_node({0, 1, 0}, 0, 0.15f, 1, 0);
  t.add_node({0, 2, 0}, 1, 0.1f, 2, 0);
  t.add_node({1, 2, 0}, 1, 0.05f, 2, 1);
  t.steps = 2;
  return t;
}

float angle(glm::vec3 a, glm::vec3 b) {
  return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0f, 1.0f));
}

}  // namespace

TEST(Mesh, CountsOfSmallTree) {
  mesh_params p;
  p.radial_segments = 6;
  p.leaves_enabled = false;
  const tree_mesh m = mesh_tree(small_tree(), p);
  // 4 node rings + 1 base ring for the lateral, each 6+1 vertices (seam duplicated).
  EXPECT_EQ(m.position.size(), size_t(5 * 7));
  // 3 internodes of 6 quads = 36 triangles; born at steps 1, 2, 2.
  EXPECT_EQ(m.triangles(), size_t(36));
  ASSERT_EQ(m.index_end.size(), size_t(3));
  EXPECT_EQ(m.index_end[0], 0u);
  EXPECT_EQ(m.index_end[1], 36u);
  EXPECT_EQ(m.index_end[2], 108u);
  EXPECT_EQ(validate_mesh(m), "");
}

TEST(Mesh, RingsSitAtNodeRadius) {
  mesh_params p;
  p.radial_segments = 8;
  const tree_skeleton t = small_tree();
  const tree_mesh m = mesh_tree(t, p);
  // Ring order: nodes 0, 1, 2, then node 3's base ring (centred on node 1), then node 3.
  const glm::vec3 centre[5] = {t.position[0], t.position[1], t.position[2], t.position[1], t.position[3]};
  const float radius[5] = {0.2f, 0.15f, 0.1f, 0.05f, 0.05f};
  for (int r = 0; r < 5; ++r)
    for (int k = 0; k <= 8; ++k) {
      const size_t v = size_t(r * 9 + k);
      EXPECT_NEAR(glm::length(m.position[v] - centre[r]), radius[r], 1e-6f) << "ring " << r;
      EXPECT_NEAR(glm::length(m.normal[v]), 1.0f, 1e-5f);
      // The normal points from the centre to the vertex (smooth radial normals).
      EXPECT_LT(glm::length(m.position[v] - m.normal[v] * m.final_radius[m.node[v]] - centre[r]), 1e-6f);
    }
  // The lateral's base ring lies across the child's direction (1,1,0)/√2, inside the trunk's tube.
  for (int k = 0; k < 8; ++k) EXPECT_NEAR(glm::dot(m.normal[3 * 9 + k], glm::vec3(1, 1, 0)), 0.0f, 1e-6f);
  // Seam vertices coincide; u runs 0..round(2π · 0.2 m · 2) = 3 around the trunk (texel density
  // as along it) and v grows by length * uv_repeat (1 m * 2 here).
  EXPECT_EQ(m.position[9], m.position[9 + 8]);
  EXPECT_FLOAT_EQ(m.uv[9 + 8].x, 3.0f);
  EXPECT_FLOAT_EQ(m.uv[9].y, 2.0f);
  EXPECT_FLOAT_EQ(m.uv[2 * 9].y, 4.0f);
}

TEST(Mesh, TrianglesFaceOutward) {
  mesh_params p;
  p.leaves_enabled = false;
  const tree_mesh m = mesh_tree(small_tree(), p);
  for (size_t k = 0; k < m.index.size(); k += 3) {
    const glm::vec3 a = m.position[m.index[k]], b = m.position[m.index[k + 1]], c = m.position[m.index[k + 2]];
    const glm::vec3 face = glm::cross(b - a, c - a);
    const glm::vec3 n = m.normal[m.index[k]] + m.normal[m.index[k + 1]] + m.normal[m.index[k + 2]];
    EXPECT_GT(glm::dot(face, n), 0.0f) << "triangle " << k / 3;
  }
}

TEST(Mesh, FramesDoNotTwist) {
  // A branch going straight up for 3 internodes, then bending by 20° per node, out of plane too.
  tree_skeleton t;
  glm::vec3 pos(0), d(0, 1, 0);
  t.add_node(pos, -1, 0.1f, 0, 0);
  for (int i = 1; i <= 10; ++i) {
    if (i > 3) d = glm::normalize(d + glm::vec3(0.36f, 0, 0.1f * float(i - 3)));
    pos += d;
    t.add_node(pos, i - 1, 0.1f, uint16_t(i), 0);
  }
  t.steps = 10;
  mesh_params p;
  p.radial_segments = 8;
  const tree_mesh m = mesh_tree(t, p);
  ASSERT_EQ(m.position.size(), size_t(11 * 9));
  for (int r = 0; r + 1 < 11; ++r) {
    const glm::vec3 n0 = m.normal[r * 9], n1 = m.normal[(r + 1) * 9];
    // Ring axes from two normals a quarter turn apart.
    const glm::vec3 t0 = glm::cross(n0, m.normal[r * 9 + 2]), t1 = glm::cross(n1, m.normal[(r + 1) * 9 + 2]);
    // Parallel transport rotates the frame by the axis' turn and no more.
    EXPECT_LE(angle(n0, n1), angle(t0, t1) + 1e-3f) << "ring " << r;
    if (r < 2) {
      EXPECT_LT(angle(n0, n1), 1e-3f);  // straight part: not turned at all
    }
  }
}

TEST(Mesh, StepDrawCountsMatchStepSkeleton) {
  lsystem_params lp;  // tree a, min = 0: derivation k adds 2^(k-1) internodes
  lp.derivations = 6;
  const tree_skeleton t = grow_honda(lp, {});
  mesh_params p;
  p.radial_segments = 5;
  const tree_mesh m = mesh_tree(t, p);
  ASSERT_EQ(validate_mesh(m), "");
  for (int s = 0; s <= 6; ++s) {
    EXPECT_EQ(m.index_end[s], uint32_t(((1u << s) - 1) * 6 * 5)) << "step " << s;
    const tree_mesh ms = mesh_tree(skeleton_at_step(t, s), p);
    EXPECT_EQ(ms.index.size(), size_t(m.index_end[s])) << "step " << s;
    const tree_mesh ma = mesh_tree_at_step(t, m, p, s);
    EXPECT_EQ(ma.index.size(), size_t(m.index_end[s]));
    EXPECT_EQ(validate_mesh(ma), "");
  }
}

TEST(Mesh, SkeletonAtStepDropsShedBranches) {
  tree_skeleton t = small_tree();
  t.add_node({2, 3, 0}, 3, 0.02f, 2, 1);  // node 4 on the lateral
  t.steps = 4;
  t.died[3] = 3;
  t.died[4] = 3;
  t.leaves.push_back({{2, 3, 0}, {1, 0, 0, 0}, 0.1f, 2, 3, 4});
  t.leaves.push_back({{0, 2, 0}, {1, 0, 0, 0}, 0.1f, 2, never_died, 2});
  const tree_skeleton s2 = skeleton_at_step(t, 2), s3 = skeleton_at_step(t, 3);
  EXPECT_EQ(s2.size(), size_t(5));
  EXPECT_EQ(s2.leaves.size(), size_t(2));
  ASSERT_EQ(s3.size(), size_t(3));
  EXPECT_EQ(s3.leaves.size(), size_t(1));
  EXPECT_EQ(s3.leaves[0].node, 2);
  EXPECT_EQ(s3.steps, 3);
  EXPECT_EQ(validate_skeleton(s3), "");
  EXPECT_EQ(validate_skeleton(s2), "");
  // The final view for export leaves the shed lateral out: 2 internodes of 8 quads remain.
  mesh_params p;
  p.leaves.mode = leaf_mode::generator;
  const tree_mesh full = mesh_tree(t, p);
  EXPECT_EQ(full.index.size(), size_t(4 * 8 * 6));
  const tree_mesh last = mesh_tree_at_step(t, full, p, -1);
  EXPECT_EQ(last.index.size(), size_t(2 * 8 * 6));
  ASSERT_EQ(last.leaves.size(), size_t(1));
  EXPECT_EQ(last.leaves[0].node, 2u);
  EXPECT_EQ(validate_mesh(last), "");
}

TEST(Mesh, LeavesScaledSortedAndSeeded) {
  tree_skeleton t = small_tree();
  t.leaves.push_back({{0, 2, 0}, {1, 0, 0, 0}, 0.2f, 2, never_died, 2});
  t.leaves.push_back({{1, 2, 0}, {1, 0, 0, 0}, 0.1f, 1, never_died, 3});
  t.leaves.push_back({{0, 1, 0}, {1, 0, 0, 0}, 0.3f, 0, never_died, 1});
  mesh_params p;
  p.leaves.mode = leaf_mode::generator;
  p.leaf_scale = 2;
  const tree_mesh m = mesh_tree(t, p, 7);
  ASSERT_EQ(m.leaves.size(), size_t(3));
  EXPECT_FLOAT_EQ(m.leaves[0].size, 0.6f);  // born 0 first
  EXPECT_FLOAT_EQ(m.leaves[1].size, 0.2f);
  EXPECT_FLOAT_EQ(m.leaves[2].size, 0.4f);
  EXPECT_EQ(m.leaf_end, (std::vector<uint32_t>{1, 2, 3}));
  const tree_mesh again = mesh_tree(t, p, 7);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(m.leaves[k].texture, uint8_t(leaf_archetype::ovate));   // the mesh's archetype
    EXPECT_EQ(m.leaves[k].texture, again.leaves[k].texture);
  }
  p.leaves_enabled = false;
  EXPECT_TRUE(mesh_tree(t, p).leaves.empty());
  // Without generator leaves, tips get leaves from place_tip_leaves (order >= 1: the lateral).
  t.leaves.clear();
  p.leaves_enabled = true;
  p.leaves.mode = leaf_mode::tips;
  p.leaves.min_order = 1;
  p.leaves.density = 3;
  const tree_mesh tips = mesh_tree(t, p);
  EXPECT_EQ(tips.leaves.size(), size_t(3));
  EXPECT_EQ(validate_mesh(tips), "");
}

TEST(Mesh, BadInputGivesEmptyMeshNotACrash) {
  tree_skeleton t = small_tree();
  t.parent[2] = 5;
  tree_mesh m = mesh_tree(t, {});
  EXPECT_TRUE(m.position.empty());
  EXPECT_EQ(validate_mesh(m), "");
  t = small_tree();
  t.radius.pop_back();
  EXPECT_TRUE(mesh_tree(t, {}).index.empty());
  t = small_tree();
  t.born[3] = 9;  // born after the last step: clamped into the table
  mesh_params p;
  p.radial_segments = 1000;  // clamped
  m = mesh_tree(t, p);
  EXPECT_EQ(validate_mesh(m), "");
  m.index[4] = uint32_t(m.position.size());
  EXPECT_NE(validate_mesh(m), "");
}

TEST(Mesh, BarkTexelDensityIsTheSameOnTrunkAndTwig) {
  // Trunk of radius 0.5 m: circumference 3.14 m, at 2 repeats a metre the texture wraps 6 times;
  // the 5 cm lateral wraps round(0.63) -> at least once. Both keep 2 repeats a metre along.
  tree_skeleton t;
  t.add_node({0, 0, 0}, -1, 0.5f, 0, 0);
  t.add_node({0, 1, 0}, 0, 0.45f, 1, 0);   // continues the trunk: keeps its 6 wraps
  t.add_node({0, 2, 0}, 1, 0.1f, 1, 0);    // still the trunk: 6 wraps though thinner
  t.add_node({1, 1, 0}, 1, 0.05f, 1, 1);   // a lateral: its own count
  t.steps = 1;
  mesh_params p;
  p.radial_segments = 8;
  p.uv_repeat = 2;
  p.leaves_enabled = false;
  const tree_mesh m = mesh_tree(t, p);
  const int stride = 9;
  EXPECT_FLOAT_EQ(m.uv[8].x, 6.0f);               // root ring's seam
  EXPECT_FLOAT_EQ(m.uv[stride + 8].x, 6.0f);      // node 1 continues the axis
  EXPECT_FLOAT_EQ(m.uv[2 * stride + 8].x, 6.0f);  // node 2 too
  EXPECT_FLOAT_EQ(m.uv[m.uv.size() - 1].x, 1.0f); // the lateral's tip ring
  // Texels per metre around: wraps / circumference, within 20% on the trunk's rings.
  EXPECT_NEAR(6.0f / (6.2831853f * 0.5f), 2.0f, 0.2f * 2.0f);
}

TEST(Mesh, CrownOcclusionDarkensTheInsideOfTheCrownOnly) {
  const tree_skeleton t = grow_honda(lsystem_params{}, {});
  tree_mesh m = mesh_tree(t, mesh_params{});
  ASSERT_FALSE(m.leaves.empty());
  ASSERT_EQ(m.occlusion.size(), m.position.size());
  // The trunk's base ring lies below the crown: open sky.
  EXPECT_FLOAT_EQ(m.occlusion[0], 1.0f);
  float lo = 1, hi = 0;
  for (float o : m.occlusion) {
    ASSERT_TRUE(std::isfinite(o));
    lo = std::min(lo, o), hi = std::max(hi, o);
  }
  EXPECT_GE(lo, 0.35f);
  EXPECT_LT(lo, 0.9f);   // something inside the crown is shaded
  // Leaves: the outermost ones see open sky, the innermost are darker.
  int open = 0, shaded = 0;
  for (const leaf_instance& l : m.leaves) open += l.occlusion > 240, shaded += l.occlusion < 200;
  EXPECT_GT(open, 0);
  EXPECT_GT(shaded, 0);
}
