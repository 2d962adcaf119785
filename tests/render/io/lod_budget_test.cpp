// Issue 54: each LOD level of a `sylva export --lods` file holds its triangle budget (within
// lod_budget_tolerance of LOD1-3's 40 / 15 / 5 % of LOD0), counted as the file holds them: the
// triangles of each `_LODn` mesh of the GLB. Where a level cannot, the export says which floor
// kept it higher and by how much.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/run_sylva.h"
#include "tests/scratch_dir.h"
#include "generators/tree_spec.h"
#include "render/io/preset.h"
#include "render/mesh/lod.h"

using namespace sylva;
using sylva_test::slurp;

namespace {

// Triangles per "<stem>_LOD<k>" mesh of a GLB: the indices of every primitive over 3.
std::array<size_t, lod_levels> glb_level_triangles(const std::string& bytes) {
  std::array<size_t, lod_levels> out{};
  uint32_t json_bytes = 0;
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0) return out;
  std::memcpy(&json_bytes, bytes.data() + 12, 4);
  const nlohmann::json j = nlohmann::json::parse(bytes.substr(20, json_bytes));
  for (const nlohmann::json& m : j["meshes"]) {
    const std::string name = m.value("name", "");
    const size_t at = name.rfind("_LOD");
    if (at == std::string::npos || at + 5 != name.size()) continue;
    const int k = name[at + 4] - '0';
    if (k < 0 || k >= lod_levels) continue;
    for (const nlohmann::json& p : m["primitives"]) out[size_t(k)] += j["accessors"][p["indices"].get<size_t>()]["count"].get<size_t>() / 3;
  }
  return out;
}

}  // namespace

TEST(LodBudget, EachFileLevelHoldsItsBudgetOrSaysWhy) {
  sylva_test::scratch_dir dir("sylva-lod-budget");
  const double budget[lod_levels] = {100, 40, 15, 5};
  // A broadleaf and two conifers (needles in whorls: many leaves to a cell).
  for (const char* name : {"species_oak", "species_pine", "species_spruce"}) {
    SCOPED_TRACE(name);
    const std::string preset_path = std::string(SYLVA_SOURCE_DIR) + "/presets/" + name + ".json";
    const std::string out = dir / (std::string(name) + ".glb");
    // Without a display the impostor is left out (with a warning); the levels are the same.
    const sylva_run r = run_sylva("env -u DISPLAY -u WAYLAND_DISPLAY", "export '" + preset_path + "' -o '" + out + "' --lods");
    ASSERT_EQ(r.code, 0) << r.err;
    const std::array<size_t, lod_levels> file = glb_level_triangles(slurp(out));
    ASSERT_GT(file[0], size_t(1000));
    for (int k = 1; k < lod_levels; ++k) {
      const double share = 100.0 * double(file[size_t(k)]) / double(file[0]);
      std::printf("%s LOD%d: %zu triangles, %.2f %% of LOD0 (budget %g %%)\n", name, k, file[size_t(k)], share, budget[k]);
      const bool holds = std::abs(share / budget[k] - 1.0) <= lod_budget_tolerance;
      const std::string why = "LOD" + std::to_string(k) + ": ";
      EXPECT_TRUE(holds || r.err.find(why) != std::string::npos)
          << "LOD" << k << " at " << share << " % of LOD0 where the budget is " << budget[k] << " %, and no reason given: " << r.err;
    }
    // The chain built here counts as the file does, and the export prints the same counts (the
    // editor's LOD view shows lod_summary of its chain too).
    preset p;
    ASSERT_TRUE(load_preset_file(preset_path, p).ok);
    const tree_skeleton t = grow(p.spec, grow_options{});
    const tree_mesh m = mesh_tree(t, p.mesh, p.spec.seed);
    const lod_chain c = build_lods(t, m, p.mesh, p.render.lod);
    for (int k = 0; k < lod_levels; ++k) EXPECT_EQ(c.triangles[size_t(k)], file[size_t(k)]) << "LOD" << k;
    EXPECT_NE(r.out.find(lod_summary(c)), std::string::npos) << r.out;
  }
}

