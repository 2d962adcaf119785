// The renderer's archetype textures: nine leaf layers drawn in one instanced call, the
// bark set follows render_params::bark, bad user textures say why and fall back. Under Xvfb.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include "render/gl/renderer.h"
#include "tests/gl/gl_test_context.h"
#include "render/assets/textures.h"
#include "tests/scratch_dir.h"

using namespace sylva;
using sylva_test::gl_context;
using sylva_test::have_display;
using RenderTextures = sylva_test::renderer_test;

namespace {



// One big leaf card facing the camera (+Z), archetype `texture`, filling most of the view.
tree_mesh one_card(uint8_t texture, float size = 2.0f) {
  tree_mesh m;
  leaf_instance l{};
  l.position = glm::vec3(0, 0, 0);
  l.orientation = glm::vec4(0, 0, 0, 1);
  l.size = size;
  l.born = 0;
  l.died = 0xffff;
  l.node = 0;
  l.texture = texture;
  m.leaves = {l};
  m.leaf_end = {1};
  m.index_end = {0};
  m.bounds_min = glm::vec3(-1, 0, -0.1f);
  m.bounds_max = glm::vec3(1, 2, 0.1f);
  return m;
}

struct offscreen {
  GLuint tex = 0, fbo = 0;
  int w, h;
  offscreen(int w_, int h_) : w(w_), h(h_) {
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
  ~offscreen() {
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
  }
  std::vector<uint8_t> read() const {
    std::vector<uint8_t> px(size_t(w) * h * 4);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return px;
  }
};

// A plain scene: no sky gradient tricks, no shadows or rays, so the card alone differs.
render_params plain() {
  render_params rp;
  rp.msaa = 0;
  rp.shadows = false;
  rp.shafts = light_shafts::off;
  rp.ground = false;
  rp.sky_zenith = rp.sky_horizon = glm::vec3(0, 0, 0.5f);   // blue: leaf texels are told apart by green
  rp.sun_azimuth = 0, rp.sun_elevation = 30;   // in front of the card (+Z): its lit side faces us
  return rp;
}

orbit_camera facing() {
  orbit_camera cam;
  cam.target = glm::vec3(0, 1, 0);
  cam.yaw = 0, cam.pitch = 0, cam.distance = 2.6f;
  return cam;
}

// A file in this process's scratch folder (tests/scratch_dir.h), removed when the process exits.
std::string temp_file(const std::string& name) {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path d = sylva_test::scratch_path("sylva_render_textures_test");
    std::filesystem::create_directories(d);
    return d;
  }();
  return (dir / name).string();
}

}  // namespace

TEST_F(RenderTextures, NineLeafLayersOneDrawAndEachArchetypeShowsItsOwnCard) {
  EXPECT_EQ(r.leaf_layers, leaf_archetype_count);
  const render_params rp = plain();
  const orbit_camera cam = facing();
  offscreen target(96, 96);
  std::vector<std::vector<bool>> masks;
  for (int a = 0; a < leaf_archetype_count; ++a) {
    upload_tree(r, one_card(uint8_t(a)));
    draw_frame(r, rp, cam, target.w, target.h, gl_framebuffer{target.fbo});
    EXPECT_EQ(r.counts.leaf_draw_calls, 1);
    const std::vector<uint8_t> px = target.read();
    std::vector<bool> leaf(size_t(target.w) * target.h);
    size_t n = 0;
    double green = 0;
    for (size_t k = 0; k < leaf.size(); ++k) {
      leaf[k] = px[k * 4 + 1] > px[k * 4 + 2] + 10;   // green over the blue background
      n += leaf[k];
      if (leaf[k]) green += px[k * 4 + 1];
    }
    // The pine card's 22 open pairs of needles cover about 7 % of it (render/assets/archetype_conifers.cpp).
    const size_t least = leaf.size() / (leaf_archetype(a) == leaf_archetype::needles ? 20 : 12);
    EXPECT_GT(n, least) << leaf_archetype_names[a] << ": the card hardly shows";
    EXPECT_GT(green / double(std::max<size_t>(n, 1)), 60.0) << leaf_archetype_names[a] << ": lit leaf texels are dark";
    masks.push_back(std::move(leaf));
  }
  // Each layer is a different outline on screen.
  for (int a = 0; a < leaf_archetype_count; ++a)
    for (int b = a + 1; b < leaf_archetype_count; ++b) {
      size_t differ = 0;
      for (size_t k = 0; k < masks[a].size(); ++k) differ += masks[a][k] != masks[b][k];
      EXPECT_GT(differ, masks[a].size() / 40) << leaf_archetype_names[a] << " vs " << leaf_archetype_names[b];
    }
  EXPECT_EQ(check_gl("leaf layers test"), 0);
}

