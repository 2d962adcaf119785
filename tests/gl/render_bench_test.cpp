// Renderer cost invariants: unchanged frames upload and allocate nothing, and leaves
// are one instanced draw per pass whatever their number. Runs under Xvfb; skipped without DISPLAY.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <new>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include "render/io/preset.h"
#include "tests/run_sylva.h"
#include "render/gl/renderer.h"
#include "tests/gl/gl_test_context.h"

// Counts heap allocations made through operator new, so a test can tell whether a frame allocates.
// Replacing the global operator is process-wide; it only adds a relaxed counter to the default.
namespace {
std::atomic<size_t> g_news{0};
}
// noinline: inlined, the free() below would pair with `new` at call sites and draw
// -Wmismatched-new-delete.
[[gnu::noinline]] void* operator new(std::size_t n) {
  g_news.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
[[gnu::noinline]] void operator delete(void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept { std::free(p); }

using namespace sylva;
using sylva_test::gl_context;
using sylva_test::have_display;

namespace {



// A leaves-only mesh of n leaves on a 10 m grid, all alive from step 0 on.
tree_mesh leaf_field(uint32_t n) {
  tree_mesh m;
  m.leaves.resize(n);
  const uint32_t side = 317;   // ~sqrt(100000)
  for (uint32_t i = 0; i < n; ++i) {
    leaf_instance& l = m.leaves[i];
    l.position = glm::vec3(float(i % side) / side * 10.0f - 5.0f, 1.0f + float(i / side) / side * 10.0f, 0.0f);
    l.orientation = glm::vec4(0, 0, 0, 1);
    l.size = 0.05f;
    l.born = 0;
    l.died = 0xffff;
    l.node = 0;
    l.texture = uint8_t(i % 4);
  }
  m.leaf_end = {n};
  m.index_end = {0};
  m.bounds_min = glm::vec3(-5, 0, -1);
  m.bounds_max = glm::vec3(5, 11, 1);
  return m;
}

}  // namespace

TEST(RenderBench, UnchangedSecondFrameUploadsAndAllocatesNothing) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  gl_context ctx;
  ASSERT_TRUE(ctx.window);
  renderer_gpu r;
  ASSERT_TRUE(init_renderer(r)) << r.error;
  preset p;
  p.spec.params = lsystem_params{};   // Honda's tree a: bark and leaves
  const tree_skeleton t = grow(p.spec, {});
  const tree_mesh m = mesh_tree(t, p.mesh, p.spec.seed);
  ASSERT_GT(m.leaves.size(), 0u);
  const size_t news_at_upload = g_news.load();
  upload_tree(r, m);   // copies the step tables: the allocation counter must see that
  EXPECT_GT(g_news.load(), news_at_upload);
  set_tree_step(r, t, p.mesh.min_radius, t.steps);
  orbit_camera cam;
  frame_camera(cam, r.bounds_min, r.bounds_max);

  // The first frame at a size allocates its render targets.
  draw_frame(r, p.render, cam, 160, 120);
  EXPECT_GT(r.counts.uploads, 0);
  const int draws = r.counts.draw_calls;

  // The same scene again: no GL uploads, no heap allocations on our side, the same draws.
  const size_t news_before = g_news.load();
  draw_frame(r, p.render, cam, 160, 120);
  const size_t news = g_news.load() - news_before;
  EXPECT_EQ(r.counts.uploads, 0);
  EXPECT_EQ(news, 0u);
  EXPECT_EQ(r.counts.draw_calls, draws);

  // Moving the camera or the sun changes only uniforms.
  cam.yaw += 20;
  p.render.sun_azimuth += 15;
  draw_frame(r, p.render, cam, 160, 120);
  EXPECT_EQ(r.counts.uploads, 0);

  // A new size does reallocate the targets: the counter sees real work.
  draw_frame(r, p.render, cam, 200, 120);
  EXPECT_GT(r.counts.uploads, 0);
  glFinish();
  destroy_renderer(r);
}

TEST(RenderBench, LeafDrawCallsDoNotGrowWithTheLeafCount) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  gl_context ctx;
  ASSERT_TRUE(ctx.window);
  renderer_gpu r;
  ASSERT_TRUE(init_renderer(r)) << r.error;
  orbit_camera cam;
  render_params rp;
  rp.msaa = 0;   // keep the software rasteriser's work small

  int draws_small = 0;
  for (uint32_t n : {10u, 100000u}) {
    const tree_mesh m = leaf_field(n);
    upload_tree(r, m);
    frame_camera(cam, r.bounds_min, r.bounds_max);
    rp.shadows = true;
    draw_frame(r, rp, cam, 96, 64);
    EXPECT_EQ(r.leaves_drawn, size_t(n));
    // All four leaf textures share one array texture: one instanced draw in the shadow pass, one in
    // the lit pass.
    EXPECT_EQ(r.counts.leaf_draw_calls, 2) << n << " leaves";
    if (n == 10) draws_small = r.counts.draw_calls;
    else EXPECT_EQ(r.counts.draw_calls, draws_small) << "the frame's draws depend on the leaf count";
    rp.shadows = false;   // no shadow pass: the lit pass's single draw remains
    draw_frame(r, rp, cam, 96, 64);
    EXPECT_EQ(r.counts.leaf_draw_calls, 1) << n << " leaves";
  }
  glFinish();
  EXPECT_EQ(check_gl("leaf draw test"), 0);
  destroy_renderer(r);
}

namespace {


}  // namespace

TEST(RenderBench, BenchRenderWithoutADisplayIsAClearFailure) {
  const sylva_run r = run_sylva("env -u DISPLAY -u WAYLAND_DISPLAY", "bench --render --repeat 1");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("DISPLAY"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST(RenderBench, BenchRenderReportsEveryPassAndTheFrameCounts) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const std::string preset = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";
  const sylva_run r =
      run_sylva("env", "bench --render --repeat 2 --json --width 96 --height 64 '" + preset + "'");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);   // one preset: one JSON line
  EXPECT_EQ(j["preset"], "lsystem_honda_a");
  EXPECT_EQ(j["width"], 96);
  EXPECT_EQ(j["height"], 64);
  // Ten derivations of Honda's binary production: 2^10 − 1 internodes plus the root node.
  EXPECT_EQ(j["nodes"], 1024);
  EXPECT_GT(j["leaves"].get<int>(), 0);
  // Backlit by default: every pass runs and takes time.
  for (const char* pass : {"shadow_ms", "lit_ms", "occlusion_ms", "blur_ms", "march_ms", "exposure_ms", "composite_ms"})
    EXPECT_GT(j[pass].get<double>(), 0.0) << pass;
  // The reported (volumetric) frame. Shadow: bark + leaves; lit: sky, ground, bark, leaves; then the
  // shafts' march, the auto-exposure reduction and the composite.
  EXPECT_EQ(j["draw_calls"], 9);
  EXPECT_EQ(j["leaf_draw_calls"], 2);
  EXPECT_EQ(j["uploads"], 0);   // the measured frames repeat the warm-up frame
}
