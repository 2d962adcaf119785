// Resuming a regrow (goal: editing a keyframe at step k and seeing the new tree takes no
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

// The self-organizing generator (shadow environment, defaults): 33 steps with a keyframe of λ at
// step 25 edited, and a forest of 4 such trees (100k+ nodes) with the same keyframe. Full regrow,
// the first (recording) growth and the resumed regrow.
namespace {
tree_spec so_keyed(int trees, float lambda) {
  tree_spec s;
  self_organizing_params p;
  p.steps = 33;
  p.tree_count = trees;
  s.params = p;
  s.seed = 1;
  s.keyframes.push_back({25, "lambda", glm::vec3(lambda, 0, 0)});
  return s;
}
}  // namespace

static void BM_SelfOrganizingKeyframeEditFullRegrow(benchmark::State& state) {
  int i = 0;
  size_t n = 0;
  for (auto _ : state) benchmark::DoNotOptimize(n = grow(so_keyed(int(state.range(0)), 0.6f + 0.01f * float(i++ % 2)), {}).size());
  state.counters["nodes"] = double(n);
}
BENCHMARK(BM_SelfOrganizingKeyframeEditFullRegrow)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);

static void BM_SelfOrganizingRecordingGrowth(benchmark::State& state) {
  for (auto _ : state) {
    growth_resume r;
    benchmark::DoNotOptimize(grow_resumable(so_keyed(int(state.range(0)), 0.6f), {}, tree_spec{}, r).size());
  }
}
BENCHMARK(BM_SelfOrganizingRecordingGrowth)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);

static void BM_SelfOrganizingKeyframeEditResumed(benchmark::State& state) {
  growth_resume r;
  tree_spec recorded = so_keyed(int(state.range(0)), 0.6f);
  grow_resumable(recorded, {}, tree_spec{}, r);
  int i = 0;
  for (auto _ : state) {
    const tree_spec next = so_keyed(int(state.range(0)), 0.61f + 0.01f * float(i++ % 2));   // differs from the recorded one
    benchmark::DoNotOptimize(grow_resumable(next, {}, recorded, r).size());
    if (r.resumed_at != 25) state.SkipWithError("did not resume at 25");
    recorded = next;
  }
}
BENCHMARK(BM_SelfOrganizingKeyframeEditResumed)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);

// Space colonization (defaults but the point count; growth ends near step 50 when the points run
// out): a keyframe of the tropism weight at step 36 edited, with 10,000 and 200,000 points.
namespace {
tree_spec sc_keyed(int points, float w) {
  tree_spec s;
  space_colonization_params p;
  p.points = points;
  s.params = p;
  s.keyframes.push_back({36, "tropism_weight", glm::vec3(w, 0, 0)});
  return s;
}
}  // namespace

static void BM_SpaceColonizationKeyframeEditFullRegrow(benchmark::State& state) {
  int i = 0;
  size_t n = 0;
  for (auto _ : state) benchmark::DoNotOptimize(n = grow(sc_keyed(int(state.range(0)), 0.1f + 0.01f * float(i++ % 2)), {}).size());
  state.counters["nodes"] = double(n);
}
BENCHMARK(BM_SpaceColonizationKeyframeEditFullRegrow)->Arg(10000)->Arg(200000)->Unit(benchmark::kMillisecond);

static void BM_SpaceColonizationKeyframeEditResumed(benchmark::State& state) {
  growth_resume r;
  tree_spec recorded = sc_keyed(int(state.range(0)), 0.1f);
  grow_resumable(recorded, {}, tree_spec{}, r);
  int i = 0;
  for (auto _ : state) {
    const tree_spec next = sc_keyed(int(state.range(0)), 0.11f + 0.01f * float(i++ % 2));
    benchmark::DoNotOptimize(grow_resumable(next, {}, recorded, r).size());
    if (r.resumed_at != 36) state.SkipWithError("did not resume at 36");
    recorded = next;
  }
}
BENCHMARK(BM_SpaceColonizationKeyframeEditResumed)->Arg(10000)->Arg(200000)->Unit(benchmark::kMillisecond);
