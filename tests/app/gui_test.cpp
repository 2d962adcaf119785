// GUI smoke test (the editor binary under Xvfb) and headless renders: determinism, shadows, god rays.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>
#include <glm/gtc/matrix_transform.hpp>

#include "app/common/gl_window.h"
#include "render/gl/renderer.h"
#include "tests/scratch_dir.h"

using namespace sylva;

namespace {

bool have_display() {
  const char* d = std::getenv("DISPLAY");
  return d && *d;
}

struct picture {
  int width = 0, height = 0;
  std::string rgba;
  float luma(int x, int y) const {
    const unsigned char* p = reinterpret_cast<const unsigned char*>(&rgba[(size_t(y) * width + x) * 4]);
    return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
  }
  const unsigned char* at(int x, int y) const {
    return reinterpret_cast<const unsigned char*>(&rgba[(size_t(y) * width + x) * 4]);
  }
};

picture load(const std::string& path) {
  picture im;
  image img;
  std::string err = load_png(path, img);
  EXPECT_EQ(err, "");
  im.width = img.width, im.height = img.height;
  im.rgba.assign(img.pixels.begin(), img.pixels.end());
  return im;
}

// A file in this process's scratch folder (tests/scratch_dir.h), removed when the process exits.
std::string temp_path(const char* name) {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path d = sylva_test::scratch_path("sylva_gui");
    std::filesystem::create_directories(d);
    return d;
  }();
  return (dir / name).string();
}

preset honda_a() {
  preset p;   // the built-in default spec is Honda's tree a (lsystem_params defaults)
  p.spec.params = lsystem_params{};
  return p;
}

std::string render(const preset& p, const char* name, int w = 320, int h = 240) {
  std::string path = temp_path(name);
  headless_stats stats;
  std::string err = render_preset_png(p, -1, path, w, h, &stats);
  EXPECT_EQ(err, "") << name;
  EXPECT_EQ(stats.gl_errors, 0) << name;
  return path;
}

// Screen position (pixels, y down) of the sun for the headless camera: frame_camera on the mesh bounds.
glm::vec2 sun_pixel(const preset& p, int w, int h) {
  tree_skeleton t = grow(p.spec, {});
  tree_mesh m = mesh_tree(t, p.mesh, p.spec.seed);
  orbit_camera cam;
  frame_camera(cam, m.bounds_min, m.bounds_max);
  glm::vec3 eye = camera_eye(cam);
  glm::mat4 vp = camera_projection(cam, float(w) / float(h), 0.1f, 1000.0f) * camera_view(cam);
  glm::vec4 c = vp * glm::vec4(eye + sun_direction(p.render) * 500.0f, 1.0f);
  glm::vec2 ndc = glm::vec2(c) / c.w;
  return {(ndc.x * 0.5f + 0.5f) * w, (0.5f - ndc.y * 0.5f) * h};
}

// Mean luma over the pixels whose distance to `c` lies in [r0, r1).
float ring_mean(const picture& im, glm::vec2 c, float r0, float r1) {
  double sum = 0;
  int n = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      float d = glm::length(glm::vec2(x + 0.5f, y + 0.5f) - c);
      if (d >= r0 && d < r1) { sum += im.luma(x, y); ++n; }
    }
  return n ? float(sum / n) : 0.0f;
}

}  // namespace

TEST(HeadlessRender, NoDisplayIsAClearError) {
  std::string saved = have_display() ? std::getenv("DISPLAY") : "";
  unsetenv("DISPLAY");
  const char* wl = std::getenv("WAYLAND_DISPLAY");
  std::string saved_wl = wl ? wl : "";
  unsetenv("WAYLAND_DISPLAY");
  std::string err = render_preset_png(honda_a(), -1, temp_path("nodisplay.png"), 64, 64);
  if (!saved.empty()) setenv("DISPLAY", saved.c_str(), 1);
  if (!saved_wl.empty()) setenv("WAYLAND_DISPLAY", saved_wl.c_str(), 1);
  EXPECT_NE(err.find("DISPLAY"), std::string::npos) << err;
}

TEST(HeadlessRender, SamePresetGivesIdenticalImages) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  preset p = honda_a();
  picture a = load(render(p, "same1.png")), b = load(render(p, "same2.png"));
  ASSERT_EQ(a.width, 320);
  ASSERT_EQ(a.height, 240);
  EXPECT_TRUE(a.rgba == b.rgba);
}

