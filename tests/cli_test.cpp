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

#include "tests/run_sylva.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {


fs::path scratch() {
  static const fs::path d = [] {
    fs::path p = fs::temp_directory_path() / ("sylva_cli_test_" + std::to_string(::getpid()));
    fs::create_directories(p);
    return p;
  }();
  return d;
}

// Removes the scratch folder once every test has run.
struct scratch_cleanup : testing::Environment {
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(scratch(), ec);
  }
};
const auto* const cleanup_env = testing::AddGlobalTestEnvironment(new scratch_cleanup);

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
  EXPECT_EQ(lines, 3);  // one line per file

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
