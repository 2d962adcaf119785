// Wind in the viewport: two moments of the swaying tree differ in pixels with the wind on and are
// identical with it off, with no upload per frame. The CPU side (sway data, skin, loop, glTF) is
// tests/render/mesh/wind_test.cpp.
#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "tests/gl/gl_test_context.h"
#include "tests/wind_tree.h"

using namespace sylva;
using honda = sylva_test::honda_tree;
using sylva_test::blowing;

class WindRender : public sylva_test::renderer_test {};

TEST_F(WindRender, TwoMomentsDifferWithWindAndMatchWithout) {
  honda h(7);
  upload_tree(r, h.m);
  upload_wind(r, h.t);
  set_tree_step(r, h.t, h.p.min_radius, h.t.steps);
  gl_texture color;
  gl_framebuffer target;
  const int w = 160, hgt = 160;
  ASSERT_EQ(create_color_target(w, hgt, color, target), "");
  glBindFramebuffer(GL_FRAMEBUFFER, target.id);
  orbit_camera cam;
  frame_camera(cam, r.bounds_min, r.bounds_max, 1.0f);
  render_params rp;
  rp.msaa = 0;
  rp.shafts = light_shafts::off;
  auto frame = [&](float time) {
    r.wind_time = time;
    draw_frame(r, rp, cam, w, hgt, target);
    std::vector<uint8_t> px(size_t(w) * hgt * 4);
    glBindFramebuffer(GL_FRAMEBUFFER, target.id);
    glReadPixels(0, 0, w, hgt, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    return px;
  };
  auto differing = [](const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    size_t n = 0;
    for (size_t i = 0; i < a.size(); i += 4) n += std::abs(int(a[i]) - int(b[i])) + std::abs(int(a[i + 1]) - int(b[i + 1])) > 24;
    return n;
  };
  const auto calm0 = frame(0.0f), calm1 = frame(1.7f);
  EXPECT_EQ(calm0, calm1) << "without wind, time changes nothing";
  rp.wind = blowing();
  const auto a = frame(0.0f);
  const int uploads_before = int(r.uploads_total);
  const auto b = frame(1.7f);
  EXPECT_EQ(int(r.uploads_total), uploads_before) << "no upload per frame: time is a uniform";
  EXPECT_EQ(r.counts.leaf_draw_calls, 2) << "one leaf call per pass, as without wind";
  // Five programs sway (bark and leaves, lit and shadow); the motion is computed once for the frame.
  EXPECT_EQ(r.counts.wind_motions, 1);
  EXPECT_GT(differing(a, b), size_t(w * hgt / 400)) << "the tree moved";
  EXPECT_EQ(frame(1.7f), b) << "the same moment draws the same image";
  delete_gl(target);
  delete_gl(color);
}
