// A hidden OpenGL 3.3 core context for the in-process renderer tests, shared by every GL test file.
#pragma once

#include <chrono>
#include <memory>
#include <cstdlib>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include "app/common/gl_window.h"
#include "generators/tree_spec.h"
#include "render/mesh/mesh.h"
#include "render/io/preset.h"
#include "tests/fixtures.h"
#include "render/gl/renderer.h"

namespace sylva_test {

inline bool have_display() {
  const char* d = std::getenv("DISPLAY");
  return d && *d;
}

struct gl_context {
  GLFWwindow* window = nullptr;
  gl_context() {
    if (!sylva::init_glfw().empty()) return;
    std::string why;
    window = sylva::create_gl33_window({64, 64, "sylva test"}, why);
  }
  ~gl_context() {
    if (window) glfwDestroyWindow(window);
    glfwTerminate();
  }
  gl_context(const gl_context&) = delete;
  gl_context& operator=(const gl_context&) = delete;
};

// A test fixture with a context and an initialised renderer `r` (skipped without a display).
class renderer_test : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!have_display()) GTEST_SKIP() << "no DISPLAY";
    ctx = std::make_unique<gl_context>();
    ASSERT_TRUE(ctx->window);
    ASSERT_TRUE(sylva::init_renderer(r)) << r.error;
    ready = true;
  }
  void TearDown() override {
    if (ready) sylva::destroy_renderer(r);   // before the context goes
  }
  // A shipped preset grown, meshed and shown on `r` at its last step.
  struct shown_tree {
    sylva::preset p;
    sylva::tree_skeleton t;
    sylva::tree_mesh m;
  };
  shown_tree show_preset(const std::string& name) {
    shown_tree s;
    s.p = shipped_preset(name);
    s.t = sylva::grow(s.p.spec, sylva::grow_options{});
    s.m = sylva::mesh_tree(s.t, s.p.mesh, s.p.spec.seed);
    sylva::upload_tree(r, s.m);
    sylva::set_tree_step(r, s.t, s.p.mesh.min_radius, s.t.steps);
    return s;
  }
  std::unique_ptr<gl_context> ctx;
  sylva::renderer_gpu r;
  bool ready = false;
};


// An offscreen RGBA colour target the tests draw into and read back: T = unsigned char (RGBA8) or
// float (RGBA32F, so that NaN survives to the readback).
template <class T>
struct color_target {
  sylva::gl_texture color;
  sylva::gl_framebuffer fbo;
  int w = 0, h = 0;
  static constexpr bool is_float = std::is_same_v<T, float>;
  color_target(int width, int height) : w(width), h(height) {
    glGenTextures(1, &color.id);
    glBindTexture(GL_TEXTURE_2D, color.id);
    glTexImage2D(GL_TEXTURE_2D, 0, is_float ? GL_RGBA32F : GL_RGBA8, w, h, 0, GL_RGBA,
                 is_float ? GL_FLOAT : GL_UNSIGNED_BYTE, nullptr);
    glGenFramebuffers(1, &fbo.id);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color.id, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
  ~color_target() {
    sylva::delete_gl(fbo);
    sylva::delete_gl(color);
  }
  std::vector<T> read() const {
    std::vector<T> px(size_t(w) * h * 4);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id);
    glReadPixels(0, 0, w, h, GL_RGBA, is_float ? GL_FLOAT : GL_UNSIGNED_BYTE, px.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return px;
  }
};

}  // namespace sylva_test
