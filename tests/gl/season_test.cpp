// The season in the viewport's pixels and in the real editor. Its CPU side (looks, fallen leaves,
// presets, exports) is tests/render/mesh/season_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <epoxy/gl.h>

#include "render/io/preset.h"
#include "render/gl/renderer.h"
#include "render/mesh/season.h"
#include "tests/gl/gl_test_context.h"
#include "tests/scratch_dir.h"
#include "tests/season_cards.h"

using namespace sylva;
using RenderSeason = sylva_test::renderer_test;
using sylva_test::card_grid;
using sylva_test::with_season;

// The viewport: autumn turns the lobed cards from green to orange-red, winter removes them, and a
// conifer's needle cards stay in winter.
TEST_F(RenderSeason, AutumnRecoloursAndWinterRemovesDeciduousLeaves) {
  render_params rp;
  rp.msaa = 0;
  rp.shadows = false;
  rp.shafts = light_shafts::off;
  rp.ground = false;
  rp.physical_sky = false;
  rp.sky_zenith = rp.sky_horizon = glm::vec3(0, 0, 0.5f);   // blue: leaf texels have more red or green
  rp.sun_azimuth = 0, rp.sun_elevation = 30;
  orbit_camera cam;
  cam.target = glm::vec3(0, 1, 0);
  cam.yaw = 0, cam.pitch = 0, cam.distance = 2.6f;
  const int w = 96, h = 96;
  GLuint tex = 0, fbo = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  struct stats { size_t leaf = 0; double red = 0, green = 0; };
  auto render = [&](uint8_t archetype, leaf_season s) {
    upload_tree(r, card_grid(archetype));
    rp.season = s;
    draw_frame(r, rp, cam, w, h, gl_framebuffer{fbo});
    std::vector<uint8_t> px(size_t(w) * h * 4);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    stats st;
    for (size_t k = 0; k < size_t(w) * h; ++k) {
      const int R = px[k * 4], G = px[k * 4 + 1], B = px[k * 4 + 2];
      if (std::max(R, G) > B + 10) ++st.leaf, st.red += R, st.green += G;
    }
    return st;
  };
  const uint8_t lobed = uint8_t(leaf_archetype::lobed), needles = uint8_t(leaf_archetype::needles);
  const stats summer = render(lobed, leaf_season::summer), autumn = render(lobed, leaf_season::autumn),
              winter = render(lobed, leaf_season::winter);
  ASSERT_GT(summer.leaf, size_t(w * h / 10)) << "the cards hardly show";
  EXPECT_LT(summer.red, summer.green);   // green in summer
  ASSERT_GT(autumn.leaf, 0u);
  EXPECT_GT(autumn.red, autumn.green);   // orange to red in autumn
  EXPECT_LT(autumn.leaf, summer.leaf);   // some have fallen
  EXPECT_EQ(winter.leaf, 0u);            // bare
  const stats pine_summer = render(needles, leaf_season::summer), pine_winter = render(needles, leaf_season::winter);
  ASSERT_GT(pine_summer.leaf, 0u);
  EXPECT_NEAR(double(pine_winter.leaf), double(pine_summer.leaf), 0.02 * double(pine_summer.leaf));
  EXPECT_LT(pine_winter.red, pine_winter.green);
  glDeleteFramebuffers(1, &fbo);
  glDeleteTextures(1, &tex);
  EXPECT_EQ(check_gl("season test"), 0);
}

// The real editor: a season change redraws the same tree (the worker is not asked to regrow).
TEST(EditorSeason, ChangingTheSeasonKeepsTheSameTree) {
  if (!sylva_test::have_display()) GTEST_SKIP() << "no DISPLAY";
  namespace fs = std::filesystem;
  const sylva_test::scratch_dir scratch("sylva_editor_season");
  const fs::path& dir = scratch.dir;
  fs::create_directories(dir / "home");
  std::ofstream(dir / "script.txt") << "wait_tree\nremember\nset season=winter\nframes 3\nexpect_same_tree\n"
                                       "set season=autumn\nframes 3\nexpect_same_tree\nexpect_modified 1\n";
  const std::string log = (dir / "log.txt").string();
  const std::string cmd = "SYLVA_HOME='" + (dir / "home").string() + "' SYLVA_SCRIPT='" + (dir / "script.txt").string() +
                          "' SYLVA_WINDOW=640x400 '" SYLVA_BINARY "' '" SYLVA_SOURCE_DIR "/presets/species_sapling.json' > '" +
                          log + "' 2>&1";
  const int status = std::system(cmd.c_str());
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << ss.str();
  EXPECT_EQ(ss.str().find("FAIL"), std::string::npos) << ss.str();
  EXPECT_NE(ss.str().find("ok expect_same_tree"), std::string::npos) << ss.str();
}
