// The mesh bound (render/io/mesh_bound.h): an upper bound of every mesh, not absurdly loose, and a
// request over the mesh budget stops before meshing with a clear message, its peak memory under the
// stated bound (growth bound + mesh budget); the skeleton JSON never meshes.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "generators/memory_bound.h"
#include "render/io/export.h"
#include "render/io/mesh_bound.h"
#include "render/io/preset.h"
#include "tests/scratch_dir.h"

using namespace sylva;
namespace fs = std::filesystem;

namespace {

template <class T, class A>
double held(const std::vector<T, A>& v) { return double(v.capacity()) * sizeof(T); }

// Bytes the mesh holds: every array at its capacity.
double mesh_held_bytes(const tree_mesh& m) {
  return held(m.position) + held(m.normal) + held(m.uv) + held(m.node) + held(m.occlusion) + held(m.index) +
         held(m.index_end) + held(m.leaves) + held(m.leaf_end) + held(m.final_radius);
}

std::string preset_path(const std::string& name) { return (fs::path(SYLVA_SOURCE_DIR) / "presets" / name).string(); }

// Grows a preset (its node cap lowered to `cap`, to stay quick) and checks the bound on its mesh.
struct bound_check {
  double actual = 0, bound = 0, rings = 0, bound_rings = 0;
};
bound_check check_bound(const tree_skeleton& t, const mesh_params& mp, uint64_t seed) {
  bound_check c;
  const mesh_estimate e = mesh_bound(t, mp);
  const tree_mesh m = mesh_tree(t, mp, seed);
  c.actual = mesh_held_bytes(m);
  c.bound = e.mesh_bytes;
  c.rings = double(m.position.size()) / double(m.radial_segments + 1);
  c.bound_rings = e.rings;
  EXPECT_LE(double(m.triangles()), e.triangles);
  EXPECT_LE(double(m.leaves.size()), e.leaves);
  EXPECT_LE(double(m.position.size()), e.vertices);
  return c;
}

// Runs the sylva binary (no shell) and returns its exit code, its stderr and its own peak RSS.
struct child_run {
  int code = -1;
  std::string err;
  double peak_bytes = 0;
};
child_run run_measured(const std::vector<std::string>& args, const fs::path& err_file) {
  child_run r;
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) ::dup2(fd, 2);
    const int null = ::open("/dev/null", O_WRONLY);
    if (null >= 0) ::dup2(null, 1);
    std::vector<char*> argv;
    std::string bin = SYLVA_BINARY;
    argv.push_back(bin.data());
    std::vector<std::string> copy = args;
    for (std::string& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(bin.c_str(), argv.data());
    ::_exit(127);
  }
  int status = 0;
  struct rusage ru {};
  if (pid > 0 && ::wait4(pid, &status, 0, &ru) == pid) {
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.peak_bytes = double(ru.ru_maxrss) * 1024.0;   // Linux: kilobytes
  }
  std::ifstream f(err_file);
  std::ostringstream s;
  s << f.rdbuf();
  r.err = s.str();
  return r;
}

}  // namespace

// Every preset at its own settings: the mesh never holds more than the bound, and the bound is
// within 4× of it.
TEST(MeshBound, UpperBoundOfEveryPreset) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(SYLVA_SOURCE_DIR) / "presets")) {
    if (entry.path().extension() != ".json") continue;
    preset p;
    if (!load_preset_file(entry.path().string(), p).ok) continue;
    std::visit([](auto& g) { g.node_cap = std::min(g.node_cap, 30000); }, p.spec.params);
    const tree_skeleton t = grow(p.spec, grow_options{});
    if (t.size() < 2) continue;
    const bound_check c = check_bound(t, p.mesh, p.spec.seed);
    EXPECT_LE(c.actual, c.bound) << entry.path().filename();
    EXPECT_LE(c.rings, c.bound_rings) << entry.path().filename();
    EXPECT_LE(c.bound, 4 * c.actual) << entry.path().filename() << ": the bound is too loose";
    ++count;
  }
  EXPECT_GT(count, 30);
}

