// The `sylva` binary's headless commands: exit codes, messages and the files they write.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>
#include <stb/stb_image.h>

#include "tests/run_sylva.h"
#include "tests/scratch_dir.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {


// This process's scratch folder (tests/scratch_dir.h), removed when the process exits.
fs::path scratch() {
  static const fs::path d = [] {
    fs::path p = sylva_test::scratch_path("sylva_cli_test");
    fs::create_directories(p);
    return p;
  }();
  return d;
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// Runs `sylva ARGS` with DISPLAY unset (no test may open a window), capturing both streams.
sylva_run sylva(const std::string& args) { return run_sylva("env -u DISPLAY -u WAYLAND_DISPLAY", args); }

std::string preset_path(const char* name) { return (fs::path(SYLVA_SOURCE_DIR) / "presets" / name).string(); }

std::string write_scratch(const char* name, const std::string& text) {
  const fs::path p = scratch() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

size_t skeleton_nodes(const fs::path& p) {
  const json j = json::parse(slurp(p), nullptr, false);
  if (j.is_discarded() || !j.contains("nodes")) return 0;
  return j["nodes"]["parent"].size();
}

}  // namespace

TEST(Cli, ParamsJsonListsEveryGenerator) {
  const sylva_run r = sylva("params --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out, nullptr, false);
  ASSERT_TRUE(j.is_array()) << r.out.substr(0, 200);
  std::set<std::string> seen;
  for (const json& p : j) {
    seen.insert(p["generator"].is_null() ? p["section"].get<std::string>() : p["generator"].get<std::string>());
    for (const char* field : {"key", "symbol", "min", "max", "default", "help"}) EXPECT_TRUE(p.contains(field));
  }
  for (const char* g : {"self_organizing", "space_colonization", "guiding_vectors", "lsystem", "mesh", "render"})
    EXPECT_TRUE(seen.count(g)) << g;
  EXPECT_EQ(sylva("params").code, 0);
}

TEST(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(sylva("--help").code, 0);
  EXPECT_EQ(sylva("export --help").code, 0);
  const std::string a = preset_path("lsystem_honda_a.json");
  for (const std::string& args : std::vector<std::string>{"--no-such-flag", "export", "params --bogus",
                                 "export " + a,  // no -o
                                 "export " + a + " -o x.xyz",
                                 "export " + a + " -o x.json --set r1=9",
                                 "export " + a + " -o x.json --set nokey=1",
                                 "export " + a + " -o x.json --seeds 5-2",
                                 "bench --repeat 0"}) {
    SCOPED_TRACE(args);
    const sylva_run r = sylva(args);
    EXPECT_EQ(r.code, 2);
    EXPECT_FALSE(r.err.empty());
  }
}

TEST(Cli, ExportJsonAndObjWriteFiles) {
  const fs::path json_out = scratch() / "a" / "tree.json";  // the folder is created
  sylva_run r = sylva("export " + preset_path("lsystem_honda_a.json") + " -o " + json_out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(skeleton_nodes(json_out), size_t(1) << 10);  // tree a: 10 derivations, min 0 -> 2^10 nodes
  EXPECT_NE(r.out.find("1024 nodes"), std::string::npos) << r.out;

  const fs::path obj_out = scratch() / "tree.obj";
  r = sylva("export " + preset_path("lsystem_honda_c.json") + " -o " + obj_out.string() + " --seed 3 --step 4");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_GT(fs::file_size(obj_out), 0u);
  EXPECT_TRUE(fs::exists(scratch() / "tree.mtl"));
}

TEST(Cli, BatchSeedsAndSweeps) {
  const fs::path out = scratch() / "batch" / "tree.json";
  sylva_run r = sylva("export " + preset_path("lsystem_honda_a.json") + " -o " + out.string() + " --seeds 4-6");
  ASSERT_EQ(r.code, 0) << r.err;
  for (int s = 4; s <= 6; ++s) EXPECT_TRUE(fs::exists(scratch() / "batch" / ("tree-" + std::to_string(s) + ".json")));
  int lines = 0;
  for (char c : r.out) lines += c == '\n';
  EXPECT_EQ(lines, 4);  // one line per file, and the manifest's
  EXPECT_NE(r.out.find("tree-manifest.tsv: 3 files"), std::string::npos) << r.out;

  // Sweeping the derivation count 2..4 on tree a (min 0) gives 2^2, 2^3, 2^4 nodes.
  const fs::path sweep = scratch() / "sweep" / "t.json";
  r = sylva("export " + preset_path("lsystem_honda_a.json") + " -o " + sweep.string() + " --set derivations=2:4:3");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(skeleton_nodes(scratch() / "sweep" / "t-1.json"), 4u);
  EXPECT_EQ(skeleton_nodes(scratch() / "sweep" / "t-2.json"), 8u);
  EXPECT_EQ(skeleton_nodes(scratch() / "sweep" / "t-3.json"), 16u);
}

TEST(Cli, FailuresExitOneWithAReason) {
  // An unwritable output path.
  sylva_run r = sylva("export " + preset_path("lsystem_honda_a.json") + " -o /dev/null/tree.json");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("/dev/null"), std::string::npos) << r.err;

  // A truncated preset: the message names the position.
  const std::string bad = write_scratch("truncated.json", "{\n  \"sylva_preset\": 1,\n  \"params\": {\"r1\": 0.5");
  r = sylva("export " + bad + " -o " + (scratch() / "x.json").string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("malformed JSON at line 3"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);  // one line
  EXPECT_FALSE(fs::exists(scratch() / "x.json"));

  // A wrong type names the key.
  const std::string typed = write_scratch("typed.json", R"({"sylva_preset":1,"params":{"derivations":"ten"}})");
  r = sylva("export " + typed + " -o " + (scratch() / "x.json").string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("params.derivations"), std::string::npos) << r.err;

  r = sylva("export " + (scratch() / "missing.json").string() + " -o " + (scratch() / "x.json").string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("missing.json"), std::string::npos) << r.err;

  // .png without a display: a clear error, not a crash.
  r = sylva("export " + preset_path("lsystem_honda_a.json") + " -o " + (scratch() / "x.png").string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("DISPLAY"), std::string::npos) << r.err;
}

TEST(Cli, WarningsGoToStderrWithExitZero) {
  // Out of range (clamped) and an unknown key: warnings, and the export still succeeds.
  const std::string p = write_scratch("clamped.json",
                                      R"({"sylva_preset":1,"generator":"lsystem","params":{"derivations":3,"r1":7,"colour":1}})");
  const sylva_run r = sylva("export " + p + " -o " + (scratch() / "clamped.json.out.json").string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("params.r1"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("params.colour"), std::string::npos) << r.err;
}

// 4x4 PNGs: an RGB bark gradient, a green RGBA leaf (alpha 255 everywhere) and a grey opacity
// map whose odd columns are white.
const std::string bark_png(
    "\x89\x50\x4e\x47\x0d\x0a\x1a\x0a\x00\x00\x00\x0d\x49\x48\x44\x52\x00\x00\x00\x04\x00\x00\x00\x04\x08\x02\x00\x00\x00"
    "\x26\x93\x09\x29\x00\x00\x00\x3f\x49\x44\x41\x54\x78\xda\x01\x34\x00\xcb\xff\x00\x00\x05\x0a\x0f\x14\x19\x1e\x23\x28"
    "\x2d\x32\x37\x00\x3c\x41\x46\x4b\x50\x55\x5a\x5f\x64\x69\x6e\x73\x00\x78\x7d\x82\x87\x8c\x91\x96\x9b\xa0\xa5\xaa\xaf"
    "\x00\xb4\xb9\xbe\xc3\xc8\xcd\xd2\xd7\xdc\xe1\xe6\xeb\x7b\x17\x16\x09\xc4\x17\xee\x78\x00\x00\x00\x00\x49\x45\x4e\x44"
    "\xae\x42\x60\x82", 120);
const std::string leaf_png(
    "\x89\x50\x4e\x47\x0d\x0a\x1a\x0a\x00\x00\x00\x0d\x49\x48\x44\x52\x00\x00\x00\x04\x00\x00\x00\x04\x08\x06\x00\x00\x00"
    "\xa9\xf1\x9e\x7e\x00\x00\x00\x12\x49\x44\x41\x54\x78\xda\x63\xb0\x59\xa0\xf1\x1f\x19\x33\x90\x2e\x00\x00\x38\x58\x20"
    "\x31\xd4\x8e\x81\xcc\x00\x00\x00\x00\x49\x45\x4e\x44\xae\x42\x60\x82", 75);
const std::string opacity_png(
    "\x89\x50\x4e\x47\x0d\x0a\x1a\x0a\x00\x00\x00\x0d\x49\x48\x44\x52\x00\x00\x00\x04\x00\x00\x00\x04\x08\x00\x00\x00\x00"
    "\x8c\x9a\xc1\xa2\x00\x00\x00\x0e\x49\x44\x41\x54\x78\xda\x63\x60\xf8\x0f\x84\xa8\x04\x00\x4b\xc8\x07\xf9\x76\xb6\x61"
    "\x0a\x00\x00\x00\x00\x49\x45\x4e\x44\xae\x42\x60\x82", 71);

TEST(Cli, ExportCarriesThePresetsOwnTextures) {
  const fs::path dir = scratch() / "own";
  fs::create_directories(dir);
  const std::string bark = (dir / "bark.png").string(), leaf = (dir / "leaf.png").string(),
                    opacity = (dir / "opacity.png").string();
  std::ofstream(bark, std::ios::binary) << bark_png;
  std::ofstream(leaf, std::ios::binary) << leaf_png;
  std::ofstream(opacity, std::ios::binary) << opacity_png;
  json preset = {{"sylva_preset", 1}, {"generator", "lsystem"}, {"params", {{"derivations", 4}}},
                 {"render", {{"bark_texture", bark}, {"leaf_texture", leaf}, {"leaf_opacity", opacity}}}};
  const std::string path = write_scratch("own_textures.json", preset.dump());

  // OBJ: the bark PNG beside it unchanged, the leaf PNG with the opacity map as its alpha.
  sylva_run r = sylva("export " + path + " -o " + (dir / "tree.obj").string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(slurp(dir / "tree_bark_custom.png"), slurp(bark));
  const std::string written = slurp(dir / "tree_leaves_custom.png");
  int w = 0, h = 0, ch = 0;
  stbi_uc* px = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(written.data()), int(written.size()), &w, &h, &ch, 4);
  ASSERT_TRUE(px);
  ASSERT_EQ(w, 4);
  for (int k = 0; k < 16; ++k) {
    EXPECT_EQ(px[k * 4 + 1], 160);                    // the leaf's own green
    EXPECT_EQ(px[k * 4 + 3], k % 2 ? 255 : 0) << k;  // the opacity map's columns
  }
  stbi_image_free(px);
  EXPECT_NE(slurp(dir / "tree.mtl").find("newmtl leaves_custom"), std::string::npos);
  // GLB: the bark PNG's bytes are inside.
  r = sylva("export " + path + " -o " + (dir / "tree.glb").string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(slurp(dir / "tree.glb").find(slurp(bark)), std::string::npos);

  // A missing texture: a warning on stderr, exit 0, the export written with procedural leaves.
  preset["render"]["leaf_texture"] = (dir / "missing.png").string();
  preset["render"].erase("leaf_opacity");
  const std::string missing = write_scratch("missing_texture.json", preset.dump());
  r = sylva("export " + missing + " -o " + (dir / "fallback.glb").string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("warning"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("missing.png: file not found; using the procedural leaves"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir / "fallback.glb"));
  EXPECT_EQ(slurp(dir / "fallback.glb").find("leaves_custom"), std::string::npos);
}

TEST(Cli, BenchJsonLine) {
  const std::string p = write_scratch("small.json", R"({"sylva_preset":1,"name":"small","generator":"lsystem",
      "params":{"derivations":4}})");
  const sylva_run r = sylva("bench " + p + " --repeat 2 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out, nullptr, false);
  ASSERT_TRUE(j.is_object()) << r.out;
  EXPECT_EQ(j["preset"], "small");
  EXPECT_EQ(j["generator"], "lsystem");
  EXPECT_EQ(j["nodes"], 16);  // 4 derivations of tree a: 2^4 nodes
  for (const char* k : {"leaves", "triangles", "grow_ms", "mesh_ms"}) EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_GT(j["peak_rss_mb"].get<double>(), 0.0);

  EXPECT_EQ(sylva("bench " + (scratch() / "missing.json").string()).code, 1);
}
