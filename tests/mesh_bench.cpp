// Mesher speed: Honda tree f (issue 2's goal: grow + mesh well under 5 ms median).
#include <benchmark/benchmark.h>

#include "generators/lsystem.h"
#include "render/mesh.h"

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
