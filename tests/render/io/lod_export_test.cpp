// `--lods` exports: MSFT_lod nodes with screen coverage, the impostor quad, the Khronos
// validator, and one OBJ per level written all or nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "tests/scratch_dir.h"
#include "generators/tree_spec.h"
#include "render/io/export.h"
#include "render/io/preset.h"
#include "render/mesh/lod.h"
#include "render/mesh/season.h"
#include "render/assets/textures.h"
#include "tests/run_sylva.h"

using namespace sylva;
namespace fs = std::filesystem;

using sylva_test::slurp;

namespace {

struct lod_scratch : sylva_test::scratch_dir {
  lod_scratch() : scratch_dir("sylva-lod-export") {}
};

struct lod_tree {
  preset p;
  tree_skeleton t;
  tree_mesh m;
  lod_chain c;
  export_impostor imp;
  export_options o;
  explicit lod_tree(const char* name = "lsystem_honda_a") {
    EXPECT_TRUE(load_preset_file(std::string(SYLVA_SOURCE_DIR) + "/presets/" + name + ".json", p).ok);
    t = grow(p.spec, grow_options{});
    m = mesh_tree(t, p.mesh, p.spec.seed);
    c = build_lods(t, m, p.mesh, lod_params{});
    o.mesh = p.mesh;
    o.texture_size = 32;
    o.lod0_coverage = c.coverage[0];
    for (int k = 1; k < lod_levels; ++k) o.lods.push_back({&c.level[size_t(k) - 1], c.coverage[size_t(k)], c.target[size_t(k)]});
    // A stand-in atlas (the GL one is tested in lod_render_test): 4 x 2 cells of 8 pixels.
    image atlas{32, 16, 4, std::vector<uint8_t>(32 * 16 * 4, 200)};
    EXPECT_EQ(encode_png(atlas, imp.color_png), "");
    EXPECT_EQ(encode_png(atlas, imp.normal_png), "");
    imp.width = imp.height = 3;
    imp.centre = {0, 1.5f, 0};
    imp.coverage = c.impostor_coverage;
    o.impostor = &imp;
  }
};

}  // namespace

TEST(LodExport, GltfHasMsftLodWithCoverageAndAnImpostorQuad) {
  lod_scratch dir;
  lod_tree h;
  const export_result r = export_tree(h.t, h.m, {"lsystem", 1}, dir / "tree.gltf", h.o);
  ASSERT_EQ(r.error, "");
  const nlohmann::json j = nlohmann::json::parse(slurp(dir / "tree.gltf"));
  EXPECT_NE(std::find(j["extensionsUsed"].begin(), j["extensionsUsed"].end(), "MSFT_lod"), j["extensionsUsed"].end());
  EXPECT_FALSE(j.contains("extensionsRequired"));   // LOD0 alone is a complete tree
  const int lod0 = j["scenes"][0]["nodes"][0];
  const nlohmann::json& n0 = j["nodes"][size_t(lod0)];
  // Engine naming (Unity's LODGroup convention): "<file stem>_LOD<k>" on each level's node and mesh,
  // the mesh holding the bark and every leaf material of the level.
  EXPECT_EQ(n0["name"], "tree_LOD0");
  ASSERT_TRUE(n0.contains("mesh"));
  EXPECT_EQ(j["meshes"][n0["mesh"].get<size_t>()]["name"], "tree_LOD0");
  EXPECT_GE(j["meshes"][n0["mesh"].get<size_t>()]["primitives"].size(), size_t(2));
  const nlohmann::json& ids = n0["extensions"]["MSFT_lod"]["ids"];
  ASSERT_EQ(ids.size(), size_t(4));   // LOD1..3 and the impostor
  const nlohmann::json& cov = n0["extras"]["MSFT_screencoverage"];
  ASSERT_EQ(cov.size(), size_t(5));
  for (size_t k = 1; k < cov.size(); ++k) EXPECT_LT(cov[k].get<float>(), cov[k - 1].get<float>());
  const char* names[] = {"tree_LOD1", "tree_LOD2", "tree_LOD3", "tree_impostor"};
  for (size_t k = 0; k < 4; ++k) EXPECT_EQ(j["nodes"][ids[k].get<size_t>()]["name"], names[k]);
  for (size_t k = 0; k < 3; ++k) {
    const nlohmann::json& n = j["nodes"][ids[k].get<size_t>()];
    EXPECT_EQ(j["meshes"][n["mesh"].get<size_t>()]["name"], names[k]);
  }
  // Each level's triangles are recorded and fall level by level; the chain counts them as the file
  // holds them (a face per side of each leaf card: lod.h final_triangles).
  size_t prev = j["nodes"][size_t(lod0)]["extras"]["triangles"];
  EXPECT_EQ(prev, h.c.triangles[0]);
  for (size_t k = 0; k < 3; ++k) {
    const size_t tris = j["nodes"][ids[k].get<size_t>()]["extras"]["triangles"];
    EXPECT_EQ(tris, h.c.triangles[k + 1]);
    EXPECT_LT(tris, prev);
    prev = tris;
  }
  // Scene 1 lists every level as its own root, for viewers without the extension.
  ASSERT_EQ(j["scenes"].size(), size_t(2));
  EXPECT_EQ(j["scenes"][1]["nodes"].size(), size_t(5));
  const nlohmann::json& imp = j["nodes"][ids[3].get<size_t>()];
  EXPECT_EQ(imp["extras"]["sylva_impostor"]["views"], 8);
  EXPECT_TRUE(fs::exists(dir / "tree_impostor.png"));
  EXPECT_TRUE(fs::exists(dir / "tree_impostor_normal.png"));
}

