// The viewport impostor's shadow: the shadow pass draws a card facing the sun (the atlas
// view nearest the sun's azimuth), so its ground shadow keeps the crown's shape whatever the camera.
// Measured as the area of shadowed ground seen from above, against LOD0's at the same sun.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "generators/tree_spec.h"
#include "tests/gl/gl_test_context.h"
#include "render/gl/impostor.h"
#include "render/io/preset.h"

using namespace sylva;

namespace {

constexpr int size = 400;

class LodImpostorShadow : public sylva_test::renderer_test {
 protected:
  gl_texture color;
  gl_framebuffer fbo;
  void TearDown() override {
    if (ready) glBindFramebuffer(GL_FRAMEBUFFER, 0), delete_gl(fbo), delete_gl(color);
    renderer_test::TearDown();
  }
  std::vector<unsigned char> frame(const render_params& rp, const orbit_camera& cam) {
    draw_frame(r, rp, cam, size, size, fbo);
    std::vector<unsigned char> px(size_t(size) * size * 4);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, size, size, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    return px;
  }
  // Ground pixels darkened by the tree's shadow and not covered by the tree itself (`tree`).
  std::vector<bool> shadow(const tree_mesh& m, const tree_skeleton& t, render_params rp, const orbit_camera& cam,
                           std::vector<bool>& tree) {
    upload_tree(r, m);
    set_tree_step(r, t, 0.0005f, t.steps);
    rp.shadows = true;
    const auto lit = frame(rp, cam);
    rp.shadows = false;
    const auto unshadowed = frame(rp, cam);
    rp.ground = false;   // the tree against the plain sky below the horizon
    const auto alone = frame(rp, cam);
    upload_tree(r, tree_mesh{});
    const auto empty = frame(rp, cam);
    std::vector<bool> out(lit.size() / 4);
    tree.assign(out.size(), false);
    for (size_t i = 0; i < out.size(); ++i) {
      int dark = 0, d = 0;
      for (int c = 0; c < 3; ++c) {
        dark += int(unshadowed[i * 4 + c]) - int(lit[i * 4 + c]);
        d += std::abs(int(alone[i * 4 + c]) - int(empty[i * 4 + c]));
      }
      tree[i] = d > 6;
      out[i] = dark > 24;
    }
    return out;
  }
};

size_t count_outside(const std::vector<bool>& s, const std::vector<bool>& a, const std::vector<bool>& b) {
  size_t n = 0;
  for (size_t i = 0; i < s.size(); ++i) n += s[i] && !a[i] && !b[i];
  return n;
}

}  // namespace

TEST_F(LodImpostorShadow, SunCardShadowMatchesLod0AndIgnoresTheCamera) {
  ASSERT_EQ(create_color_target(size, size, color, fbo), "");
  auto [p, t, m] = show_preset("species_oak");
  const impostor_atlas a = render_impostor(r, p.render, 8, 256);
  ASSERT_EQ(a.error, "");
  const auto layers = impostor_layers(a);
  render_params rp = p.render;
  rp.shafts = light_shafts::off;
  rp.fog_density = 0;
  rp.haze = 0;
  rp.auto_exposure = false;
  rp.msaa = 0;
  rp.sun_elevation = 40;
  rp.sun_azimuth = -160;
  // From above, framing the tree's base and the crown's shadow.
  const glm::vec3 lo = m.bounds_min, hi = m.bounds_max, c = 0.5f * (lo + hi), s = sun_direction(rp);
  const glm::vec3 cast = c - s * (c.y / s.y);
  orbit_camera cam;
  cam.target = glm::vec3(0.5f * (c.x + cast.x), 0, 0.5f * (c.z + cast.z));
  cam.pitch = 89.5f;   // straight down: turning the camera turns the image only
  const float reach = 0.5f * glm::length(glm::vec2(cast.x - c.x, cast.z - c.z)) + 0.6f * glm::length(glm::vec2(hi.x - lo.x, hi.z - lo.z));
  cam.distance = hi.y + reach / std::tan(glm::radians(0.5f * cam.fov));
  const float sun = impostor_sun_azimuth(rp);
  // The camera's card faces a far camera at the overhead camera's yaw (the overhead eye itself stands
  // over the shadow, off the tree's axis).
  auto azimuth = [&] { return cam.yaw; };
  std::vector<bool> tree0, tree1, tree2, tree3;
  cam.yaw = 35;
  const auto full = shadow(m, t, rp, cam, tree0);
  const auto imp = shadow(impostor_mesh(a, layers, m, azimuth(), sun), t, rp, cam, tree1);
  // The camera turned by 90 degrees about the vertical: the camera's card turns, the sun's does not.
  cam.yaw = 125;
  const auto imp_turned = shadow(impostor_mesh(a, layers, m, azimuth(), sun), t, rp, cam, tree2);
  const auto full_turned = shadow(m, t, rp, cam, tree3);
  // The old flat sheet: the shadow pass drew the camera's card. From yaw 125 it stands 75 degrees
  // off the sun, nearly edge-on to it.
  std::vector<bool> tree4;
  const auto sheet = shadow(impostor_mesh(a, layers, m, azimuth(), azimuth()), t, rp, cam, tree4);
  const double n_full = double(count_outside(full, tree0, tree1)), n_imp = double(count_outside(imp, tree0, tree1));
  const double n_full_turned = double(count_outside(full_turned, tree3, tree2));
  const double n_imp_turned = double(count_outside(imp_turned, tree3, tree2));
  const double n_sheet = double(count_outside(sheet, tree3, tree4));
  std::printf("shadow px from above: LOD0 %.0f, impostor %.0f (%.3f), camera turned 90: LOD0 %.0f, impostor %.0f (%.3f); "
              "camera-facing sheet %.0f (%.3f)\n",
              n_full, n_imp, n_imp / n_full, n_full_turned, n_imp_turned, n_imp_turned / n_imp, n_sheet, n_sheet / n_full);
  // Measured (oak, sun 40 degrees up): impostor / LOD0 0.838, turned / unturned 0.983, the old sheet
  // 0.145. The flat card misses the crown's depth along the sun, hence the 0.2 tolerance.
  ASSERT_GT(n_full, 2000.0);
  EXPECT_NEAR(n_imp / n_full, 1.0, 0.2);
  EXPECT_NEAR(n_imp_turned / n_imp, 1.0, 0.03);
  EXPECT_LT(n_sheet / n_full_turned, 0.7);   // the test tells the old sheet from the sun's card
}
