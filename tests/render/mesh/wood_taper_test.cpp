// Wood that reads as wood: every axis of every species tapers from base to tip by the
// pipe model with disused pipes, a lateral is thinner than its parent where it leaves it, the trunk
// stands in the ground with its flare, and the oak and the pine fork sympodially.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "generators/skeleton.h"
#include "generators/space_colonization.h"
#include "generators/tree_spec.h"
#include "render/io/export.h"
#include "render/mesh/mesh.h"
#include "render/io/preset.h"
#include "tests/fixtures.h"
#include "tests/scratch_dir.h"

using namespace sylva;
namespace fs = std::filesystem;

namespace {

const char* const species[] = {"oak",    "maple",  "beech", "birch",   "ash",  "poplar",  "willow", "pine",
                               "spruce", "fir",    "cedar", "cypress", "palm", "sapling", "bush"};
// The species whose presets set the disused-pipe taper (pipe_taper): along every axis of two or more
// internodes the tip is clearly thinner than the base. The others have the plain pipe model, where
// an axis with no lateral keeps one radius (their owners may turn pipe_taper on).
const char* const tapered[] = {"oak", "pine", "spruce", "fir", "cedar", "cypress", "willow", "palm"};

preset load(const std::string& name) { return sylva_test::shipped_preset("species_" + name); }

// The child continuing each node's axis: the same order first, then the widest (the mesher's rule
// picks the same order first, then the most aligned; for the radii the widest is the stricter).
std::vector<int32_t> continuations(const tree_skeleton& t, const std::vector<float>& r) {
  std::vector<int32_t> cont(t.size(), -1);
  for (size_t i = 0; i < t.size(); ++i) {
    const int32_t par = t.parent[i];
    if (par < 0 || !(r[i] > 0)) continue;   // a shed child continues nothing
    const int32_t c = cont[size_t(par)];
    const bool same = t.order[i] == t.order[size_t(par)];
    if (c < 0 || (same && t.order[size_t(c)] != t.order[size_t(par)]) ||
        (same == (t.order[size_t(c)] == t.order[size_t(par)]) && r[i] > r[size_t(c)]))
      cont[size_t(par)] = int32_t(i);
  }
  return cont;
}

struct axis_stats {
  int axes = 0, long_axes = 0, growing = 0, laterals = 0, thick_laterals = 0;
  int under_tapered = 0;        // axes thinner at the tip than the taper promises, by less than 1e-4
  float worst_long_ratio = 0;   // largest tip/base over axes of 3 m or more
};

axis_stats measure(const tree_skeleton& t) {
  const std::vector<float> r = t.pipe_exponent > 0 ? radii_at_step(t, t.steps) : t.radius;
  const std::vector<int32_t> cont = continuations(t, r);
  axis_stats s;
  for (size_t i = 0; i < t.size(); ++i) {
    const int32_t par = t.parent[i];
    if (!(r[i] > 0)) continue;   // shed by the final step: no wood to measure
    const bool starts = par < 0 || cont[size_t(par)] != int32_t(i);
    if (!starts) continue;
    ++s.axes;
    // The base of an axis: a root's own radius, or a lateral's radius where it leaves its parent.
    const float base = par < 0 ? r[i] : r[i] * pipe_taper_factor(t, i);
    if (par >= 0) {
      ++s.laterals;
      if (!(base < r[size_t(par)])) ++s.thick_laterals;
    }
    // Down the axis: never wider toward the tip, and at least the disused-pipe taper of each
    // internode, (1 + τℓ) per internode (skeleton.h).
    size_t k = i;
    float prev = base, promise = par < 0 ? 1.0f : 1.0f / pipe_taper_factor(t, i), length = 0;
    if (par >= 0) length += glm::length(t.position[i] - t.position[size_t(par)]);
    while (true) {
      if (r[k] > prev * (1 + 1e-5f)) { ++s.growing; break; }
      prev = r[k];
      if (cont[k] < 0 || !(r[size_t(cont[k])] > 0)) break;
      k = size_t(cont[k]);
      promise /= pipe_taper_factor(t, k);
      length += glm::length(t.position[k] - t.position[size_t(t.parent[k])]);
    }
    if (r[k] / base > promise * (1 + 1e-4f)) ++s.under_tapered;
    if (length >= 3) {
      ++s.long_axes;
      s.worst_long_ratio = std::max(s.worst_long_ratio, r[k] / base);
    }
  }
  return s;
}

}  // namespace