TEST(HeadlessRender, ShadowDarkensTheGroundUnderTheTree) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  preset p = honda_a();
  p.render.sun_elevation = 65;   // a high sun puts the shadow right under the crown
  p.render.shafts = light_shafts::off;
  p.render.auto_exposure = false;   // the same exposure for both images
  p.render.fog_density = p.render.haze = 0;
  p.render.shadows = false;
  picture off = load(render(p, "shadow_off.png"));
  p.render.shadows = true;
  picture on = load(render(p, "shadow_on.png"));
  // The ground fills the lower part of the frame (the camera looks slightly down at the crown).
  double sum_on = 0, sum_off = 0;
  int darker = 0, n = 0;
  for (int y = on.height * 2 / 3; y < on.height; ++y)
    for (int x = 0; x < on.width; ++x) {
      sum_on += on.luma(x, y);
      sum_off += off.luma(x, y);
      darker += on.luma(x, y) < off.luma(x, y) - 10;
      ++n;
    }
  // Shadows only ever remove light, so the band must get darker on average, and a visible patch
  // (at least 2% of the band) must lose more than 10 levels.
  EXPECT_LT(sum_on / n, sum_off / n - 1.0);
  EXPECT_GT(darker, n / 50);
}

TEST(HeadlessRender, GodRaysBrightenARingAroundTheSun) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  preset p = honda_a();
  // Sun behind the crown: opposite the camera's default yaw, low enough to be in view.
  p.render.sun_azimuth = orbit_camera{}.yaw - 180;
  p.render.sun_elevation = 5;
  p.render.exposure = 0.3f;   // keep the tonemap out of saturation so brightness adds up near the sun
  p.render.auto_exposure = false;
  p.render.fog_density = p.render.haze = 0;   // the radial blur alone
  const int w = 320, h = 240;
  glm::vec2 sun = sun_pixel(p, w, h);
  ASSERT_GT(sun.x, 0);
  ASSERT_LT(sun.x, w);
  ASSERT_GT(sun.y, 0);
  ASSERT_LT(sun.y, h);
  p.render.shafts = light_shafts::off;
  picture off = load(render(p, "rays_off.png", w, h));
  p.render.shafts = light_shafts::radial;
  picture on = load(render(p, "rays_on.png", w, h));
  const float inner_on = ring_mean(on, sun, 10, 30), inner_off = ring_mean(off, sun, 10, 30);
  const float outer_on = ring_mean(on, sun, 60, 90), outer_off = ring_mean(off, sun, 60, 90);
  EXPECT_GT(inner_on, inner_off + 3.0f) << inner_on << " vs " << inner_off;
  // Radial: the gain falls off away from the sun.
  EXPECT_GT(inner_on - inner_off, outer_on - outer_off) << outer_on << " vs " << outer_off;
}

TEST(HeadlessRender, BrokenShaderIsReportedAndFallsBack) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const std::string up = init_glfw();
  ASSERT_TRUE(up.empty()) << up;
  std::string why;
  GLFWwindow* win = create_gl33_window({64, 64, "test"}, why);
  ASSERT_TRUE(win) << why;
  const int errors = gl_error_count();
  gl_program bad = compile_program("broken test shader", "#version 330 core\nvoid main() { gl_Position = oops; }",
                                   "#version 330 core\nout vec4 c; void main() { c = vec4(1); }");
  EXPECT_TRUE(bad.failed);
  EXPECT_EQ(bad.id, 0u);
  EXPECT_NE(gl_last_message().find("broken test shader"), std::string::npos) << gl_last_message();

  // A renderer whose lit bark program failed still draws a frame (flat fallback), without GL errors.
  renderer_gpu r;
  ASSERT_TRUE(init_renderer(r));
  delete_gl(r.shared->bark);
  r.shared->bark = bad;
  preset p = honda_a();
  tree_skeleton t = grow(p.spec, {});
  upload_tree(r, mesh_tree(t, p.mesh));
  set_tree_step(r, t, p.mesh.min_radius, t.steps);
  orbit_camera cam;
  frame_camera(cam, r.bounds_min, r.bounds_max);
  draw_frame(r, p.render, cam, 64, 64);
  glFinish();
  check_gl("fallback frame");
  EXPECT_EQ(gl_error_count(), errors);
  destroy_renderer(r);
  glfwDestroyWindow(win);
  glfwTerminate();
}

