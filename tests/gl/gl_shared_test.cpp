// Renderers in one GL context share its programs and procedural textures (render/gl/gl_shared.h):
// three renderers, as the editor's view, its slot B and the library's thumbnails hold, compile each
// program once instead of three times, draw with the same archetype textures, and the set outlives
// any one of them until the last is destroyed.
#include <gtest/gtest.h>

#include <cstdio>

#include "render/gl/renderer.h"
#include "tests/gl/gl_test_context.h"

using namespace sylva;

TEST(GlShared, RenderersInOneContextCompileEachProgramOnce) {
  if (!sylva_test::have_display()) GTEST_SKIP() << "no DISPLAY";
  sylva_test::gl_context ctx;
  ASSERT_TRUE(ctx.window);
  // Each on its own, as before: every renderer compiles every program.
  const int start = gl_programs_compiled();
  renderer_gpu alone[3];
  for (renderer_gpu& r : alone) ASSERT_TRUE(init_renderer(r)) << r.error;
  const int unshared = gl_programs_compiled() - start;
  for (renderer_gpu& r : alone) destroy_renderer(r);
  // Sharing: the first compiles, the others are given its set.
  const int mark = gl_programs_compiled();
  renderer_gpu view, slot_b, library;
  ASSERT_TRUE(init_renderer(view)) << view.error;
  const int one = gl_programs_compiled() - mark;
  ASSERT_TRUE(init_renderer(slot_b, view.shared)) << slot_b.error;
  ASSERT_TRUE(init_renderer(library, view.shared)) << library.error;
  std::printf("programs compiled for three renderers: %d each on its own, %d sharing one set\n", unshared,
              gl_programs_compiled() - mark);
  EXPECT_GT(one, 10);
  EXPECT_EQ(gl_programs_compiled() - mark, one) << "the second and third renderers compile nothing";
  EXPECT_EQ(unshared, 3 * one);
  EXPECT_EQ(view.shared->users, 3);
  EXPECT_EQ(slot_b.leaf_tex.id, view.leaf_tex.id) << "one upload of the leaf archetypes";
  EXPECT_EQ(library.bark_tex.id, view.bark_tex.id) << "and of each bark archetype";
  // The set stays while any renderer holds it: the view still draws once the other two are gone.
  destroy_renderer(slot_b);
  destroy_renderer(library);
  EXPECT_EQ(view.shared->users, 1);
  EXPECT_TRUE(view.shared->ok);
  const int errors = gl_error_count();
  orbit_camera cam;
  draw_frame(view, render_params{}, cam, 32, 32);
  glFinish();
  EXPECT_EQ(gl_error_count(), errors);
  destroy_renderer(view);
  EXPECT_EQ(view.shared, nullptr);
}