TEST(WoodTaper, EveryAxisOfEverySpeciesTapersAndNoLateralIsAsThickAsItsParent) {
  for (const char* name : species) {
    SCOPED_TRACE(name);
    const preset p = load(name);
    const tree_skeleton t = grow(p.spec, {});
    const axis_stats s = measure(t);
    ASSERT_GT(s.axes, 1);
    EXPECT_EQ(s.growing, 0) << "axes whose radius grows toward the tip";
    // No whorl of equal tubes: every lateral is thinner than its parent at the junction.
    EXPECT_EQ(s.thick_laterals, 0) << "of " << s.laterals << " laterals";
    const bool has_taper = std::find_if(std::begin(tapered), std::end(tapered),
                                        [&](const char* n) { return std::string(n) == name; }) != std::end(tapered);
    if (has_taper) {
      EXPECT_GT(t.pipe_taper, 0.0f);
      EXPECT_EQ(s.under_tapered, 0);
      ASSERT_GT(s.long_axes, 0);
      EXPECT_LT(s.worst_long_ratio, 0.9f) << "an axis of 3 m or more barely tapers";
    }
  }
}

TEST(WoodTaper, TheTrunkFallsContinuouslyFromBaseToTip) {
  for (const char* name : tapered) {
    SCOPED_TRACE(name);
    const preset p = load(name);
    const tree_skeleton t = grow(p.spec, {});
    const std::vector<float> r = radii_at_step(t, t.steps);
    const std::vector<int32_t> cont = continuations(t, r);
    // Down the trunk every internode is strictly thinner at its tip than at its base.
    size_t k = 0, steps = 0;
    while (cont[k] >= 0) {
      const size_t c = size_t(cont[k]);
      EXPECT_LT(r[c], r[k]) << "node " << c;
      k = c;
      ++steps;
    }
    ASSERT_GT(steps, 0u);
    EXPECT_LT(r[k] / r[0], 0.25f) << "the leader's tip against the trunk's base";
  }
}

TEST(WoodTaper, TaperIsAParameterAndZeroIsThePlainPipeModel) {
  tree_skeleton t;
  t.add_node({0, 0, 0}, -1, 0, 0, 0);
  t.add_node({0, 2, 0}, 0, 0, 0, 0);
  t.add_node({0, 3, 0}, 1, 0, 0, 0);
  apply_pipe_radii(t, 2, 0.01f, 0);
  EXPECT_FLOAT_EQ(t.radius[0], 0.01f);
  EXPECT_FLOAT_EQ(t.radius[2], 0.01f);
  apply_pipe_radii(t, 2, 0.01f, 0.1f);
  // Internode 1->2 is 1 m: node 1 is 1.1 r_tip; internode 0->1 is 2 m: the root is 1.2 x that.
  EXPECT_FLOAT_EQ(t.radius[2], 0.01f);
  EXPECT_NEAR(t.radius[1], 0.011f, 1e-6f);
  EXPECT_NEAR(t.radius[0], 0.0132f, 1e-6f);
  EXPECT_NEAR(pipe_taper_factor(t, 1), 1.2f, 1e-6f);
  // The per-step view recomputes the same taper.
  EXPECT_NEAR(radii_at_step(t, 0)[0], 0.0132f, 1e-6f);
}