TEST_F(RenderTextures, BarkArchetypeChangeUploadsItsSetOnce) {
  render_params rp = plain();
  const orbit_camera cam = facing();
  upload_tree(r, one_card(0));
  draw_frame(r, rp, cam, 32, 32);
  EXPECT_EQ(r.bark_shown, int(bark_archetype::furrowed));
  draw_frame(r, rp, cam, 32, 32);
  EXPECT_EQ(r.counts.uploads, 0);
  rp.bark = bark_archetype::ringed;
  draw_frame(r, rp, cam, 32, 32);
  EXPECT_EQ(r.bark_shown, int(bark_archetype::ringed));
  EXPECT_EQ(r.counts.uploads, 3) << "colour, normal and roughness";
  draw_frame(r, rp, cam, 32, 32);
  EXPECT_EQ(r.counts.uploads, 0);
}

TEST_F(RenderTextures, BadUserTexturesSayWhyAndKeepTheProceduralOnes) {
  render_params rp = plain();
  rp.bark = bark_archetype::plated;
  const orbit_camera cam = facing();
  upload_tree(r, one_card(4));

  const std::string corrupt = temp_file("corrupt.png"), wide = temp_file("wide.png"), npot = temp_file("npot.png");
  std::ofstream(corrupt, std::ios::binary) << "\x89PNG\r\n\x1a\ngarbage";
  ASSERT_EQ(save_png(image{8200, 2, 3, std::vector<uint8_t>(8200 * 2 * 3, 40)}, wide), "");
  ASSERT_EQ(save_png(image{3, 5, 4, std::vector<uint8_t>(3 * 5 * 4, 200)}, npot), "");

  rp.bark_texture = corrupt;
  rp.leaf_texture = wide;
  draw_frame(r, rp, cam, 32, 32);
  EXPECT_NE(r.texture_message.find("corrupt.png"), std::string::npos) << r.texture_message;
  EXPECT_NE(r.texture_message.find("8200x2 pixels, over the limit of 8192"), std::string::npos) << r.texture_message;
  EXPECT_NE(r.texture_message.find("procedural"), std::string::npos) << r.texture_message;
  EXPECT_FALSE(r.user_bark);
  EXPECT_FALSE(r.user_leaf);
  EXPECT_EQ(r.bark_shown, int(bark_archetype::plated));
  EXPECT_EQ(r.leaf_layers, leaf_archetype_count);

  rp.bark_texture = temp_file("missing.png");
  rp.leaf_texture = "";
  draw_frame(r, rp, cam, 32, 32);
  EXPECT_NE(r.texture_message.find("missing.png"), std::string::npos) << r.texture_message;

  // A non-power-of-two image is fine: used, no message. Its one layer serves every archetype.
  rp.bark_texture = npot;
  rp.leaf_texture = npot;
  draw_frame(r, rp, cam, 32, 32);
  EXPECT_EQ(r.texture_message, "");
  EXPECT_TRUE(r.user_bark);
  EXPECT_TRUE(r.user_leaf);
  EXPECT_EQ(r.leaf_layers, 1);
  EXPECT_EQ(r.counts.leaf_draw_calls, 1);

  // Clearing the paths brings the procedural sets back.
  rp.bark_texture = rp.leaf_texture = "";
  draw_frame(r, rp, cam, 32, 32);
  EXPECT_FALSE(r.user_bark);
  EXPECT_EQ(r.bark_shown, int(bark_archetype::plated));
  EXPECT_EQ(r.leaf_layers, leaf_archetype_count);
  EXPECT_EQ(check_gl("bad user textures test"), 0);
  for (const std::string& f : {corrupt, wide, npot}) std::filesystem::remove(f);
}