// Extreme settings on trees of each generator: still an upper bound.
TEST(MeshBound, UpperBoundAtExtremeSettings) {
  const char* names[] = {"lsystem_honda_a.json", "self_organizing_default.json", "space_colonization_seed_sphere.json",
                         "guiding_vectors_default.json"};
  std::vector<mesh_params> extremes;
  {
    mesh_params m;   // the most bark: 32 segments, curve rings, collars and flare everywhere
    m.radial_segments = 32;
    m.curve_rings = 8;
    m.curve_angle = 2;
    m.detail_budget = 4;
    m.collar = 1;
    m.collar_min_radius = 0.0001f;
    m.flare_strength = 2;
    m.flare_height = 3;
    m.gnarl = 30;
    extremes.push_back(m);
    m.leaves.mode = leaf_mode::tips;   // tips mode: 33 leaves a tip before the cap
    m.leaves.density = 32;
    m.leaves.cap = 2000000;
    extremes.push_back(m);
    m.leaves.mode = leaf_mode::shoots;   // dense clumped whorls
    m.leaves.spacing = 0.005f;
    m.leaves.arrangement = leaf_arrangement::whorled;
    m.leaves.whorl = 8;
    m.leaves.clumping = 1;
    extremes.push_back(m);
  }
  {
    mesh_params m;   // the least: 3 segments, straight tubes, no caps, no leaves
    m.radial_segments = 3;
    m.curve_rings = 0;
    m.detail_budget = 1;
    m.caps = false;
    m.collar = 0;
    m.flare_strength = 0;
    m.leaves_enabled = false;
    extremes.push_back(m);
  }
  for (const char* name : names) {
    preset p;
    ASSERT_TRUE(load_preset_file(preset_path(name), p).ok) << name;
    std::visit([](auto& g) { g.node_cap = std::min(g.node_cap, 20000); }, p.spec.params);
    const tree_skeleton t = grow(p.spec, grow_options{});
    ASSERT_GT(t.size(), 10u) << name;
    for (size_t k = 0; k < extremes.size(); ++k) {
      const bound_check c = check_bound(t, extremes[k], p.spec.seed);
      EXPECT_LE(c.actual, c.bound) << name << " extreme " << k;
      EXPECT_GT(c.actual, 0.2 * c.bound) << name << " extreme " << k;
    }
  }
}

// Before growth: the worst shape of a node count bounds a real tree of that size.
TEST(MeshBound, NodeCountBoundCoversRealTrees) {
  preset p;
  ASSERT_TRUE(load_preset_file(preset_path("lsystem_honda_a.json"), p).ok);
  const tree_skeleton t = grow(p.spec, grow_options{});
  const mesh_estimate real = mesh_bound(t, p.mesh);
  const mesh_estimate worst = mesh_bound_for_nodes(double(t.size()), p.mesh, t.steps);
  EXPECT_GE(worst.peak_bytes, real.peak_bytes);
  EXPECT_GE(worst.rings, real.rings);
  // Scaling the tree's own shape to twice its nodes gives about twice the bark.
  const mesh_estimate like = mesh_estimate_like(t, 2.0 * double(t.size()), p.mesh);
  EXPECT_NEAR(like.vertices, 2 * real.vertices, 0.01 * real.vertices);
}

TEST(MeshBound, RefusalNamesEstimateBudgetAndSetting) {
  mesh_params p;
  p.radial_segments = 32;
  p.mesh_budget = 1000;
  const mesh_estimate e = mesh_bound_for_nodes(2e6, p, 20);
  const std::string why = mesh_budget_refusal(e, p);
  EXPECT_NE(why.find("the mesh would take up to "), std::string::npos) << why;
  EXPECT_NE(why.find("2,000,000 nodes at radial_segments 32"), std::string::npos) << why;
  EXPECT_NE(why.find("over mesh_budget 1000 MB"), std::string::npos) << why;
  EXPECT_NE(why.find("raise mesh.mesh_budget"), std::string::npos) << why;
  const int fit = mesh_fit_segments(e, p);
  EXPECT_TRUE(fit == 0 || why.find("lower mesh.radial_segments (" + std::to_string(fit) + " fits)") != std::string::npos) << why;
  // A fitting count really fits; one more does not.
  p.mesh_budget = 4000;
  const mesh_estimate e2 = mesh_bound_for_nodes(2e6, p, 20);
  const int fit2 = mesh_fit_segments(e2, p);
  ASSERT_GT(fit2, 3);
  mesh_params q = p;
  q.radial_segments = fit2;
  EXPECT_EQ(mesh_budget_refusal(mesh_bound_for_nodes(2e6, q, 20), q), "");
  q.radial_segments = fit2 + 1;
  EXPECT_NE(mesh_budget_refusal(mesh_bound_for_nodes(2e6, q, 20), q), "");
  EXPECT_EQ(mesh_budget_refusal(mesh_bound_for_nodes(1000, p, 20), p), "");
}

