// Picking speed (goal: a branch under the mouse within one frame for 100,000 nodes).
#include <benchmark/benchmark.h>

#include "generators/lsystem.h"
#include "render/mesh/pick.h"

using namespace sylva;

static void BM_PickBranch(benchmark::State& state) {
  lsystem_params p;   // Honda's tree with 17 derivations: 131,071 nodes
  p.derivations = 17;
  const tree_skeleton t = grow_honda(p, {});
  const std::vector<float> radii = radii_at_step(t, t.steps);
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const glm::vec3& q : t.position) lo = glm::min(lo, q), hi = glm::max(hi, q);
  const glm::vec3 centre = 0.5f * (lo + hi);
  const glm::vec3 eye = centre + glm::vec3(0, 0, 3 * (hi.y - lo.y));
  int hits = 0;
  for (auto _ : state) {
    const pick_hit h = pick_branch(t, radii, t.steps, eye, centre - eye, 0.002f);
    hits += h.node >= 0;
    benchmark::DoNotOptimize(h);
  }
  state.counters["nodes"] = double(t.size());
  state.counters["hit"] = hits > 0 ? 1 : 0;
}
BENCHMARK(BM_PickBranch)->Unit(benchmark::kMillisecond);
