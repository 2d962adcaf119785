// A hidden OpenGL 3.3 core context for the in-process renderer tests, shared by every GL test file.
#pragma once

#include <chrono>
#include <memory>
#include <cstdlib>
#include <thread>

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include "app/headless.h"
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
  std::unique_ptr<gl_context> ctx;
  sylva::renderer_gpu r;
  bool ready = false;
};

}  // namespace sylva_test
