// Resuming a regrow (issue 18's goal: editing a keyframe at step k and seeing the new tree takes no
// longer than a full regrow). Honda's tree with 17 derivations (131,071 nodes), a keyframe at
// derivation 14 edited: the full regrow, the first (recording) growth, and the resumed regrow.
#include <benchmark/benchmark.h>

#include "generators/keyframes.h"
#include "generators/resume.h"

using namespace sylva;

namespace {
tree_spec keyed(float alpha) {
  tree_spec s;
  lsystem_params p;
  p.derivations = 17;
  s.params = p;
  s.keyframes.push_back({14, "alpha1", glm::vec3(alpha, 0, 0)});
  return s;
}
}  // namespace

static void BM_HondaKeyframeEditFullRegrow(benchmark::State& state) {
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(grow(keyed(20.0f + float(i++ % 2)), {}).size());
}
BENCHMARK(BM_HondaKeyframeEditFullRegrow)->Unit(benchmark::kMillisecond);

static void BM_HondaRecordingGrowth(benchmark::State& state) {
  for (auto _ : state) {
    growth_resume r;
    benchmark::DoNotOptimize(grow_resumable(keyed(20.0f), {}, tree_spec{}, r).size());
  }
}
BENCHMARK(BM_HondaRecordingGrowth)->Unit(benchmark::kMillisecond);

static void BM_HondaKeyframeEditResumed(benchmark::State& state) {
  growth_resume r;
  tree_spec recorded = keyed(20.0f);
  grow_resumable(recorded, {}, tree_spec{}, r);
  int i = 0;
  for (auto _ : state) {
    const tree_spec next = keyed(21.0f + float(i++ % 2));   // every edit differs from the recorded one
    benchmark::DoNotOptimize(grow_resumable(next, {}, recorded, r).size());
    if (r.resumed_at != 14) state.SkipWithError("did not resume at 14");
    recorded = next;
  }
}
BENCHMARK(BM_HondaKeyframeEditResumed)->Unit(benchmark::kMillisecond);