// The worst in-range mesh request: Honda's tree at the most derivations and the node cap's
// maximum, 32 radial segments, 8 curve rings, detail budget 4. It stops before meshing (on the trial's
// estimate, before growing) with the message, and its peak memory is far under the stated bound.
TEST(MeshBound, WorstInRangeRequestStopsUnderItsBound) {
  const sylva_test::scratch_dir dir("mesh_bound");
  preset p;
  ASSERT_TRUE(load_preset_file(preset_path("lsystem_honda_a.json"), p).ok);
  const std::vector<std::string> sets = {"derivations=24", "node_cap=20000000", "radial_segments=32", "curve_rings=8",
                                         "detail_budget=4"};
  for (const std::string& s : sets) ASSERT_EQ(set_preset_param(p, s), "") << s;
  const double stated = growth_memory_bound(p.spec).bytes() + mesh_budget_bytes(p.mesh);
  std::vector<std::string> args = {"export", preset_path("lsystem_honda_a.json"), "-o", dir / "worst.glb"};
  for (const std::string& s : sets) args.insert(args.end(), {"--set", s});
  const child_run r = run_measured(args, dir / "worst.err");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("the mesh would take about"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("over mesh_budget 4000 MB"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("bad_alloc"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "worst.glb"));
  EXPECT_GT(r.peak_bytes, 0);
  EXPECT_LT(r.peak_bytes, stated);
  EXPECT_LT(r.peak_bytes, 1e9);   // a trial growth, no more
  std::printf("worst in-range mesh request: peak RSS %.0f MB, stated bound %.0f MB\n", r.peak_bytes / 1e6, stated / 1e6);
}

// A mesh that is made, under a budget just over its bound: the process's peak stays under the
// growth's peak plus the bound (the mesh with what the writer makes of it); the same request with
// a budget below its bound is refused after growing, before meshing; the skeleton JSON of it is
// written, unmeshed, under any budget.
TEST(MeshBound, MeshedRequestStaysUnderGrowthPeakPlusBound) {
  const sylva_test::scratch_dir dir("mesh_bound");
  preset p;
  ASSERT_TRUE(load_preset_file(preset_path("lsystem_honda_a.json"), p).ok);
  const std::vector<std::string> sets = {"derivations=13", "radial_segments=32", "curve_rings=8", "detail_budget=4"};
  for (const std::string& s : sets) ASSERT_EQ(set_preset_param(p, s), "") << s;
  const tree_skeleton t = grow(p.spec, grow_options{});
  auto args_for = [&](const std::string& out, int budget_mb) {
    std::vector<std::string> a = {"export", preset_path("lsystem_honda_a.json"), "-o", dir / out};
    for (const std::string& s : sets) a.insert(a.end(), {"--set", s});
    a.insert(a.end(), {"--set", "mesh_budget=" + std::to_string(budget_mb)});
    return a;
  };
  const child_run skeleton_only = run_measured(args_for("tree.json", 50), dir / "json.err");
  EXPECT_EQ(skeleton_only.code, 0) << skeleton_only.err;
  EXPECT_TRUE(fs::exists(dir / "tree.json"));
  for (const char* ext : {".obj", ".glb"}) {
    const mesh_estimate e = with_writer(mesh_bound(t, p.mesh), find_export_format(ext));
    ASSERT_GT(e.mesh_bytes, 50e6) << "a mesh large enough to measure";
    const int fits_mb = int(e.total_bytes() / 1e6) + 1, short_mb = int(e.total_bytes() / 1e6 * 0.9);
    const child_run made = run_measured(args_for(std::string("tree") + ext, fits_mb), dir / "made.err");
    EXPECT_EQ(made.code, 0) << made.err;
    const child_run refused = run_measured(args_for(std::string("refused") + ext, short_mb), dir / "refused.err");
    EXPECT_EQ(refused.code, 1) << ext;
    EXPECT_NE(refused.err.find("the mesh would take up to"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(dir / (std::string("refused") + ext)));
    EXPECT_LT(skeleton_only.peak_bytes + e.mesh_bytes * 0.5, made.peak_bytes) << ext << ": the mesh shows in the peak";
    EXPECT_LE(made.peak_bytes, skeleton_only.peak_bytes + e.total_bytes()) << ext;
    EXPECT_LT(refused.peak_bytes, skeleton_only.peak_bytes + 0.1 * e.mesh_bytes) << ext << ": refused before meshing";
    std::printf("%s: skeleton JSON peak %.0f MB; made %.0f MB (bound %.0f MB: mesh %.0f, writer %.0f); refused %.0f MB\n", ext,
                skeleton_only.peak_bytes / 1e6, made.peak_bytes / 1e6, e.total_bytes() / 1e6, e.mesh_bytes / 1e6,
                e.writer_bytes() / 1e6, refused.peak_bytes / 1e6);
  }
}

TEST(MeshBound, StatedInParams) {
  const std::string text = mesh_bound_text();
  EXPECT_NE(text.find("peak mesh memory <= mesh_budget (default 4000 MB, at most 32000 MB)"), std::string::npos) << text;
  // The per-node costs the text states are the bound's own.
  mesh_params d;
  const double per_node = mesh_bound_for_nodes(1e6, d, 1000, 0).peak_bytes / 1e6;
  char want[64];
  std::snprintf(want, sizeof want, "at most %.0f B a node", per_node);
  EXPECT_NE(text.find(want), std::string::npos) << text;
}