TEST(LodExport, KhronosValidatorReportsNoErrorsOrWarnings) {
  if (std::system("command -v node >/dev/null 2>&1 && command -v npm >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "node/npm not installed (scripts/install-deps.sh installs them)";
  const std::string src = SYLVA_SOURCE_DIR;
  ASSERT_EQ(std::system(("bash " + src + "/scripts/install-gltf-validator.sh").c_str()), 0);
  lod_scratch dir;
  lod_tree h;
  ASSERT_EQ(export_tree(h.t, h.m, {"lsystem", 1}, dir / "lods.glb", h.o).error, "");
  ASSERT_EQ(export_tree(h.t, h.m, {"lsystem", 1}, dir / "lods.gltf", h.o).error, "");
  // A tree whose levels merge leaves into baked cluster cards (render/mesh/lod_cards.h): their materials too.
  lod_tree palm("species_palm");
  ASSERT_NE(palm.c.level[2].cards, nullptr);
  ASSERT_EQ(export_tree(palm.t, palm.m, {"palm", 1}, dir / "palm.glb", palm.o).error, "");
  // MSFT_lod is unknown to the validator: it reports it as an info (UNSUPPORTED_EXTENSION), not a
  // warning, so the 0-errors-0-warnings bar holds.
  const std::string cmd = "node " + src + "/scripts/validate-gltf.js " + (dir / "lods.glb") + " " + (dir / "lods.gltf") +
                          " " + (dir / "palm.glb") + " > " + (dir / "report.txt") + " 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << slurp(dir / "report.txt");
}

TEST(LodExport, ObjWritesOneFilePerLevelAllOrNothing) {
  lod_scratch dir;
  lod_tree h;
  h.o.impostor = nullptr;
  const export_result r = export_tree(h.t, h.m, {"lsystem", 1}, dir / "tree.obj", h.o);
  ASSERT_EQ(r.error, "");
  for (const char* f : {"tree.obj", "tree_lod1.obj", "tree_lod2.obj", "tree_lod3.obj", "tree.mtl", "tree_lod3.mtl"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  // Faces per file are each level's triangles.
  auto faces = [&](const std::string& f) {
    std::istringstream s(slurp(dir / f));
    size_t n = 0;
    for (std::string line; std::getline(s, line);) n += line.rfind("f ", 0) == 0;
    return n;
  };
  EXPECT_EQ(faces("tree.obj"), h.c.triangles[0]);
  EXPECT_EQ(faces("tree_lod2.obj"), h.c.triangles[2]);
  // A failure while staging any file leaves the previous export whole and adds nothing.
  const std::string before = slurp(dir / "tree_lod1.obj");
  fs::remove(dir / "tree_lod3.obj");
  h.c.level[0].leaves.clear();   // a different LOD1 than on disk
  h.c.level[0].leaf_end.assign(h.c.level[0].leaf_end.size(), 0);
  inject_write_failure_for_tests(5);
  const export_result bad = export_tree(h.t, h.m, {"lsystem", 1}, dir / "tree.obj", h.o);
  inject_write_failure_for_tests(-1);
  EXPECT_NE(bad.error, "");
  EXPECT_EQ(slurp(dir / "tree_lod1.obj"), before);
  EXPECT_FALSE(fs::exists(dir / "tree_lod3.obj"));
}

TEST(LodExport, WinterDropsBroadleavesAndTheirBakedCardsOnEveryLevel) {
  lod_scratch dir;
  lod_tree h("species_oak");
  h.o.impostor = nullptr;
  ASSERT_TRUE(h.c.level[2].cards) << "LOD3 of the oak carries baked cluster cards";
  render_params rp = h.p.render;
  rp.season = leaf_season::winter;
  h.o.season = season_leaf_look(rp);
  ASSERT_TRUE(season_changes_leaves(h.o.season));
  ASSERT_EQ(export_tree(h.t, h.m, {"oak", 1}, dir / "tree.obj", h.o).error, "");
  auto faces = [&](const std::string& f) {
    std::istringstream s(slurp(dir / f));
    size_t n = 0;
    for (std::string line; std::getline(s, line);) n += line.rfind("f ", 0) == 0;
    return n;
  };
  // The oak's leaves are broadleaves and go in winter; its acorns are fruit cards and stay. So each
  // level's file holds its bark (the level's triangle count less four per card) and its acorns, each
  // written two-sided (two faces, four triangles: render/io/export_parts.cpp), on every level's
  // file, not only LOD0's.
  auto fruits = [](const tree_mesh& m) {
    return size_t(std::count_if(m.leaves.begin(), m.leaves.end(),
                                [](const leaf_instance& l) { return archetype_is_fruit(leaf_archetype(l.texture)); }));
  };
  ASSERT_GT(fruits(h.m), size_t(0)) << "the oak carries acorns";
  ASSERT_LT(fruits(h.m), h.m.leaves.size());
  EXPECT_EQ(faces("tree.obj"), h.c.triangles[0] - 4 * h.m.leaves.size() + 4 * fruits(h.m));
  for (int k = 1; k < lod_levels; ++k) {
    const tree_mesh& l = h.c.level[size_t(k) - 1];
    ASSERT_GT(l.leaves.size(), fruits(l));
    EXPECT_EQ(faces("tree_lod" + std::to_string(k) + ".obj"), h.c.triangles[size_t(k)] - 4 * l.leaves.size() + 4 * fruits(l))
        << "LOD" << k;
  }
}

TEST(LodExport, CliWritesLevelsAndRefusesWhatItCannot) {
  lod_scratch dir;
  const std::string preset = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";
  // OBJ needs no display: four levels.
  const sylva_run obj = run_sylva("env -u DISPLAY -u WAYLAND_DISPLAY", "export '" + preset + "' -o '" + (dir / "t.obj") + "' --lods");
  EXPECT_EQ(obj.code, 0) << obj.err;
  for (const char* f : {"t.obj", "t_lod1.obj", "t_lod2.obj", "t_lod3.obj"}) EXPECT_TRUE(fs::exists(dir / f)) << f;
  // glTF without a display: written, the impostor left out with a warning.
  const sylva_run glb = run_sylva("env -u DISPLAY -u WAYLAND_DISPLAY", "export '" + preset + "' -o '" + (dir / "t.glb") + "' --lods");
  EXPECT_EQ(glb.code, 0) << glb.err;
  EXPECT_NE(glb.err.find("impostor left out"), std::string::npos) << glb.err;
  const sylva_run png = run_sylva("", "export '" + preset + "' -o '" + (dir / "t.png") + "' --lods");
  EXPECT_EQ(png.code, 2);
  EXPECT_NE(png.err.find("--lods writes"), std::string::npos) << png.err;
  const sylva_run anim = run_sylva("", "export '" + preset + "' -o '" + (dir / "a.glb") + "' --lods --animation");
  EXPECT_EQ(anim.code, 2);
  EXPECT_FALSE(fs::exists(dir / "a.glb"));
}
