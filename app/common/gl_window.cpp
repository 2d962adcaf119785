// Off-screen PNG rendering: a hidden GLFW window, the editor's renderer, one frame, read back.
#include "app/common/gl_window.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>
#include <cstdlib>
#include <vector>

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include "generators/timing.h"
#include "render/gl/renderer.h"
#include "render/io/mesh_bound.h"

namespace sylva {

namespace {
std::string glfw_error(const std::string& what) {
  const char* desc = nullptr;
  glfwGetError(&desc);
  return desc ? what + ": " + desc : what;
}
}  // namespace

std::string save_view_png(renderer_gpu& r, const render_params& rp, const orbit_camera& cam, int width, int height,
                          const std::string& path, double* frame_ms) {
  if (width < 16 || height < 16 || width > 8192 || height > 8192)
    return "image size " + std::to_string(width) + "x" + std::to_string(height) + " is outside 16..8192";
  gl_texture color;
  gl_framebuffer fbo;
  std::string error = create_color_target(width, height, color, fbo);
  if (error.empty()) {
    auto t0 = std::chrono::steady_clock::now();
    draw_frame(r, rp, cam, width, height, fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id);
    const image shot = read_back_rgba(0, 0, width, height);
    if (frame_ms) *frame_ms = ms_since(t0);
    check_gl("read pixels");
    error = save_png(shot, path);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  delete_gl(fbo);
  delete_gl(color);
  return error;
}

std::string display_missing(const char* what) {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!display || !*display) && (!wayland || !*wayland))
    return std::string(what) + " needs a display: DISPLAY is not set (run under xvfb-run -a)";
  return "";
}

std::string init_glfw() {
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (attempt) std::this_thread::sleep_for(std::chrono::milliseconds(200));
    if (glfwInit()) return "";
  }
  return glfw_error("cannot initialise GLFW (is the X server at DISPLAY reachable?)");
}

GLFWwindow* create_gl33_window(const gl_window_options& o, std::string& why) {
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_VISIBLE, o.visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  if (o.debug) glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
  if (o.maximized) glfwWindowHint(GLFW_MAXIMIZED, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(o.width, o.height, o.title, nullptr, nullptr);
  if (!window) {
    why = glfw_error("cannot create an OpenGL 3.3 core context");
    return nullptr;
  }
  glfwMakeContextCurrent(window);
  return window;
}

std::string open_hidden_gl_context(hidden_gl_context& c, const char* title, bool debug) {
  std::string why;
  GLFWwindow* window = nullptr;
  for (int attempt = 0; attempt < 2 && !window; ++attempt) {
    if (attempt) std::this_thread::sleep_for(std::chrono::milliseconds(200));
    if (why = init_glfw(); !why.empty()) continue;
    window = create_gl33_window({64, 64, title, false, debug, false}, why);
    if (!window) glfwTerminate();
  }
  if (!window) return why;
  c.window = window;
  return "";
}

void close_hidden_gl_context(hidden_gl_context& c) {
  if (!c.window) return;
  glfwDestroyWindow(static_cast<GLFWwindow*>(c.window));
  glfwTerminate();
  c.window = nullptr;
}

std::string render_preset_png(const preset& p, int step, const std::string& path, int width, int height) {
  return render_preset_png(p, step, path, width, height, nullptr);
}

std::string render_preset_png(const preset& p, int step, const std::string& path, int width, int height,
                              headless_stats* stats) {
  if (std::string why = display_missing("PNG rendering"); !why.empty()) return why;
  if (width < 16 || height < 16 || width > 8192 || height > 8192)
    return "image size " + std::to_string(width) + "x" + std::to_string(height) + " is outside 16..8192";

  // Grow and mesh first: no window is opened for a tree that cannot be built.
  auto t0 = std::chrono::steady_clock::now();
  budgeted_growth g = grow_for_mesh(p.spec, p.mesh, nullptr);   // nothing is meshed over the mesh budget
  tree_skeleton tree = std::move(g.tree);
  const grow_report& report = g.report;
  const double grow_ms = ms_since(t0);
  if (report.error) return "growth failed: " + report.message;
  if (!g.refusal.empty()) return g.refusal;
  t0 = std::chrono::steady_clock::now();
  tree_mesh mesh = mesh_tree(tree, p.mesh, p.spec.seed);
  const double mesh_ms = ms_since(t0);

  hidden_gl_context context;
  if (std::string why = open_hidden_gl_context(context, "sylva render", true); !why.empty()) return why;
  install_gl_debug_output();
  const int errors_before = gl_error_count();

  std::string error;
  renderer_gpu r;
  if (!init_renderer(r)) error = r.error.empty() ? "renderer initialisation failed" : r.error;
  if (error.empty()) {
    upload_tree(r, mesh);
    upload_wind(r, tree);
    r.wind_time = stats ? stats->wind_time : 0.0f;
    set_tree_step(r, tree, p.mesh.min_radius, step < 0 ? tree.steps : std::min(step, tree.steps));
    orbit_camera cam;
    frame_camera(cam, r.bounds_min, r.bounds_max, float(width) / float(height));

    double frame_ms = 0;
    r.measure_passes = stats && stats->measure_passes;
    error = save_view_png(r, p.render, cam, width, height, path, &frame_ms);
    if (!r.texture_message.empty())   // the procedural texture stood in; say so, but render
      std::fprintf(stderr, "sylva: warning: texture: %s\n", r.texture_message.c_str());
    const int errors = gl_error_count() - errors_before;
    if (errors > 0 && error.empty()) error = std::to_string(errors) + " GL error(s): " + gl_last_message();
    if (stats) {
      stats->gl_errors = errors;
      stats->grow_ms = grow_ms;
      stats->mesh_ms = mesh_ms;
      stats->frame_ms = frame_ms;
      stats->triangles = r.triangles_drawn;
      stats->leaves = r.leaves_drawn;
      stats->shadow_ms = r.timings.shadow;
      stats->lit_ms = r.timings.lit;
      stats->occlusion_ms = r.timings.occlusion;
      stats->blur_ms = r.timings.blur;
      stats->composite_ms = r.timings.composite;
    }
  }
  destroy_renderer(r);
  close_hidden_gl_context(context);
  return error;
}

}  // namespace sylva
