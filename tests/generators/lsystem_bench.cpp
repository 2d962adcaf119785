// L-system derivation speed: a bracketed D0L and a parametric system with conditions.
#include <benchmark/benchmark.h>

#include "generators/lsystem_engine.h"

using namespace sylva;

// ABOP Fig. 1.24a, n = 8: L(n+1) = L(n) + 10·5^n gives 976,561 modules.
static const char* d0l_source = "#angle 25.7\n#axiom F\nF -> F[+F]F[-F]F\n";
// Honda's production with a condition, n = 17: 1 + 11·(2^17 − 1) = 1,441,782 modules.
static const char* parametric_source =
    "#define r1 0.75\n#define r2 0.77\n#define min 0\n#define q 0.5\n#define e 0.4\n#axiom A(100,30)\n"
    "A(s,w) : s >= min -> !(w)F(s)[+(35)/(0)A(s*r1,w*q^e)][+(-35)/(137)A(s*r2,w*(1-q)^e)]\n";

static void derive_bench(benchmark::State& state, const char* source, int n) {
  lsystem_program prog;
  compile_lsystem(source, prog);
  size_t modules = 0, bytes = 0;
  for (auto _ : state) {
    lsystem_derive_report rep;
    lsystem_string s = derive_lsystem(prog, n, 1, 50000000, {}, rep);
    modules = s.modules.size();
    bytes = s.modules.size() * sizeof(lsystem_module) + s.params.size() * sizeof(float);
    benchmark::DoNotOptimize(s.modules.data());
  }
  state.counters["modules"] = double(modules);
  state.counters["bytes_per_module"] = double(bytes) / double(modules);
}

static void BM_DeriveD0L(benchmark::State& state) { derive_bench(state, d0l_source, 8); }
BENCHMARK(BM_DeriveD0L)->Unit(benchmark::kMillisecond);

static void BM_DeriveParametric(benchmark::State& state) { derive_bench(state, parametric_source, 17); }
BENCHMARK(BM_DeriveParametric)->Unit(benchmark::kMillisecond);

// Derivation plus turtle interpretation, as `sylva bench` measures grow_ms.
static void grow_bench(benchmark::State& state, const char* source, int n) {
  lsystem_params p;
  p.mode = lsystem_mode::text;
  p.source = source;
  p.derivations = n;
  size_t nodes = 0;
  for (auto _ : state) {
    tree_skeleton t = grow_lsystem(p, {});
    nodes = t.size();
    benchmark::DoNotOptimize(t.position.data());
  }
  state.counters["nodes"] = double(nodes);
}
static void BM_GrowD0L(benchmark::State& state) { grow_bench(state, d0l_source, 8); }
BENCHMARK(BM_GrowD0L)->Unit(benchmark::kMillisecond);
static void BM_GrowParametric(benchmark::State& state) { grow_bench(state, parametric_source, 17); }
BENCHMARK(BM_GrowParametric)->Unit(benchmark::kMillisecond);