TEST(EditorSmoke, ScreenshotShowsTheTree) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  std::string preset_path = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";
  if (!std::filesystem::exists(preset_path)) preset_path.clear();   // the built-in default tree
  const std::string shot = temp_path("editor.png");
  std::filesystem::remove(shot);
  const std::string cmd = "SYLVA_SCREENSHOT='" + shot + "' SYLVA_FRAMES=6 SYLVA_WINDOW=1280x800 '" +
                          std::string(SYLVA_BINARY) + "' " + (preset_path.empty() ? "" : "'" + preset_path + "'") +
                          " > /dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  picture im = load(shot);
  ASSERT_EQ(im.width, 1280);
  ASSERT_EQ(im.height, 800);
  // The crown sits above the horizon, right of the parameter panel: count pixels there that are
  // neither sky (blue dominant) nor panel grey: leaves are green, bark is brown.
  int tree = 0, n = 0;
  for (int y = im.height / 10; y < im.height * 4 / 10; ++y)
    for (int x = im.width * 45 / 100; x < im.width * 85 / 100; ++x) {
      const unsigned char* p = im.at(x, y);
      const bool green = p[1] > p[2] + 12 && p[1] >= p[0];
      const bool brown = p[0] > p[2] + 12 && p[0] > p[1];
      tree += green || brown;
      ++n;
    }
  EXPECT_GT(tree, n / 50) << "tree pixels " << tree << " of " << n;
  EXPECT_LT(tree, n) << "the whole region is one colour";
}

TEST(HeadlessRender, ScrubbingShowsTheYoungerTree) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  preset p = honda_a();
  p.render.shadows = false;
  p.render.shafts = light_shafts::off;
  p.render.ground = false;   // brown soil would count as bark
  p.render.physical_sky = false;
  p.render.sun_azimuth = orbit_camera{}.yaw;   // front-lit, so the bark shows its colour
  p.render.sun_elevation = 40;
  // Pixels that differ from the empty scene (no tree: step rendering of a tree with no leaves
  // is not empty, so compare against a render at the final step instead): the tree at step 3 has
  // 2^3 = 8 internodes and no more, so it covers far fewer pixels than the full tree of step 10.
  const int w = 240, h = 180;
  std::string young = temp_path("step3.png"), full = temp_path("step10.png");
  ASSERT_EQ(render_preset_png(p, 3, young, w, h), "");
  ASSERT_EQ(render_preset_png(p, -1, full, w, h), "");
  picture a = load(young), b = load(full);
  auto tree_pixels = [](const picture& im) {
    int n = 0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) {
        const unsigned char* q = im.at(x, y);
        n += (q[0] > q[2] + 12 && q[0] > q[1]) || (q[1] > q[0] + 25 && q[1] > q[2] + 25);   // bark or leaf
      }
    return n;
  };
  const int na = tree_pixels(a), nb = tree_pixels(b);
  EXPECT_GT(na, 20) << "the young tree is visible";
  EXPECT_LT(na * 3, nb) << "young " << na << " full " << nb;
}

TEST(HeadlessRender, UserBarkTextureIsUsedAndABadPathIsHarmless) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const std::string red = temp_path("red_bark.png");
  image pixels{8, 8, 4, {}};
  for (int i = 0; i < 8 * 8; ++i) pixels.pixels.insert(pixels.pixels.end(), {0xff, 0x10, 0x10, 0xff});
  ASSERT_EQ(save_png(pixels, red), "");
  preset p = honda_a();
  p.mesh.leaves_enabled = false;
  p.render.shadows = false;
  p.render.shafts = light_shafts::off;
  p.render.bark_color = glm::vec3(0.45f);   // neutral tint: the texture's colour shows
  p.render.sun_azimuth = orbit_camera{}.yaw;   // front-lit and clear, so the bark's colour reads
  p.render.sun_elevation = 40;
  p.render.fog_density = p.render.haze = 0;
  auto reddish = [](const picture& im) {
    int n = 0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) n += im.at(x, y)[0] > im.at(x, y)[1] + 60;
    return n;
  };
  const int before = reddish(load(render(p, "bark_default.png")));
  p.render.bark_texture = red;
  const int after = reddish(load(render(p, "bark_red.png")));
  EXPECT_GT(after, before + 200) << before << " -> " << after;
  // A missing file keeps the procedural texture: same image as no user texture at all.
  p.render.bark_texture = temp_path("does_not_exist.png");
  EXPECT_EQ(reddish(load(render(p, "bark_missing.png"))), before);
}