// Blades in LOD0 (--profile hero-baked) make the file's LOD0 bigger than the flat-card LOD0 the
// budgets are shares of: the export says so, with both counts, instead of letting the shares pass
// for budgets held.
TEST(LodBudget, BladesInLod0AreSaidToChangeTheShares) {
  sylva_test::scratch_dir dir("sylva-lod-budget-blades");
  const std::string preset_path = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";
  const sylva_run plain = run_sylva("env -u DISPLAY -u WAYLAND_DISPLAY", "export '" + preset_path + "' -o '" + (dir / "p.glb") + "' --lods");
  ASSERT_EQ(plain.code, 0) << plain.err;
  EXPECT_EQ(plain.err.find("LOD0 in the file holds"), std::string::npos) << plain.err;
  const sylva_run blades = run_sylva("env -u DISPLAY -u WAYLAND_DISPLAY",
                                     "export '" + preset_path + "' -o '" + (dir / "b.glb") + "' --lods --profile hero-baked");
  ASSERT_EQ(blades.code, 0) << blades.err;
  const std::array<size_t, lod_levels> file = glb_level_triangles(slurp(dir / "b.glb")),
                                       flat = glb_level_triangles(slurp(dir / "p.glb"));
  ASSERT_GT(file[0], flat[0]);
  EXPECT_EQ(file[1], flat[1]);   // the levels are the same cards
  EXPECT_NE(blades.err.find("LOD0 in the file holds " + std::to_string(file[0]) + " triangles where the levels' budgets count " +
                            std::to_string(flat[0])),
            std::string::npos)
      << blades.err;
}

namespace {

// A straight stem of `internodes` from radius r0 thinning by dr a node, meshed without leaves.
struct stem {
  tree_skeleton t;
  mesh_params mp;
  tree_mesh m;
  stem(int internodes, float length, float r0, float dr) {
    for (int k = 0; k <= internodes; ++k) t.add_node({0, length * float(k), 0}, k - 1, r0 - dr * float(k), 0, 0);
    t.steps = 0;
    mp.leaves_enabled = false;
    m = mesh_tree(t, mp);
  }
};

}  // namespace

TEST(LodBudget, ALevelKeptAboveItsBudgetSaysWhichFloorAndHowMuch) {
  lod_params lp;
  lp.lod3_budget = 1;
  // A stump as wide as it is tall: its trunk at its coarsest (one span of 3 sides, 6 triangles) is
  // more than 1 % of it. The bark floor.
  {
    stem s(16, 0.05f, 1.0f, 0.001f);
    const lod_chain c = build_lods(s.t, s.m, s.mp, lp);
    ASSERT_TRUE(c.reduced) << c.message;
    ASSERT_GT(c.triangles[3], size_t(1.1 * double(c.target[3])));
    const std::string& note = c.note[3];
    EXPECT_NE(note.find("LOD3: " + std::to_string(c.triangles[3]) + " triangles"), std::string::npos) << note;
    EXPECT_NE(note.find("over its budget of " + std::to_string(c.target[3])), std::string::npos) << note;
    EXPECT_NE(note.find("the bark floor (trunk and limbs at their coarsest) keeps " + std::to_string(c.triangles[3])),
              std::string::npos) << note;
    EXPECT_NE(c.message.find(note), std::string::npos);
  }
  // A thin stem with ten leaves: 1 % is less than the trunk's first span (6 triangles) and one card
  // (4): both floors, each with its triangles.
  {
    stem s(12, 0.2f, 0.1f, 0.005f);
    for (uint32_t k = 0; k < 10; ++k)
      s.m.leaves.push_back({{0.1f, 0.2f * float(k + 1), 0}, {0, 0, 0, 1}, 0.1f, 0, 0xffff, k + 1, 0, 255});
    const lod_chain c = build_lods(s.t, s.m, s.mp, lp);
    ASSERT_TRUE(c.reduced) << c.message;
    ASSERT_EQ(c.triangles[3], 6 + exported_card_triangles) << c.note[3];
    const std::string& note = c.note[3];
    EXPECT_NE(note.find("over its budget of " + std::to_string(c.target[3])), std::string::npos) << note;
    EXPECT_NE(note.find("the bark floor (trunk and limbs at their coarsest) keeps 6"), std::string::npos) << note;
    EXPECT_NE(note.find("the leaf floor (at least one card) 4"), std::string::npos) << note;
    // Levels that hold their budgets carry no note.
    for (int k = 1; k < 3; ++k) {
      if (std::abs(double(c.triangles[size_t(k)]) / double(c.target[size_t(k)]) - 1) <= lod_budget_tolerance) {
        EXPECT_EQ(c.note[size_t(k)], "") << "LOD" << k;
      }
    }
  }
}
