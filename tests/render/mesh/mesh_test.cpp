// Bark mesher and leaf instances: counts derived by hand, ring geometry, twist, step tables.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include <map>
#include <tuple>

#include "generators/lsystem.h"
#include "generators/tree_spec.h"
#include "render/mesh/mesh.h"

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

// The mesher as it was before its shape details: one ring per node, straight tubes, open
// ends, no collar, flare or gnarl. The counts below are derived by hand for it.
mesh_params plain() {
  mesh_params p;
  p.curve_rings = 0;
  p.gnarl = 0;
  p.collar = 0;
  p.flare_strength = 0;
  p.caps = false;
  p.root_depth = 0;   // the foot ring at its node, on the ground
  return p;
}

float angle(glm::vec3 a, glm::vec3 b) {
  return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0f, 1.0f));
}

}  // namespace

TEST(Mesh, CountsOfSmallTree) {
  mesh_params p = plain();
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
  mesh_params p = plain();
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
  mesh_params p = plain();
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
  mesh_params p = plain();
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
  mesh_params p = plain();
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
  // Zero-length internodes and every shape knob at its extreme still give a finite, valid mesh.
  t = small_tree();
  t.position[2] = t.position[1];
  t.add_node(t.position[2], 2, 0.01f, 2, 0);
  p = mesh_params{};
  p.curve_angle = 2;
  p.curve_rings = 8;
  p.detail_budget = 4;
  p.gnarl = 30;
  p.twist = 45;
  p.collar = 1;
  p.collar_length = 8;
  p.collar_min_radius = 0.0001f;
  p.flare_strength = 2;
  p.flare_height = 3;
  p.flare_lobes = 6;
  EXPECT_EQ(validate_mesh(mesh_tree(t, p)), "");
  p.curve_angle = std::nanf("");
  p.gnarl = std::nanf("");
  p.detail_budget = std::nanf("");
  p.flare_strength = INFINITY;
  EXPECT_EQ(validate_mesh(mesh_tree(t, p)), "");
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
  mesh_params p = plain();
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
  // The trunk's base ring lies below the crown: nearly open sky (the lowest leaves are within the
  // local sky's reach of it, render/mesh/crown_occlusion.cpp).
  EXPECT_GT(m.occlusion[0], 0.95f);
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

// ---- Issue 12: shape details (curves, gnarl, twist, collars, root flare, caps) ----

namespace {

// Edges used by one triangle only, once vertices at the same place are welded (the UV seam and a
// cap's apex ring are duplicated vertices): the open borders of the surface.
size_t open_edges(const tree_mesh& m) {
  std::map<std::tuple<float, float, float>, uint32_t> weld;
  std::vector<uint32_t> id(m.position.size());
  for (size_t v = 0; v < m.position.size(); ++v) {
    const glm::vec3 q = glm::round(m.position[v] * 1e5f);
    id[v] = weld.emplace(std::make_tuple(q.x, q.y, q.z), uint32_t(weld.size())).first->second;
  }
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (size_t k = 0; k < m.index.size(); k += 3)
    for (int e = 0; e < 3; ++e) {
      const uint32_t a = id[m.index[k + e]], b = id[m.index[k + (e + 1) % 3]];
      if (a != b) ++uses[std::minmax(a, b)];
    }
  size_t open = 0;
  for (const auto& [edge, count] : uses) open += count == 1;
  return open;
}

// A trunk that zig-zags by ±30° at every node, as guiding-vector and space-colonization axes do.
tree_skeleton zigzag(int nodes) {
  tree_skeleton t;
  glm::vec3 pos(0);
  t.add_node(pos, -1, 0.05f, 0, 0);
  for (int i = 1; i <= nodes; ++i) {
    const float side = (i % 2 ? 1.0f : -1.0f) * 0.5f;   // ±30° from vertical (tan 30° ≈ 0.58)
    pos += glm::normalize(glm::vec3(side, 0.87f, 0)) * 0.3f;
    t.add_node(pos, i - 1, 0.05f - 0.003f * float(i), uint16_t(i), 0);
  }
  t.steps = nodes;
  return t;
}

// The sharpest kink of the centre line through consecutive rings of a single-axis mesh.
float sharpest_kink(const tree_mesh& m) {
  const size_t stride = size_t(m.radial_segments) + 1;
  std::vector<glm::vec3> c;
  for (size_t r = 0; r < m.position.size() / stride; ++r) {
    glm::vec3 sum(0);
    for (size_t k = 0; k + 1 < stride; ++k) sum += m.position[r * stride + k];
    c.push_back(sum / float(stride - 1));
  }
  float worst = 0;
  for (size_t r = 1; r + 1 < c.size(); ++r) worst = std::max(worst, angle(c[r] - c[r - 1], c[r + 1] - c[r]));
  return worst;
}

}  // namespace

TEST(MeshShape, CurvedAxisPassesThroughNodesAndTurnsGently) {
  const tree_skeleton t = zigzag(12);
  mesh_params p = plain();
  p.radial_segments = 8;
  const tree_mesh straight = mesh_tree(t, p);
  p.curve_rings = 2;
  p.curve_angle = 12;
  p.detail_budget = 4;   // no budget cut here
  const tree_mesh curved = mesh_tree(t, p);
  ASSERT_EQ(validate_mesh(curved), "");
  // A ±30° zig-zag turns each internode's curve by about 30°: two rings inserted in each of the
  // 11 inner internodes (the first leaves the upright root, the last ends straight).
  EXPECT_GT(curved.position.size(), straight.position.size());
  EXPECT_LE(curved.position.size(), straight.position.size() + 2 * 12 * 9);
  // The polyline's centre line kinks by the joint angle (60°) at every node; the curve's, with
  // its rings where it turns most, by about half that.
  EXPECT_GT(sharpest_kink(straight), glm::radians(55.0f));
  EXPECT_LT(sharpest_kink(curved), glm::radians(36.0f));
  std::printf("zig-zag: sharpest kink %.1f° as a polyline, %.1f° curved\n", glm::degrees(sharpest_kink(straight)),
              glm::degrees(sharpest_kink(curved)));
  // The budget keeps the rings where the tube is widest (near the base) when it runs out.
  p.detail_budget = 1.25f;   // 12 internodes: 3 spare rings
  const tree_mesh cut = mesh_tree(t, p);
  EXPECT_EQ(cut.position.size(), straight.position.size() + 3 * 9);
  // The curve passes through the nodes: every node's own ring is centred on it.
  for (size_t i = 0; i < t.size(); ++i) {
    glm::vec3 c(0);
    size_t count = 0, last = 0;
    for (size_t v = 0; v < curved.node.size(); ++v)
      if (curved.node[v] == i) last = v;
    for (size_t v = last + 1 - 9; v < last; ++v) c += curved.position[v], ++count;  // its node ring is its last
    EXPECT_LT(glm::length(c / float(count) - t.position[i]), 1e-4f) << "node " << i;
  }
  // Inserted rings belong to the internode's child, so scrubbing hides and shrinks them with it.
  for (size_t k = 0; k < curved.index.size(); ++k)
    EXPECT_GE(int(t.born[curved.node[curved.index[k]]]), 0);
  for (int s = 0; s <= t.steps; ++s)
    for (uint32_t k = 0; k < curved.index_end[s]; ++k)
      ASSERT_LE(int(t.born[curved.node[curved.index[k]]]), s) << "step " << s;
}

TEST(MeshShape, DefaultShapeStaysWithinTriangleBudgetForEachGenerator) {
  // Issue 12's budget: at default settings at most 1.5x the bark triangles of one ring per node,
  // on the default tree of each generator.
  for (int g = 0; g < generator_count; ++g) {
    tree_spec spec;
    spec.params = default_params(g);
    const tree_skeleton t = grow(spec, grow_options{});
    mesh_params before = plain(), now;
    before.leaves_enabled = now.leaves_enabled = false;
    const tree_mesh a = mesh_tree(t, before), b = mesh_tree(t, now);
    ASSERT_GT(a.triangles(), 0u);
    EXPECT_EQ(validate_mesh(b), "");
    const double ratio = double(b.triangles()) / double(a.triangles());
    EXPECT_LE(ratio, 1.5) << generator_names[g] << ": " << a.triangles() << " -> " << b.triangles();
    std::printf("%s: %zu nodes, bark triangles %zu -> %zu (x%.3f)\n", generator_names[g], t.size(), a.triangles(),
                b.triangles(), ratio);
  }
}

TEST(MeshShape, CapsCloseEveryTubeEnd) {
  mesh_params p = plain();
  p.radial_segments = 6;
  const tree_skeleton t = small_tree();
  const tree_mesh open = mesh_tree(t, p);
  p.caps = true;
  const tree_mesh closed = mesh_tree(t, p);
  ASSERT_EQ(validate_mesh(closed), "");
  // Two tips and the trunk's foot, 6 triangles each; their apex rings add 3 rings of 7 vertices.
  EXPECT_EQ(closed.triangles(), open.triangles() + 3 * 6);
  EXPECT_EQ(closed.position.size(), open.position.size() + 3 * 7);
  // Open borders: without caps the foot, two tips and the lateral's base ring (6 edges each).
  // With caps only the lateral's base ring is left, sunk inside the trunk.
  EXPECT_EQ(open_edges(open), size_t(4 * 6));
  EXPECT_EQ(open_edges(closed), size_t(6));
  // A tip's apex sits one tip radius beyond it; the foot's cap lies flat in the base ring.
  EXPECT_NEAR(closed.position.back().x, 1.0f + 0.05f / std::sqrt(2.0f), 1e-5f);
  for (size_t k = 0; k < closed.index.size(); k += 3) {   // and every face looks outward
    const glm::vec3 a = closed.position[closed.index[k]], b = closed.position[closed.index[k + 1]],
                    c = closed.position[closed.index[k + 2]];
    const glm::vec3 n = closed.normal[closed.index[k]] + closed.normal[closed.index[k + 1]] + closed.normal[closed.index[k + 2]];
    EXPECT_GT(glm::dot(glm::cross(b - a, c - a), n), 0.0f) << "triangle " << k / 3;
  }
  // A cap is born with its tip: step 1 draws the trunk's first internode and the foot only.
  EXPECT_EQ(closed.index_end[0], uint32_t(6 * 3));
  EXPECT_EQ(closed.index_end[1], uint32_t(6 * 3 + 6 * 6));
}

TEST(MeshShape, DefaultMeshOfGrownTreesIsClosedAndOutward) {
  lsystem_params lp;
  lp.derivations = 5;
  const tree_skeleton t = grow_honda(lp, {});
  mesh_params p;
  p.leaves_enabled = false;
  const tree_mesh m = mesh_tree(t, p);
  ASSERT_EQ(validate_mesh(m), "");
  // Only the laterals' base rings, sunk in their parents, stay open: seg edges per lateral.
  size_t laterals = 0;
  std::vector<int> children(t.size(), 0);
  for (size_t i = 1; i < t.size(); ++i) ++children[size_t(t.parent[i])];
  for (int c : children) laterals += c > 1 ? size_t(c - 1) : 0;
  EXPECT_EQ(open_edges(m), laterals * size_t(p.radial_segments));
  size_t inward = 0;
  for (size_t k = 0; k < m.index.size(); k += 3) {
    const glm::vec3 a = m.position[m.index[k]], b = m.position[m.index[k + 1]], c = m.position[m.index[k + 2]];
    const glm::vec3 n = m.normal[m.index[k]] + m.normal[m.index[k + 1]] + m.normal[m.index[k + 2]];
    inward += glm::dot(glm::cross(b - a, c - a), n) <= 0;
  }
  EXPECT_EQ(inward, 0u);
  for (int s = 0; s <= t.steps; ++s)
    for (uint32_t k = 0; k < m.index_end[s]; ++k) ASSERT_LE(int(t.born[m.node[m.index[k]]]), s);
}

TEST(MeshShape, LateralCollarSwellsAndBlendsIntoItsParent) {
  // The junction of small_tree: a trunk of radius 0.15 m at node 1 and a lateral of 0.05 m at 45°.
  const tree_skeleton t = small_tree();
  mesh_params p = plain();
  p.radial_segments = 8;
  p.collar = 0.4f;
  p.collar_length = 2;
  p.collar_min_radius = 0.01f;
  p.detail_budget = 4;
  const tree_mesh m = mesh_tree(t, p);
  ASSERT_EQ(validate_mesh(m), "");
  // The lateral's rings, base first: each ring's centre and mean radius.
  const size_t stride = 9;
  std::vector<glm::vec3> centre;
  std::vector<float> radius;
  for (size_t v = 0; v < m.position.size(); v += stride) {
    if (m.node[v] != 3) continue;
    glm::vec3 c(0);
    for (size_t k = 0; k < 8; ++k) c += m.position[v + k];
    c /= 8.0f;
    float r = 0;
    for (size_t k = 0; k < 8; ++k) r += glm::length(m.position[v + k] - c) / 8.0f;
    centre.push_back(c), radius.push_back(r);
  }
  // Base ring (swollen, sunk in the trunk), the ring where the swell has faded, tip ring.
  ASSERT_EQ(centre.size(), size_t(3));
  // No gap: the base ring lies wholly inside the trunk (distance to the trunk's axis x = z = 0).
  for (size_t k = 0; k < 8; ++k) {
    const glm::vec3 v = m.position[k + 3 * stride];
    EXPECT_LT(std::hypot(v.x, v.z), 0.15f) << "base vertex " << k;
  }
  EXPECT_NEAR(radius[0], 0.05f * 1.4f, 1e-4f);
  // The fade ring lies wholly outside the trunk's bark, at the lateral's own radius...
  for (size_t k = 0; k < 8; ++k) {
    const glm::vec3 v = m.position[k + 4 * stride];
    EXPECT_GT(std::hypot(v.x, v.z), 0.15f) << "fade vertex " << k;
  }
  EXPECT_NEAR(radius[1], 0.05f, 1e-4f);
  EXPECT_NEAR(radius[2], 0.05f, 1e-4f);
  // ... so where the lateral's axis leaves the bark (x = 0.15, 0.212 m along it) it is swollen,
  // and it narrows without a step from the base to the fade ring (one tube, no seam).
  const float along = glm::length(centre[1] - centre[0]), at_bark = 0.15f * std::sqrt(2.0f);
  ASSERT_GT(along, at_bark);
  const float swollen = radius[0] + (radius[1] - radius[0]) * (at_bark / along);
  EXPECT_GT(swollen, 0.05f * 1.1f);
  EXPECT_LE(radius[0], 0.15f);   // never wider than the parent
  // No inward face anywhere on the junction.
  for (size_t k = 0; k < m.index.size(); k += 3) {
    const glm::vec3 a = m.position[m.index[k]], b = m.position[m.index[k + 1]], c = m.position[m.index[k + 2]];
    const glm::vec3 n = m.normal[m.index[k]] + m.normal[m.index[k + 1]] + m.normal[m.index[k + 2]];
    EXPECT_GT(glm::dot(glm::cross(b - a, c - a), n), 0.0f) << "triangle " << k / 3;
  }
  // Laterals thinner than collar_min_radius keep a plain tube.
  p.collar_min_radius = 0.06f;
  EXPECT_EQ(mesh_tree(t, p).position.size(), size_t(5 * stride));
}

TEST(MeshShape, RootFlareHasLobesAndMeetsTheGround) {
  // A 0.3 m trunk standing on the ground, 4 m tall in 0.5 m internodes.
  tree_skeleton t;
  t.add_node({0, 0, 0}, -1, 0.3f, 0, 0);
  for (int i = 1; i <= 8; ++i) t.add_node({0, 0.5f * float(i), 0}, i - 1, 0.3f - 0.02f * float(i), uint16_t(i), 0);
  t.steps = 8;
  mesh_params p = plain();
  p.radial_segments = 24;
  p.flare_lobes = 5;
  p.flare_height = 1;
  p.flare_strength = 0.6f;
  const tree_mesh m = mesh_tree(t, p);
  ASSERT_EQ(validate_mesh(m), "");
  const size_t stride = 25;
  // The base ring lies flat on the ground, with 5 lobes reaching 1.6x the trunk's radius.
  int peaks = 0;
  float lo = 1e9f, hi = 0;
  for (int k = 0; k < 24; ++k) {
    EXPECT_NEAR(m.position[size_t(k)].y, 0.0f, 1e-6f);
    const auto rad = [&](int j) { return std::hypot(m.position[size_t((j + 24) % 24)].x, m.position[size_t((j + 24) % 24)].z); };
    peaks += rad(k) > rad(k - 1) && rad(k) >= rad(k + 1);
    lo = std::min(lo, rad(k)), hi = std::max(hi, rad(k));
  }
  EXPECT_EQ(peaks, 5);
  EXPECT_NEAR(hi, 0.3f * 1.6f, 0.01f);
  EXPECT_GT(lo, 0.3f * 1.1f);   // a fifth of the swell all round
  {
    // With a root depth the same lobed ring sits that far below the ground.
    mesh_params deep = p;
    deep.root_depth = 0.1f;
    const tree_mesh sunk = mesh_tree(t, deep);
    for (int k = 0; k < 24; ++k) {
      EXPECT_NEAR(sunk.position[size_t(k)].y, -0.1f, 1e-6f);
      EXPECT_NEAR(std::hypot(sunk.position[size_t(k)].x, sunk.position[size_t(k)].z),
                  std::hypot(m.position[size_t(k)].x, m.position[size_t(k)].z), 1e-5f);
    }
  }
  // Rings above the flare's height are round again, at their node's radius.
  for (size_t v = 0; v < m.position.size(); ++v)
    if (m.position[v].y > 1.01f) {
      const float r = std::hypot(m.position[v].x, m.position[v].z);
      EXPECT_LE(r, 0.3f * 1.0001f);
    }
  // Rings were added up the flare (at 0.1, 0.25, 0.45, 0.7 m) to shape it.
  EXPECT_EQ(m.position.size(), (9 + 4) * stride);
  // A thin trunk's flare stays within 6 radii of the ground.
  for (float& r : t.radius) r *= 0.1f;
  const tree_mesh thin = mesh_tree(t, p);
  for (size_t v = 0; v < thin.position.size(); ++v)
    if (thin.position[v].y > 6 * 0.03f + 1e-4f) {
      EXPECT_LE(std::hypot(thin.position[v].x, thin.position[v].z), 0.03f * 1.0001f);
    }
  // Rings too coarse for three lobes (a reduced level of detail) flare round instead.
  p.radial_segments = 4;
  const tree_mesh coarse = mesh_tree(t, p);
  for (int k = 0; k < 4; ++k)
    EXPECT_NEAR(std::hypot(coarse.position[size_t(k)].x, coarse.position[size_t(k)].z),
                std::hypot(coarse.position[0].x, coarse.position[0].z), 1e-6f);
  // Faces stay outward on the lobes.
  for (size_t k = 0; k < m.index.size(); k += 3) {
    const glm::vec3 a = m.position[m.index[k]], b = m.position[m.index[k + 1]], c = m.position[m.index[k + 2]];
    const glm::vec3 n = m.normal[m.index[k]] + m.normal[m.index[k + 1]] + m.normal[m.index[k + 2]];
    EXPECT_GT(glm::dot(glm::cross(b - a, c - a), n), 0.0f) << "triangle " << k / 3;
  }
}

TEST(MeshShape, GnarlIsSeededByTheTreeAndCarriesLeaves) {
  lsystem_params lp;
  lp.derivations = 6;
  tree_skeleton t = grow_honda(lp, {});
  mesh_params p = plain();
  p.leaves.mode = leaf_mode::shoots;
  const tree_mesh smooth = mesh_tree(t, p);
  p.gnarl = 8;
  const tree_mesh a = mesh_tree(t, p), b = mesh_tree(t, p, 99);
  ASSERT_EQ(validate_mesh(a), "");
  ASSERT_EQ(a.position.size(), smooth.position.size());
  EXPECT_EQ(a.position, b.position);   // the same tree, the same gnarl, whatever the leaf seed
  float moved = 0;
  for (size_t v = 0; v < a.position.size(); ++v) moved = std::max(moved, glm::length(a.position[v] - smooth.position[v]));
  EXPECT_GT(moved, 0.01f);
  // Each internode turns by at most gnarl x 2.5 (order scale), so its length is kept.
  const std::vector<glm::vec3> rot = gnarl_rotations(t, p), disp = gnarl_offsets(t, gnarl_turns(rot));
  for (size_t i = 1; i < t.size(); ++i) {
    const int32_t par = t.parent[i];
    EXPECT_LE(glm::length(rot[i]), glm::radians(8.0f * 2.5f) + 1e-5f);
    EXPECT_NEAR(glm::length(t.position[i] + disp[i] - t.position[par] - disp[par]), glm::length(t.position[i] - t.position[par]), 1e-4f);
  }
  // This step's shoots are not turned (age 0); the seedling's wood is.
  for (size_t i = 1; i < t.size(); ++i)
    if (t.born[i] == t.steps) {
      EXPECT_EQ(glm::length(rot[i]), 0.0f);
    }
  // Leaves keep their distance to their internode's (gnarled) segment.
  ASSERT_EQ(a.leaves.size(), smooth.leaves.size());
  auto dist = [](glm::vec3 x, glm::vec3 s0, glm::vec3 s1) {
    const glm::vec3 d = s1 - s0;
    const float f = std::clamp(glm::dot(x - s0, d) / std::max(glm::dot(d, d), 1e-12f), 0.0f, 1.0f);
    return glm::length(x - s0 - d * f);
  };
  for (size_t k = 0; k < a.leaves.size(); ++k) {
    const uint32_t i = a.leaves[k].node;
    const int32_t par = t.parent[i];
    if (par < 0) continue;
    const float before = dist(smooth.leaves[k].position, t.position[par], t.position[i]);
    const float after = dist(a.leaves[k].position, t.position[par] + disp[par], t.position[i] + disp[i]);
    EXPECT_NEAR(after, before, 1e-4f) << "leaf " << k;
  }
  // An export of an earlier step re-meshes that step's tree: its leaves follow that step's gnarl.
  const int step = 4;
  const tree_mesh at = mesh_tree_at_step(t, a, p, step);
  const tree_skeleton s = skeleton_at_step(t, step);
  const std::vector<glm::vec3> ds = gnarl_offsets(s, gnarl_turns(gnarl_rotations(s, p)));
  ASSERT_EQ(validate_mesh(at), "");
  // Pair each leaf of the step's export with the smooth mesh's leaf alive then (same order).
  size_t j = 0;
  for (const leaf_instance& l0 : smooth.leaves) {
    if (!(l0.born <= step && step < l0.died)) continue;
    ASSERT_LT(j, at.leaves.size());
    const leaf_instance& l = at.leaves[j++];
    const int32_t par0 = t.parent[l0.node], par = s.parent[l.node];
    if (par0 < 0) continue;
    const float before = dist(l0.position, t.position[size_t(par0)], t.position[l0.node]);
    const float after = dist(l.position, s.position[size_t(par)] + ds[size_t(par)], s.position[l.node] + ds[l.node]);
    EXPECT_NEAR(after, before, 1e-4f) << "leaf " << j;
  }
  EXPECT_EQ(j, at.leaves.size());
}

TEST(MeshShape, TwistLeansTheBarkTextureAlongTheAxis) {
  const tree_skeleton t = small_tree();
  mesh_params p = plain();
  p.radial_segments = 8;
  p.uv_repeat = 2;
  const tree_mesh straight = mesh_tree(t, p);
  p.twist = 10;
  const tree_mesh twisted = mesh_tree(t, p);
  // Node 1's ring: v = 2 (1 m at 2 repeats a metre): u moves by v * tan(10°) texture units.
  for (int k = 0; k <= 8; ++k) {
    EXPECT_FLOAT_EQ(twisted.uv[9 + k].y, straight.uv[9 + k].y);
    EXPECT_NEAR(twisted.uv[9 + k].x - straight.uv[9 + k].x, 2.0f * std::tan(glm::radians(10.0f)), 1e-5f);
  }
  EXPECT_EQ(twisted.uv[0], straight.uv[0]);   // the base is not turned
}
