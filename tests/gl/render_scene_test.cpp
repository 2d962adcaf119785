// The low-sun scene: the physical sky (CPU model), volumetric light shafts through an occluder
// with a hole, and bad lighting input (no NaN, no GL error). GL tests run under Xvfb.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <thread>
#include <vector>

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render/gl/renderer.h"
#include "tests/gl/gl_test_context.h"
#include "render/gl/sky.h"

using namespace sylva;
using sylva_test::gl_context;
using sylva_test::have_display;
using LightShafts = sylva_test::renderer_test;

namespace {


bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }


using float_target = sylva_test::color_target<float>;

// A vertical wall in the plane z = 0 (x in [-20, 20], y in [0, 20]) with a square hole of side 1.5 m
// centred at (0, 3): bark triangles of node 0, radius 0 (no inflation).
tree_mesh wall_with_hole() {
  tree_mesh m;
  auto quad = [&](float x0, float y0, float x1, float y1) {
    const uint32_t b = uint32_t(m.position.size());
    for (glm::vec2 c : {glm::vec2(x0, y0), glm::vec2(x1, y0), glm::vec2(x1, y1), glm::vec2(x0, y1)}) {
      m.position.push_back(glm::vec3(c, 0.0f));
      m.normal.push_back(glm::vec3(0, 0, 1));
      m.uv.push_back(c);
      m.node.push_back(0);
    }
    // Both windings: the wall casts a shadow whichever face the shadow pass culls.
    for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u, 0u, 2u, 1u, 0u, 3u, 2u}) m.index.push_back(b + i);
  };
  quad(-20, 0, 20, 2.25f);       // below the hole
  quad(-20, 3.75f, 20, 20);      // above
  quad(-20, 2.25f, -0.75f, 3.75f);
  quad(0.75f, 2.25f, 20, 3.75f);
  m.index_end = {uint32_t(m.index.size())};
  m.leaf_end = {0};
  m.final_radius = {0.0f};
  m.bounds_min = glm::vec3(-20, 0, -0.5f);
  m.bounds_max = glm::vec3(20, 20, 0.5f);
  m.radial_segments = 3;
  return m;
}

float luma(const std::vector<float>& px, int w, int x, int y) {
  const float* p = &px[(size_t(y) * w + x) * 4];
  return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
}

}  // namespace

TEST(PhysicalSky, GoldenHourSunIsRedderAndDimmerThanNoon) {
  render_params p;
  sky_model noon, low;
  p.sun_elevation = 60;
  compute_sky(p, noon);
  p.sun_elevation = 4;
  compute_sky(p, low);
  EXPECT_GT(low.sun_light.x / low.sun_light.z, 1.5f * noon.sun_light.x / noon.sun_light.z);
  EXPECT_LT(low.sun_light.y, noon.sun_light.y);
  // The noon sky is blue overhead, and the sky lights an upward face more than a downward one.
  const glm::vec3 up = sky_radiance(noon, glm::vec3(0, 1, 0));
  EXPECT_GT(up.z, up.x);
  EXPECT_GT((noon.sh[0] + noon.sh[2]).z, (noon.sh[0] - noon.sh[2]).z);
}

TEST(PhysicalSky, ExtremesStayFiniteAndNonNegative) {
  for (float elevation : {-10.0f, -1.0f, 0.0f, 0.5f, 45.0f, 90.0f})
    for (float turbidity : {1.7f, 10.0f, 0.0f, 100.0f}) {
      render_params p;
      p.sun_elevation = elevation;
      p.turbidity = turbidity;
      sky_model s;
      compute_sky(p, s);
      ASSERT_TRUE(finite(s.sun_light)) << elevation << " " << turbidity;
      for (const glm::vec3& c : s.sh) ASSERT_TRUE(finite(c));
      for (glm::vec3 d : {glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), glm::normalize(glm::vec3(1, -1, 0)), s.sun_dir}) {
        const glm::vec3 L = sky_radiance(s, d);
        ASSERT_TRUE(finite(L)) << elevation << " " << turbidity;
        EXPECT_GE(std::min({L.x, L.y, L.z}), 0.0f);
      }
      // Below the horizon the sky dims but never goes black.
      EXPECT_GT(sky_radiance(s, glm::vec3(0, 1, 0)).z, 0.0f);
      if (elevation < -3.0f) {   // the sun fades out over the first degrees below the horizon
        EXPECT_EQ(s.sun_light, glm::vec3(0));
      }
    }
}

