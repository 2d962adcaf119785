// The wood pass's cost (goal: under 10% of grow time on the 642,000-internode
// benchmark, bench/self_organizing_642k.json). The growth runs once; each iteration bends a copy.
#include <benchmark/benchmark.h>

#include "generators/job_pool.h"
#include "generators/self_organizing.h"
#include "generators/wood.h"

using namespace sylva;

// The pinned settings of bench/self_organizing_642k.json.
static self_organizing_params params_642k() {
  self_organizing_params p;
  p.steps = 67;
  p.node_cap = 642000;
  p.lambda = 0.5f;
  p.sigma = 0;
  p.bm = 0;
  p.shed_min_buds = 0;
  return p;
}

static const tree_skeleton& tree_642k() {
  static const tree_skeleton t = [] {
    grow_options o;
    o.seed = 1;
    return grow_self_organizing(params_642k(), o);
  }();
  return t;
}

// Bends a fresh copy of t per iteration (the copy is not timed), with the job pool capped at
// `threads` (0: all of it; 1: the pass's one-thread sweeps).
static void bend(benchmark::State& state, const tree_skeleton& t, const wood_params& w, int threads = 0) {
  const int old = set_job_pool_limit(threads);
  for (auto _ : state) {
    state.PauseTiming();
    tree_skeleton c = t;
    state.ResumeTiming();
    apply_wood(c, w);
    benchmark::DoNotOptimize(c.position.data());
  }
  set_job_pool_limit(old);
  state.counters["nodes"] = double(t.size());
}
static void bend_642k(benchmark::State& state, const wood_params& w) { bend(state, tree_642k(), w); }

static void BM_WoodPass642k(benchmark::State& state) {
  wood_params w;
  w.gravity = 1;
  bend_642k(state, w);
}
BENCHMARK(BM_WoodPass642k)->Unit(benchmark::kMillisecond);

// The same without reaction wood: what the recovery costs.
static void BM_WoodPass642kNoRecovery(benchmark::State& state) {
  wood_params w;
  w.gravity = 1;
  w.recovery = 0;
  bend_642k(state, w);
}
BENCHMARK(BM_WoodPass642kNoRecovery)->Unit(benchmark::kMillisecond);

static void BM_Grow642k(benchmark::State& state) {
  const self_organizing_params p = params_642k();
  for (auto _ : state) {
    grow_options o;
    o.seed = 1;
    tree_skeleton t = grow_self_organizing(p, o);
    benchmark::DoNotOptimize(t.position.data());
  }
}
BENCHMARK(BM_Grow642k)->Unit(benchmark::kMillisecond);

// Trees around the pool's threshold (wood.cpp: 16,384 nodes), on one thread (Arg 1) and on the
// pool (Arg 0): the default tree and its 19,723 nodes, and the 642k tree.
static void wood_threads(benchmark::State& state, const tree_skeleton& t) {
  wood_params w;
  w.gravity = 1;
  bend(state, t, w, int(state.range(0)));
}
static void BM_WoodPassDefaultThreads(benchmark::State& state) {
  static const tree_skeleton t = [] {
    grow_options o;
    o.seed = 1;
    return grow_self_organizing(self_organizing_params{}, o);
  }();
  wood_threads(state, t);
}
BENCHMARK(BM_WoodPassDefaultThreads)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);
static void BM_WoodPass642kThreads(benchmark::State& state) { wood_threads(state, tree_642k()); }
BENCHMARK(BM_WoodPass642kThreads)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);