TEST(WoodTaper, TheTrunkStandsInTheGroundWithItsFlareInEveryExport) {
  const sylva_test::scratch_dir scratch("sylva_wood_taper");
  const fs::path& dir = scratch.dir;
  for (const char* name : {"oak", "pine", "palm"}) {
    SCOPED_TRACE(name);
    const preset p = load(name);
    const tree_skeleton t = grow(p.spec, {});
    const tree_mesh m = mesh_tree(t, p.mesh);
    ASSERT_EQ(validate_mesh(m), "");
    // The bark reaches below the ground, by the root depth.
    EXPECT_LT(m.bounds_min.y, -0.5f * p.mesh.root_depth);
    // The flare widens the base: the widest bark at ground level against the trunk's radius above
    // the flare.
    float ground = 0;
    const float trunk_r = m.final_radius[0];
    for (const glm::vec3& v : m.position)
      if (std::abs(v.y) < 0.15f) ground = std::max(ground, std::hypot(v.x, v.z));
    // (With 8 ring vertices the lobes are undersampled: the ring's widest vertex swells by at least
    // 0.4 of the flare strength, where the lobes fall between vertices.)
    EXPECT_GT(ground, (1 + 0.3f * p.mesh.flare_strength) * trunk_r) << "flare at the ground";
    // The exports carry it: the GLB's bark POSITION minimum and the OBJ's lowest vertex are below 0.
    export_info info{generator_name(p.spec), 1};
    export_options eo;
    apply_render_params(eo, p.render);
    const std::string glb = (dir / (std::string(name) + ".glb")).string(), obj = (dir / (std::string(name) + ".obj")).string();
    ASSERT_EQ(export_tree(t, m, info, glb, eo).error, "");
    ASSERT_EQ(export_tree(t, m, info, obj, eo).error, "");
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, glb)) << err;
    double bark_min = 1e30;
    for (const tinygltf::Mesh& mesh : model.meshes)
      for (const tinygltf::Primitive& prim : mesh.primitives) {
        const auto it = prim.attributes.find("POSITION");
        if (it == prim.attributes.end()) continue;
        const tinygltf::Accessor& a = model.accessors[size_t(it->second)];
        if (a.minValues.size() == 3) bark_min = std::min(bark_min, a.minValues[1]);
      }
    EXPECT_LT(bark_min, -0.5 * p.mesh.root_depth);
    FILE* f = std::fopen(obj.c_str(), "r");
    ASSERT_NE(f, nullptr);
    char line[512];
    double obj_min = 1e30;
    while (std::fgets(line, sizeof line, f)) {
      double x, y, z;
      if (line[0] == 'v' && line[1] == ' ' && std::sscanf(line + 2, "%lf %lf %lf", &x, &y, &z) == 3) obj_min = std::min(obj_min, y);
    }
    std::fclose(f);
    EXPECT_LT(obj_min, -0.5 * p.mesh.root_depth);
  }
}

TEST(WoodTaper, ARootDepthOfZeroLeavesTheFootOnTheGround) {
  const preset p = load("oak");
  const tree_skeleton t = grow(p.spec, {});
  mesh_params mp = p.mesh;
  mp.root_depth = 0;
  mp.leaves_enabled = false;
  const tree_mesh m = mesh_tree(t, mp);
  EXPECT_NEAR(m.bounds_min.y, 0.0f, 1e-4f);
}

TEST(WoodTaper, SympodialForksStopTheApexAndTwoShootsTakeOver) {
  space_colonization_params p;
  p.points = 1500;
  p.size = {8, 5, 8};
  p.offset = {0, 5, 0};
  p.trunk_length = 2;
  p.segment_length = 0.25f;
  p.influence_radius = 2.5f;
  p.kill_distance = 0.5f;
  grow_options o;
  const tree_skeleton plain = grow_space_colonization(p, o);
  p.fork_length = 1.5f;
  p.fork_angle = 60;
  p.crook = 20;
  p.bud_life = 6;
  const tree_skeleton forked = grow_space_colonization(p, o);
  ASSERT_EQ(validate_skeleton(forked), "");
  // The trunk's apex forks: the top node of the trunk has two children that diverge widely.
  auto children_of_trunk_top = [](const tree_skeleton& t, float& spread) {
    size_t k = 0;
    std::vector<int32_t> kids;
    while (true) {
      kids.clear();
      for (size_t i = k + 1; i < t.size(); ++i)
        if (t.parent[i] == int32_t(k)) kids.push_back(int32_t(i));
      if (kids.size() != 1) break;
      k = size_t(kids[0]);
    }
    spread = 0;
    for (int32_t a : kids)
      for (int32_t b : kids) {
        const glm::vec3 da = glm::normalize(t.position[size_t(a)] - t.position[k]);
        const glm::vec3 db = glm::normalize(t.position[size_t(b)] - t.position[k]);
        spread = std::max(spread, std::acos(std::clamp(glm::dot(da, db), -1.0f, 1.0f)));
      }
    return kids.size();
  };
  float spread = 0;
  EXPECT_GE(children_of_trunk_top(forked, spread), 2u);
  EXPECT_GT(glm::degrees(spread), 35.0f);
  // The fork and bud life leave fewer limbs on the trunk than Runions' plain model grows there.
  auto trunk_laterals = [](const tree_skeleton& t) {
    int n = 0;
    for (size_t i = 1; i < t.size(); ++i) n += t.order[size_t(t.parent[i])] == 0 && t.order[i] == 1;
    return n;
  };
  EXPECT_LT(trunk_laterals(forked), trunk_laterals(plain)) << trunk_laterals(forked) << " vs " << trunk_laterals(plain);
  // Off by default: the defaults grow Runions' tree unchanged (same node count as before the fork
  // settings existed, since none of them is read).
  space_colonization_params d;
  EXPECT_EQ(d.fork_length, 0.0f);
  EXPECT_EQ(d.bud_life, 0);
  EXPECT_EQ(d.crook, 0.0f);
}
