// Mesher speed: Honda tree f (goal: grow + mesh well under 5 ms median).
#include <benchmark/benchmark.h>

#include "generators/lsystem.h"
#include "render/mesh/mesh.h"

using namespace sylva;

static lsystem_params honda_f() {
  lsystem_params p;
  p.s0 = 100, p.w0 = 2, p.q = 0.5f, p.e = 0, p.min_length = 0.5f;
  p.alpha1 = 0, p.alpha2 = 60, p.phi1 = 180, p.phi2 = 0, p.r1 = 0.92f, p.r2 = 0.37f, p.derivations = 15;
  return p;
}

static void BM_GrowAndMeshHondaF(benchmark::State& state) {
  const lsystem_params p = honda_f();
  size_t tris = 0;
  for (auto _ : state) {
    tree_skeleton t = grow_honda(p, {});
    tree_mesh m = mesh_tree(t, mesh_params{});
    tris = m.triangles();
    benchmark::DoNotOptimize(m.index.data());
  }
  state.counters["triangles"] = double(tris);
}
BENCHMARK(BM_GrowAndMeshHondaF)->Unit(benchmark::kMillisecond);

static void BM_MeshHondaF(benchmark::State& state) {
  const tree_skeleton t = grow_honda(honda_f(), {});
  for (auto _ : state) {
    tree_mesh m = mesh_tree(t, mesh_params{});
    benchmark::DoNotOptimize(m.index.data());
  }
  state.counters["nodes"] = double(t.size());
}
BENCHMARK(BM_MeshHondaF)->Unit(benchmark::kMillisecond);

#include <filesystem>

#include "render/io/export.h"

// Issue 8's goal: GLB export of a ~1,000,000-triangle tree under 1 s (tree a, 15 derivations,
// 16 radial segments: 32767 internodes * 32 triangles + leaves), written to a temporary folder.
static void BM_ExportGlbMillionTriangles(benchmark::State& state) {
  lsystem_params lp;
  lp.derivations = 15;
  const tree_skeleton t = grow_honda(lp, {});
  mesh_params p;
  p.radial_segments = 16;
  const tree_mesh m = mesh_tree(t, p);
  export_options o;
  o.mesh = p;
  const std::string path = (std::filesystem::temp_directory_path() / "sylva_bench_export.glb").string();
  export_result r;
  for (auto _ : state) r = export_tree(t, m, {"lsystem", 1}, path, o);
  std::filesystem::remove(path);
  state.counters["triangles"] = double(r.triangles);
  state.counters["file_MB"] = double(r.bytes) / 1e6;
}
BENCHMARK(BM_ExportGlbMillionTriangles)->Unit(benchmark::kMillisecond)->Iterations(3);

// Issue 11: a 100,000-leaf tree places its foliage in < 10 ms. A binary tree of 2^13 shoots of
// 0.5 m with a leaf node every 4 cm, one leaf each: ~102,000 leaves.
static void BM_PlaceShootLeaves100k(benchmark::State& state) {
  sylva::tree_skeleton t;
  t.add_node({0, 0, 0}, -1, 0.2f, 0, 0);
  for (size_t i = 0; t.size() < 8192; ++i)
    for (int side = -1; side <= 1; side += 2) {
      const glm::vec3 p = t.position[i] + glm::vec3(0.2f * float(side), 0.45f, 0.1f * float(side * (int(i) % 3 - 1)));
      t.add_node(p, int32_t(i), 0.01f, uint16_t(1), uint8_t(std::min<size_t>(i, 7)));
    }
  t.steps = 1;
  sylva::leaf_params p;
  p.spacing = 0.04f;
  size_t leaves = 0;
  for (auto _ : state) {
    auto f = sylva::place_shoot_leaves(t, p, 1);
    leaves = f.leaves.size();
    benchmark::DoNotOptimize(f.leaves.data());
  }
  state.counters["leaves"] = double(leaves);
}
BENCHMARK(BM_PlaceShootLeaves100k)->Unit(benchmark::kMillisecond);
