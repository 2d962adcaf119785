// The growth worker (app/common/worker.cpp): newest request wins, mesh-only edits reuse the skeleton, and
// a stress of many requests across every generator with a polling reader and stops mid-growth.
// `make tsan` runs this file under ThreadSanitizer.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "app/common/worker.h"

using namespace sylva;

namespace {
// Polls the worker (as the editor's frame loop does) until it publishes generation g, or 20 s pass.
std::shared_ptr<const grow_result> wait_for(worker_state& w, uint32_t g) {
  std::shared_ptr<const grow_result> r;
  uint32_t seen = 0;
  for (int i = 0; i < 2000; ++i) {
    if (auto x = take_result(w, seen)) {
      r = x;
      seen = x->generation;
      if (seen == g) return r;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return nullptr;
}
}  // namespace

TEST(GrowthWorker, NewestRequestWinsAndMeshEditsReuseTheSkeleton) {
  worker_state w;
  start_worker(w);
  lsystem_params big;
  big.derivations = 16;
  lsystem_params small;
  small.derivations = 6;
  mesh_params m;
  post_request(w, tree_spec{big, 1}, m);   // superseded at once: cancelled or never started
  const uint32_t g = post_request(w, tree_spec{small, 1}, m);
  auto r = wait_for(w, g);
  ASSERT_TRUE(r);
  // Honda with min = 0: n derivations give 2^n - 1 internodes plus the root, 2^6 = 64 nodes.
  EXPECT_EQ(r->skeleton->size(), 64u);
  EXPECT_TRUE(r->regrown);
  EXPECT_EQ(validate_mesh(r->mesh), "");

  mesh_params m2 = m;
  m2.radial_segments = 5;
  const uint32_t g2 = post_request(w, tree_spec{small, 1}, m2);
  auto r2 = wait_for(w, g2);
  ASSERT_TRUE(r2);
  EXPECT_FALSE(r2->regrown);
  EXPECT_EQ(r2->skeleton.get(), r->skeleton.get());   // the same tree, not regrown
  EXPECT_EQ(r2->mesh.radial_segments, 5);
  stop_worker(w);
}

TEST(GrowthWorker, OverlaysFollowARegrownTreeAndStayWithItsReMeshes) {
  worker_state w;
  start_worker(w);
  self_organizing_params p;
  p.steps = 8;
  mesh_params m;
  const uint32_t g = post_request(w, tree_spec{p, 3}, m);
  auto r = wait_for(w, g);
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->regrown);
  EXPECT_FALSE(r->overlays);   // published before its overlays: no slider release waits for them
  std::shared_ptr<const overlay_geometry> late;
  for (int i = 0; i < 2000 && !late; ++i) {
    late = take_late_overlays(w, *r);
    if (!late) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(late);
  // The overlays the worker built once idle are the ones built from the result's own debug.
  const overlay_geometry want = build_overlays(*r->debug, r->skeleton.get());
  EXPECT_GT(want.points.size(), 0u);
  EXPECT_EQ(late->points.size(), want.points.size());
  EXPECT_EQ(late->lines.size(), want.lines.size());
  EXPECT_EQ(late->present, want.present);
  // A re-mesh of the same growth carries them; a result they were not built for gets none.
  mesh_params m2 = m;
  m2.radial_segments = 5;
  auto r2 = wait_for(w, post_request(w, tree_spec{p, 3}, m2));
  ASSERT_TRUE(r2);
  EXPECT_FALSE(r2->regrown);
  EXPECT_EQ(r2->overlays.get(), late.get());
  EXPECT_FALSE(take_late_overlays(w, *r2));   // it has them already
  grow_result other;
  other.debug = std::make_shared<growth_debug>();
  EXPECT_FALSE(take_late_overlays(w, other));
  stop_worker(w);
}

namespace {
// Small specs of all four generators, so that a request grows in a few milliseconds to a second.
std::vector<tree_spec> stress_specs() {
  std::vector<tree_spec> specs;
  for (int g = 0; g < generator_count; ++g) {
    tree_spec s{default_params(g), uint64_t(g + 1)};
    std::visit(
        [](auto& p) {
          using P = std::decay_t<decltype(p)>;
          if constexpr (std::is_same_v<P, self_organizing_params>) p.steps = 8;
          if constexpr (std::is_same_v<P, space_colonization_params>) p.points = 600;
          if constexpr (std::is_same_v<P, guiding_vectors_params>) p.steps = 2;
          if constexpr (std::is_same_v<P, lsystem_params>) p.derivations = 7;
        },
        s.params);
    specs.push_back(s);
  }
  return specs;
}
}  // namespace

TEST(GrowthWorker, StressManyRequestsPollingReaderAndStops) {
  const std::vector<tree_spec> specs = stress_specs();
  for (int round = 0; round < 5; ++round) {
    worker_state w;
    start_worker(w);
    std::atomic<bool> done{false};
    std::atomic<int> seen_results{0};
    // The reader polls as the editor's frame loop does and reads every published result whole.
    std::thread reader([&] {
      uint32_t seen = 0;
      while (!done) {
        if (auto r = take_result(w, seen)) {
          seen = r->generation;
          ++seen_results;
          ASSERT_TRUE(r->skeleton);
          size_t n = 0;
          for (size_t i = 0; i < r->skeleton->size(); ++i) n += r->skeleton->parent[i] < int32_t(i);
          EXPECT_EQ(n, r->skeleton->size());
          EXPECT_TRUE(std::isfinite(r->grow_ms + r->mesh_ms));
        }
        std::this_thread::yield();
      }
    });
    mesh_params m;
    uint32_t last = 0;
    for (int i = 0; i < 120; ++i) {
      m.radial_segments = 5 + i % 4;   // some requests only change the mesh
      last = post_request(w, specs[size_t(i / 2) % specs.size()], m);
      std::this_thread::sleep_for(std::chrono::milliseconds(i % 7));
    }
    if (round < 4) {
      // The last round waits for the final result; the others stop mid-growth.
      std::this_thread::sleep_for(std::chrono::milliseconds(5 * round));
    } else {
      auto r = wait_for(w, last);
      ASSERT_TRUE(r);
      EXPECT_EQ(r->generation, last);
      EXPECT_GT(r->skeleton->size(), 1u);
      std::this_thread::sleep_for(std::chrono::milliseconds(50));   // the reader sees it too
      EXPECT_GT(seen_results.load(), 0);
    }
    stop_worker(w);
    done = true;
    reader.join();
    EXPECT_FALSE(w.thread.joinable());
  }
}

// The LOD chain off the UI thread (lod_worker): the newest request's chain arrives, once, and is
// the chain build_lods makes on the calling thread; an older request's is never handed out.
TEST(LodWorker, TheChainArrivesAndEqualsTheOneBuiltOnTheCallingThread) {
  lsystem_params l;
  l.derivations = 8;
  const tree_spec spec{l, 3};
  mesh_params mp;
  auto t = std::make_shared<const tree_skeleton>(grow(spec, grow_options{}));
  auto m = std::make_shared<const tree_mesh>(mesh_tree(*t, mp, spec.seed));
  lod_params p;
  const lod_chain here = build_lods(*t, *m, mp, p);
  lod_worker w;
  EXPECT_EQ(take_lod_result(w), nullptr);   // nothing asked for: no thread, nothing to take
  lod_params older = p;
  older.lod1_budget = p.lod1_budget / 2;
  post_lod_request(w, t, m, mp, older);    // superseded by the next request
  const uint32_t id = post_lod_request(w, t, m, mp, p);
  ASSERT_TRUE(wait_lod_result(w, id, 120000));
  const std::shared_ptr<const lod_result> r = take_lod_result(w);
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->id, id);
  ASSERT_NE(r->chain, nullptr);
  EXPECT_EQ(r->chain->triangles, here.triangles);
  EXPECT_EQ(r->chain->target, here.target);
  for (size_t k = 0; k < here.level.size(); ++k) {
    EXPECT_EQ(r->chain->level[k].position, here.level[k].position) << "LOD" << k + 1;
    EXPECT_EQ(r->chain->level[k].index, here.level[k].index) << "LOD" << k + 1;
    EXPECT_EQ(r->chain->level[k].leaves.size(), here.level[k].leaves.size()) << "LOD" << k + 1;
  }
  EXPECT_EQ(take_lod_result(w), nullptr);   // handed out once
}
