// Issue 54: the Export dialog writes the LOD chain as `sylva export --lods` does, driven as a user
// would (a scripted session): the "LOD chain" box, then Export as... an FBX and a GLB. The FBX holds
// its LOD group with the four levels, the GLB its _LOD0.._LOD3 meshes with the chain's triangles
// and the impostor, and the status bar the same counts as the command line prints.
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "editor_script_run.h"
#include "generators/tree_spec.h"
#include "render/io/fbx_records.h"
#include "render/io/preset.h"
#include "render/mesh/lod.h"

using namespace sylva;
namespace fs = std::filesystem;
using sylva_test::run_script;
using sylva_test::script_passed;
using sylva_test::test_dir;

namespace {

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  for (size_t at = 0; (at = s.find(from, at)) != std::string::npos; at += to.size()) s.replace(at, from.size(), to);
}

nlohmann::json glb_json(const std::string& bytes) {
  uint32_t n = 0;
  if (bytes.size() < 20) return nlohmann::json::object();
  std::memcpy(&n, bytes.data() + 12, 4);
  return nlohmann::json::parse(bytes.substr(20, n));
}

std::array<size_t, lod_levels> glb_levels(const nlohmann::json& j) {
  std::array<size_t, lod_levels> out{};
  for (const nlohmann::json& m : j["meshes"]) {
    const std::string name = m.value("name", "");
    const size_t at = name.rfind("_LOD");
    if (at == std::string::npos || at + 5 != name.size() || name[at + 4] < '0' || name[at + 4] > '3') continue;
    for (const nlohmann::json& p : m["primitives"])
      out[size_t(name[at + 4] - '0')] += j["accessors"][p["indices"].get<size_t>()]["count"].get<size_t>() / 3;
  }
  return out;
}

}  // namespace

TEST(EditorExportLods, DialogWritesTheChainAsTheCommandLineDoes) {
  if (!sylva_test::have_display()) GTEST_SKIP() << "no DISPLAY";
  const fs::path dir = test_dir("export_lods_files");
  fs::create_directories(dir);
  const std::string preset_path = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";
  preset p;
  ASSERT_TRUE(load_preset_file(preset_path, p).ok);
  const tree_skeleton t = grow(p.spec, grow_options{});
  const tree_mesh m = mesh_tree(t, p.mesh, p.spec.seed);
  const lod_chain c = build_lods(t, m, p.mesh, p.render.lod);
  std::string script = R"(wait_tree
show_export 1
export_lods 1
export_as DIR/t.fbx
expect_file DIR/t.fbx
frames 3
expect_message COUNTS
export_as DIR/t.glb
expect_file DIR/t.glb
frames 3
expect_message COUNTS
)";
  replace_all(script, "DIR", dir.string());
  replace_all(script, "COUNTS", lod_summary(c));   // the status bar's counts: the command line's line
  const sylva_test::run_result r = run_script("export_lods", script, preset_path);
  ASSERT_TRUE(script_passed(r));

  // The GLB: four levels, each with the chain's triangles, and the impostor rendered on the
  // editor's own GL thread: LOD0's MSFT_lod lists LOD1-3 and the impostor, with its coverage.
  const nlohmann::json j = glb_json(sylva_test::slurp((dir / "t.glb").string()));
  const std::array<size_t, lod_levels> tris = glb_levels(j);
  for (int k = 0; k < lod_levels; ++k) EXPECT_EQ(tris[size_t(k)], c.triangles[size_t(k)]) << "LOD" << k;
  const nlohmann::json& lod0 = j["nodes"][j["scenes"][0]["nodes"][0].get<size_t>()];
  ASSERT_TRUE(lod0.contains("extensions")) << lod0.dump();
  const nlohmann::json& ids = lod0["extensions"]["MSFT_lod"]["ids"];
  ASSERT_EQ(ids.size(), size_t(4));
  EXPECT_EQ(j["nodes"][ids[3].get<size_t>()]["name"], "t_impostor");
  EXPECT_NEAR(lod0["extras"]["MSFT_screencoverage"][4].get<double>(), double(c.impostor_coverage), 1e-6);
  // The FBX: the LOD group (a LodGroup model and attribute) connected over t_LOD0..3.
  fbx::document d;
  ASSERT_EQ(fbx::parse(sylva_test::slurp((dir / "t.fbx").string()), d), "");
  const fbx::record* objects = fbx::find(d.top, "Objects");
  ASSERT_NE(objects, nullptr);
  int groups = 0, levels = 0;
  for (const fbx::record& o : objects->children) {
    if (o.props.size() < 3) continue;
    groups += o.name == "NodeAttribute" && fbx::as_string(o.props[2]) == "LodGroup";
    const std::string n = fbx::object_name(o);
    levels += o.name == "Model" && n.size() == 6 && n.compare(0, 5, "t_LOD") == 0;
  }
  EXPECT_EQ(groups, 1);
  EXPECT_EQ(levels, lod_levels);
}
