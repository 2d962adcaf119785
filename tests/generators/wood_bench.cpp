// The wood pass's cost (goal: under 10% of grow time on the 642,000-internode
// benchmark, bench/self_organizing_642k.json). The growth runs once; each iteration bends a copy.
#include <benchmark/benchmark.h>

#include "generators/self_organizing.h"
#include "generators/wood.h"

using namespace sylva;

static const tree_skeleton& tree_642k() {
  static const tree_skeleton t = [] {
    self_organizing_params p;   // the pinned settings of bench/self_organizing_642k.json
    p.steps = 67;
    p.node_cap = 642000;
    p.lambda = 0.5f;
    p.sigma = 0;
    p.bm = 0;
    p.shed_min_buds = 0;
    grow_options o;
    o.seed = 1;
    return grow_self_organizing(p, o);
  }();
  return t;
}

static void BM_WoodPass642k(benchmark::State& state) {
  const tree_skeleton& t = tree_642k();
  wood_params w;
  w.gravity = 1;
  for (auto _ : state) {
    state.PauseTiming();   // the copy is not the pass
    tree_skeleton c = t;
    state.ResumeTiming();
    apply_wood(c, w);
    benchmark::DoNotOptimize(c.position.data());
  }
  state.counters["nodes"] = double(t.size());
}
BENCHMARK(BM_WoodPass642k)->Unit(benchmark::kMillisecond);

// The same without reaction wood: what the recovery costs.
static void BM_WoodPass642kNoRecovery(benchmark::State& state) {
  const tree_skeleton& t = tree_642k();
  wood_params w;
  w.gravity = 1;
  w.recovery = 0;
  for (auto _ : state) {
    state.PauseTiming();
    tree_skeleton c = t;
    state.ResumeTiming();
    apply_wood(c, w);
    benchmark::DoNotOptimize(c.position.data());
  }
}
BENCHMARK(BM_WoodPass642kNoRecovery)->Unit(benchmark::kMillisecond);

static void BM_Grow642k(benchmark::State& state) {
  self_organizing_params p;
  p.steps = 67;
  p.node_cap = 642000;
  p.lambda = 0.5f;
  p.sigma = 0;
  p.bm = 0;
  p.shed_min_buds = 0;
  for (auto _ : state) {
    grow_options o;
    o.seed = 1;
    tree_skeleton t = grow_self_organizing(p, o);
    benchmark::DoNotOptimize(t.position.data());
  }
}
BENCHMARK(BM_Grow642k)->Unit(benchmark::kMillisecond);
