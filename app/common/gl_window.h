// GL windows: the editor's window, hidden windows for the CLI and tests, and off-screen
// rendering of a preset to PNG with the editor's renderer.
#pragma once

#include <string>

#include "render/io/preset.h"

struct GLFWwindow;

namespace sylva {

struct renderer_gpu;
struct orbit_camera;

// glfwInit, retried once (a display shared with other clients now and then refuses a connection).
// Returns "" or the reason.
std::string init_glfw();
// The one way Sylva opens OpenGL: a window with a 3.3 core, forward-compatible context (as on
// llvmpipe), made current. Used by the editor, the hidden contexts below and the GL test fixtures.
// Needs init_glfw; returns nullptr with the reason in `why` when no such context can be had.
struct gl_window_options {
  int width = 64, height = 64;
  const char* title = "sylva";
  bool visible = false;     // hidden windows render off-screen (create_color_target)
  bool debug = false;       // a debug context (install_gl_debug_output)
  bool maximized = false;
};
GLFWwindow* create_gl33_window(const gl_window_options& o, std::string& why);

// A hidden window whose OpenGL 3.3 core context is current, for rendering without the editor.
struct hidden_gl_context {
  void* window = nullptr;   // GLFWwindow*
  bool ok() const { return window != nullptr; }
};
// "" when a display is named by DISPLAY or WAYLAND_DISPLAY, else the reason (for `what` needs).
std::string display_missing(const char* what);
// Opens the context (one retry: a display shared with other clients now and then refuses a
// connection). Returns "" or the reason; `debug` asks for a debug context.
std::string open_hidden_gl_context(hidden_gl_context& c, const char* title, bool debug);
void close_hidden_gl_context(hidden_gl_context& c);

struct headless_stats {
  bool measure_passes = false;   // input: time each pass (glFinish between passes; benchmarks only)
  float wind_time = 0;           // input: seconds into the wind's motion (when the preset's wind is on)
  double shadow_ms = 0, lit_ms = 0, occlusion_ms = 0, blur_ms = 0, composite_ms = 0;
  int gl_errors = 0;         // GL errors seen while rendering (debug callback + glGetError)
  double grow_ms = 0, mesh_ms = 0, frame_ms = 0;
  size_t triangles = 0, leaves = 0;
};

// Grows and meshes the preset, renders it as it stood at `step` (-1: final) at width x height and
// writes a PNG. Returns "" or an error; without DISPLAY a clear error. Any GL error is an error.
std::string render_preset_png(const preset& p, int step, const std::string& path, int width, int height);
std::string render_preset_png(const preset& p, int step, const std::string& path, int width, int height,
                              headless_stats* stats);

// Renders the current view of an initialised renderer off-screen and writes a PNG ("" or error).
// Needs a current GL context; the editor uses it for File > Export as .png.
std::string save_view_png(renderer_gpu& r, const render_params& rp, const orbit_camera& cam, int width, int height,
                          const std::string& path, double* frame_ms = nullptr);

}  // namespace sylva