// Sun low in +Z, a wall with a hole facing it, seen from the side (the camera in the wall's shadow):
// the air behind the hole is lit, the air beside it is not, so the beam is brighter than its
// surroundings.
TEST_F(LightShafts, BeamBehindAHoleIsBrighterThanBesideIt) {
  const tree_mesh m = wall_with_hole();
  upload_tree(r, m);
  const float zero[2] = {0.0f, 0.0f};   // node 0: built at radius 0, shown at radius 0
  glBindBuffer(GL_TEXTURE_BUFFER, r.node_radius.id);
  glBufferSubData(GL_TEXTURE_BUFFER, 0, sizeof zero, zero);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);

  render_params rp;
  rp.sun_azimuth = 0;   // toward +Z
  rp.sun_elevation = 4;
  rp.ground_color = glm::vec3(0.02f);   // a dark ground ends every view ray inside the wall's shadow
  // A dim grey sky and no sky light in the fog: what lights the air is the sun alone.
  rp.physical_sky = false;
  rp.sky_zenith = rp.sky_horizon = glm::vec3(0.05f);
  rp.sun_color = glm::vec3(1);
  rp.ambient = 0;
  rp.auto_exposure = false;
  rp.exposure = 0.5f;
  rp.fog_density = 0.1f;
  rp.fog_height = 100;
  rp.haze = 0;
  rp.scattering_g = 0;   // isotropic: the side view sees the beam as well as the sun
  rp.msaa = 0;
  orbit_camera cam;
  cam.target = glm::vec3(0, 3, -4);
  cam.yaw = 90;   // looking along -X at the air behind the wall
  cam.pitch = 20;
  cam.distance = 12;
  const int w = 160, h = 120;
  float_target target(w, h);
  const int errors = gl_error_count();

  auto pixel = [&](glm::vec3 world) {
    const glm::mat4 vp = camera_projection(cam, float(w) / float(h), 0.1f, 1000.0f) * camera_view(cam);
    const glm::vec4 c = vp * glm::vec4(world, 1.0f);
    return glm::ivec2((c.x / c.w * 0.5f + 0.5f) * w, (c.y / c.w * 0.5f + 0.5f) * h);   // GL rows: bottom up
  };
  // The beam drops with the sun's elevation behind the wall.
  const float z = -4, beam_y = 3 + z * std::tan(glm::radians(rp.sun_elevation));
  auto mean = [&](const std::vector<float>& px, float y) {
    float sum = 0;
    int n = 0;
    for (float zz = -3; zz >= -5; zz -= 0.5f) {
      const glm::ivec2 q = pixel(glm::vec3(0, y + zz * std::tan(glm::radians(rp.sun_elevation)) - z * std::tan(glm::radians(rp.sun_elevation)), zz));
      if (q.x < 0 || q.y < 0 || q.x >= w || q.y >= h) continue;
      sum += luma(px, w, q.x, q.y);
      ++n;
    }
    return n ? sum / float(n) : -1.0f;
  };

  rp.shafts = light_shafts::volumetric;
  draw_frame(r, rp, cam, w, h, target.fbo);
  const std::vector<float> on = target.read();
  const float beam = mean(on, beam_y), above = mean(on, beam_y + 1.6f), below = mean(on, beam_y - 1.6f);
  ASSERT_GE(beam, 0.0f);
  ASSERT_GE(above, 0.0f);
  ASSERT_GE(below, 0.0f);
  EXPECT_GT(beam, above * 1.1f + 0.01f) << "beam " << beam << " above " << above;
  EXPECT_GT(beam, below * 1.1f + 0.01f) << "beam " << beam << " below " << below;

  // Without the volumetric pass the fog is the same everywhere at that distance: no beam.
  rp.shafts = light_shafts::off;
  draw_frame(r, rp, cam, w, h, target.fbo);
  const std::vector<float> off = target.read();
  EXPECT_LT(std::abs(mean(off, beam_y) - mean(off, beam_y + 1.6f)), 0.02f);
  glFinish();
  EXPECT_EQ(check_gl("shaft test"), 0);
  EXPECT_EQ(gl_error_count(), errors);
}

// Bad lighting input: a sun below the horizon, turbidity and fog at their extremes, tiny and
// zero-size views. Every pixel stays finite and GL reports no error.
TEST_F(LightShafts, BadLightingInputGivesNoNaNAndNoGLError) {
  const tree_mesh m = wall_with_hole();
  upload_tree(r, m);
  const float zero[2] = {0.0f, 0.0f};
  glBindBuffer(GL_TEXTURE_BUFFER, r.node_radius.id);
  glBufferSubData(GL_TEXTURE_BUFFER, 0, sizeof zero, zero);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  orbit_camera cam;
  frame_camera(cam, r.bounds_min, r.bounds_max, 4.0f / 3.0f);
  const int errors = gl_error_count();
  float_target target(64, 48);
  struct variant { float elevation, turbidity, fog, haze, g; light_shafts shafts; bool physical, auto_exposure; };
  const variant variants[] = {
      {-10, 3, 0.015f, 0.001f, 0.7f, light_shafts::volumetric, true, true},
      {-2, 10, 1.0f, 0.1f, 0.95f, light_shafts::volumetric, true, true},
      {0, 1.7f, 0, 0, -0.9f, light_shafts::volumetric, true, true},
      {90, 10, 1.0f, 0.1f, 0.95f, light_shafts::radial, true, true},
      {5, 1.0f, 0.0f, 0.0f, 0.0f, light_shafts::volumetric, false, false},
      {-10, 3, 1.0f, 0.1f, 0.7f, light_shafts::radial, false, true},
  };
  for (const variant& v : variants) {
    render_params rp;
    rp.sun_elevation = v.elevation, rp.turbidity = v.turbidity, rp.fog_density = v.fog, rp.haze = v.haze;
    rp.scattering_g = v.g, rp.shafts = v.shafts, rp.physical_sky = v.physical, rp.auto_exposure = v.auto_exposure;
    rp.msaa = 0;
    draw_frame(r, rp, cam, 64, 48, target.fbo);
    const std::vector<float> px = target.read();
    size_t bad = 0;
    for (float f : px) bad += !std::isfinite(f);
    EXPECT_EQ(bad, 0u) << "elevation " << v.elevation << " turbidity " << v.turbidity << " fog " << v.fog;
    // 0 x 0 (a minimised window) draws nothing; 1 x 1 still works.
    draw_frame(r, rp, cam, 0, 0, target.fbo);
    draw_frame(r, rp, cam, 1, 1, target.fbo);
  }
  glFinish();
  EXPECT_EQ(check_gl("bad input"), 0);
  EXPECT_EQ(gl_error_count(), errors);
}
