// Archetype texture generation (goal: all 9 leaf and 5 bark sets at 512 px in < 300 ms on
// the two-core development machine, wall clock, two threads).
#include <benchmark/benchmark.h>

#include "render/assets/textures.h"

using namespace sylva;

static void BM_AllArchetypeTextures512(benchmark::State& state) {
  size_t bytes = 0;
  for (auto _ : state) bytes = make_all_archetype_textures(512, 1, int(state.range(0)));
  state.counters["MB"] = double(bytes) / 1048576.0;
}
BENCHMARK(BM_AllArchetypeTextures512)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
