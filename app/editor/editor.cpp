// The editor: the window and frame loop (docs/design/09-editor.md): start-up (the document, then
// the window), the frames, shutdown. Each frame builds the UI from editor_state
// (app/editor/editor_state.h; its parts live in app/editor/editor_*.cpp), then draws the tree under it.
#include "app/editor/editor.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include "app/common/wake.h"
#include "app/editor/editor_script.h"
#include "app/editor/editor_settings.h"
#include "app/editor/editor_state.h"
#include "app/common/gl_window.h"
#include "app/editor/view_gizmo.h"

namespace sylva {

namespace {

using namespace ed;

void handle_mouse(editor_state& e, const view_rect& view) {
  const int viewport_height = int(view.h);
  ImGuiIO& io = ImGui::GetIO();
  if (io.WantCaptureMouse) return;
  // A click that did not drag picks the branch under the mouse (Pruning).
  if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) && io.MouseDragMaxDistanceSqr[0] < 9 && e.cur().shown && e.cur().shown->skeleton)
    pick_in_view(e.prune, *e.cur().shown->skeleton, e.step, e.camera, view, io.MousePos.x, io.MousePos.y);
  const ImVec2 d = io.MouseDelta;
  // A drag starts past three pixels from the press (the pick's slack), so a click never orbits.
  if (ImGui::IsMouseDragging(ImGuiMouseButton_Left, 3)) orbit_camera_rotate(e.camera, d.x, d.y);
  if (ImGui::IsMouseDragging(ImGuiMouseButton_Right, 3) || ImGui::IsMouseDragging(ImGuiMouseButton_Middle, 3))
    orbit_camera_pan(e.camera, d.x, d.y, viewport_height);
  if (io.MouseWheel != 0) orbit_camera_zoom(e.camera, io.MouseWheel);
}

void load_fonts() {
  ImGuiIO& io = ImGui::GetIO();
  // Latin, Latin Extended-A (Měch), Greek (λ σ τ κ φ α), phonetic subscripts (dᵢ), punctuation,
  // super/subscripts (s₀ r₁),
  // arrows and maths (≥ −): the symbols the parameter labels use.
  static const ImWchar ranges[] = {0x0020, 0x017F, 0x0370, 0x03FF, 0x1D00, 0x1DBF, 0x2000, 0x206F,
                                   0x2070, 0x209F, 0x2190, 0x21FF, 0x2200, 0x22FF, 0};
  const char* candidates[] = {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
                              "/usr/share/fonts/TTF/DejaVuSans.ttf", nullptr};
  for (int i = 0; candidates[i]; ++i)
    if (fs::exists(candidates[i]) && io.Fonts->AddFontFromFileTTF(candidates[i], 16.0f * ui_scale, nullptr, ranges)) return;
  std::fprintf(stderr, "sylva: DejaVu Sans not found (install fonts-dejavu-core); Greek symbols will not show\n");
  io.Fonts->AddFontDefault();
}

// The style and the font at a content scale (fonts and sizes follow the monitor).
void apply_ui_scale(float scale) {
  ui_scale = std::clamp(scale, 1.0f, 4.0f);
  ImGuiStyle& style = ImGui::GetStyle();
  style = ImGuiStyle();
  ImGui::StyleColorsDark(&style);
  style.WindowRounding = 0;
  // Dialogs and popups are opaque: the tree behind them is distracting, not informative.
  style.Colors[ImGuiCol_PopupBg].w = 1;
  style.Colors[ImGuiCol_WindowBg].w = 1;
  style.Colors[ImGuiCol_ModalWindowDimBg] = ImVec4(0, 0, 0, 0.45f);
  style.ScaleAllSizes(ui_scale);
  ImGui::GetIO().Fonts->Clear();
  load_fonts();
}

std::string save_region_png(int x, int y, int width, int height, const std::string& path) {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  image shot = read_back_rgba(x, y, width, height);
  for (size_t i = 3; i < shot.pixels.size(); i += 4) shot.pixels[i] = 255;
  return save_png(shot, path);
}

std::string save_window_png(int width, int height, const std::string& path) { return save_region_png(0, 0, width, height, path); }

// SYLVA_* variables into the options, each read once (editor.h).
editor_options options_from_environment(const std::string& preset_path) {
  editor_options o;
  o.preset_path = preset_path;
  if (const char* s = std::getenv("SYLVA_SCREENSHOT")) o.screenshot_path = s;
  if (const char* s = std::getenv("SYLVA_FRAMES")) o.frames = std::max(1, std::atoi(s));
  if (const char* s = std::getenv("SYLVA_OVERLAYS")) o.overlays = std::atoi(s) != 0;
  if (const char* s = std::getenv("SYLVA_WINDOW")) {
    int w = 0, h = 0;
    if (std::sscanf(s, "%dx%d", &w, &h) == 2 && w >= 320 && h >= 240) {
      o.width = w;
      o.height = h;
      o.fit_screen = false;
    }
  }
  if (const char* s = std::getenv("SYLVA_SCRIPT")) o.script_path = s;
  if (const char* s = std::getenv("SYLVA_NODE_BUDGET")) o.node_budget = std::max<int64_t>(1000, std::atoll(s));
  if (const char* s = std::getenv("SYLVA_SHOW_BROWSER")) o.show_browser = std::atoi(s) != 0;
  if (const char* s = std::getenv("SYLVA_SHOW_EXPORT")) o.show_export = std::atoi(s) != 0;
  if (const char* s = std::getenv("SYLVA_UI_SCALE")) o.ui_scale = float(std::atof(s));
  return o;
}

// One run of the editor: what start-up makes, the frames use and shutdown saves.
struct editor_run {
  const editor_options& o;
  std::unique_ptr<editor_state> e = std::make_unique<editor_state>();
  script_state script;
  editor_settings settings;
  bool scripted = false, automated = false, remember_window = false;
  GLFWwindow* window = nullptr;
  int exit_code = 0, frames_with_tree = 0;
  std::chrono::steady_clock::time_point started;
};

// Start-up, the document: slot A on the preset named (else the oak, else the default tree), the
// script, the recovery offer. Returns the exit code when the editor cannot run, else -1.
int start_document(editor_run& r) {
  const editor_options& o = r.o;
  editor_state* e = r.e.get();
  editor_slot& a = e->ab.slots[0];   // the editor starts on slot A
  a.worker = std::make_unique<worker_state>();
  a.doc = default_preset();
  if (!o.preset_path.empty()) {
    preset loaded;
    load_result lr = load_preset_file(o.preset_path, loaded);
    if (!lr.ok) {
      std::fprintf(stderr, "sylva: cannot open %s: %s\n", o.preset_path.c_str(), lr.error.c_str());
      set_status(*e, "Cannot open " + o.preset_path + ": " + lr.error + " (showing the default tree)", true);
    } else {
      a.doc = loaded;
      a.path = o.preset_path;
      if (!lr.warnings.empty()) set_status(*e, lr.warnings.front());
    }
  }
  // With no preset named, a newcomer meets a species tree (the oak), not an abstract L-system.
  if (o.preset_path.empty() && o.screenshot_path.empty() && !o.script_path) {
    for (const fs::path& d : preset_dirs()) {
      preset oak;
      if (const fs::path p = d / "species_oak.json"; fs::exists(p) && load_preset_file(p.string(), oak).ok) {
        a.doc = oak;
        a.path = p.string();
        break;
      }
    }
  }
  a.undo_base = a.doc;
  note_saved(*e, a.path);
  e->home = user_folder();
  if (o.script_path) {
    if (std::string err; !load_script(*o.script_path, r.script, err)) {
      std::fprintf(stderr, "sylva: %s\n", err.c_str());
      return 2;
    }
  }
  r.scripted = !r.script.lines.empty();
  r.automated = !o.screenshot_path.empty();
  if (o.node_budget) a.worker->node_budget = *o.node_budget;
  // Work left unsaved by a crash or a killed session: offered back (not in automatic screenshots).
  if (!r.automated) find_recovery(*e);
  e->show_overlays = o.overlays;
  if (o.show_browser) e->browser.open = *o.show_browser;
  if (o.show_export) e->exporter.open = *o.show_export;
  return -1;
}

// The window fits the monitor's work area on the first start and keeps its place afterwards:
// its size, and its position (-1: the window manager's choice).
void place_window(const editor_run& r, int& width, int& height, int& pos_x, int& pos_y) {
  const editor_options& o = r.o;
  width = o.width, height = o.height, pos_x = -1, pos_y = -1;
  if (!o.fit_screen) return;
  int ax = 0, ay = 0, aw = 0, ah = 0;
  if (GLFWmonitor* m = glfwGetPrimaryMonitor()) glfwGetMonitorWorkarea(m, &ax, &ay, &aw, &ah);
  if (aw > 0 && ah > 0) {
    const int frame = 40;   // room for the window manager's title bar
    if (r.remember_window && r.settings.width > 0) {
      width = std::min(r.settings.width, aw), height = std::min(r.settings.height, ah - frame);
      pos_x = std::clamp(r.settings.x, ax, ax + aw - width), pos_y = std::clamp(r.settings.y, ay, ay + ah - height);
    } else {
      width = std::min(o.width, aw), height = std::min(o.height, ah - frame);
      pos_x = ax + (aw - width) / 2, pos_y = ay + std::max(0, (ah - frame - height) / 2) + frame;
    }
  }
}

// Start-up, the window: GLFW, the settings, the window, ImGui, the renderer, the worker and the
// library. Returns the exit code when there is no window, else -1.
int open_window(editor_run& r) {
  const editor_options& o = r.o;
  editor_state* e = r.e.get();
  editor_slot& a = e->ab.slots[0];
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!display || !*display) && (!wayland || !*wayland)) {
    std::fprintf(stderr, "sylva: the editor needs a display (DISPLAY is not set); try `sylva export` instead\n");
    return 1;
  }
  if (const std::string why = init_glfw(); !why.empty()) {
    std::fprintf(stderr, "sylva: %s\n", why.c_str());
    return 1;
  }
  // Each line of the settings that cannot be used is said and left out; the editor starts with the
  // defaults for it.
  std::vector<std::string> setting_notes;
  r.settings = load_settings(e->home, &setting_notes);
  if (!setting_notes.empty()) set_status(*e, setting_notes[0] + (setting_notes.size() > 1 ? " (more on stderr)" : ""), true);
  for (size_t i = 1; i < setting_notes.size(); ++i) std::fprintf(stderr, "sylva: %s\n", setting_notes[i].c_str());
  if (!o.node_budget && r.settings.node_budget > 0) a.worker->node_budget = r.settings.node_budget;
  if (!r.scripted) e->recent = r.settings.recent;
  r.remember_window = o.fit_screen && o.screenshot_path.empty() && !r.scripted;
  int width, height, pos_x, pos_y;
  place_window(r, width, height, pos_x, pos_y);
  std::string why;   // shown once placed, so that it does not jump
  GLFWwindow* window = create_gl33_window({width, height, "Sylva", false, false, r.remember_window && r.settings.maximized}, why);
  if (window && pos_x >= 0) glfwSetWindowPos(window, pos_x, pos_y);
  if (window) glfwShowWindow(window);
  if (!window) {
    std::fprintf(stderr, "sylva: %s\n", why.c_str());
    glfwTerminate();
    return 1;
  }
  r.window = e->window = window;
  // Closing the window asks first when there are unsaved changes.
  glfwSetWindowUserPointer(window, e);
  glfwSetWindowCloseCallback(window, [](GLFWwindow* w) {
    auto* ed = static_cast<editor_state*>(glfwGetWindowUserPointer(w));
    if (!ed || ed->quit_confirmed) return;
    glfwSetWindowShouldClose(w, GLFW_FALSE);
    ed->close_requested = true;
  });
  glfwSwapInterval(o.screenshot_path.empty() ? 1 : 0);
  install_gl_debug_output();

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;   // the layout is fixed; no imgui.ini litter
  {
    float xs = 1, ys = 1;
    glfwGetWindowContentScale(window, &xs, &ys);
    if (o.ui_scale) xs = *o.ui_scale;
    apply_ui_scale(xs);
  }
  // Moved to a monitor with another scale: the style and fonts follow before the next frame.
  glfwSetWindowContentScaleCallback(window, [](GLFWwindow* w, float xs, float) {
    if (auto* ed = static_cast<editor_state*>(glfwGetWindowUserPointer(w))) ed->rescale_to = xs;
  });
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  install_input_queue(window, &e->input);
  ImGui_ImplOpenGL3_Init("#version 330 core");

  if (!init_renderer(a.renderer)) set_status(*e, a.renderer.error, true);
  start_worker(*a.worker);
  {
    std::vector<std::string> folders;
    for (const fs::path& d : preset_dirs()) folders.push_back(d.string());
    e->browser.share = a.renderer.shared;   // the library's thumbnails: the same context, the same programs
    init_preset_browser(e->browser, folders);
  }
  return -1;
}

// Where a frame's 3D view lies between the panels (window coordinates, y down).
struct frame_layout {
  float left, top, bottom;
};

// A frame, first half: the UI built from the state, the input handled, the growth polled, the
// script's next line run. Only then is the state read for drawing (docs/design/09-editor.md).
frame_layout build_ui(editor_run& r, int win_w, int win_h, double dt) {
  editor_state* e = r.e.get();
  e->hold_post = false;
  timeline_markers = !e->cur().doc.spec.keyframes.empty() || !e->cur().doc.spec.cuts.empty();
  e->prompts_shown.clear();
  if (e->close_requested) {
    e->close_requested = false;
    request(*e, editor_state::then::quit);
  }
  draw_menu(*e);
  const float top = ImGui::GetFrameHeight();
  const float bottom = float(win_h) - status_height() - (e->show_timeline ? timeline_height() : 0);
  if (e->show_panel) draw_panel(*e, top, float(win_h) - status_height());
  const float left = e->show_panel ? panel_width() : 0;
  if (e->show_timeline) draw_timeline(*e, left, bottom, float(win_w) - left);
  draw_status(*e, float(win_h) - status_height(), float(win_w));
  draw_toast(*e, left, top, float(win_w));
  draw_overlay_legend(*e, left, bottom);
  draw_message_log(*e);
  draw_shortcuts(*e);
  draw_dialogs(*e);
  if (std::string p = draw_preset_browser(e->browser, e->cur().baseline_path, modified(*e)); !p.empty()) request(*e, editor_state::then::open, p);
  {
    // An export's outcome goes through set_status, so it is dated (not taken for stale at once),
    // logged, and a failure gets its toast.
    std::string exported;
    bool export_failed = false;
    draw_export_dialog(e->exporter, export_context{e->cur().shown, e->step, e->cur().doc, e->cur().renderer, e->camera, left, top}, exported, export_failed);
    if (!exported.empty()) set_status(*e, exported, export_failed);
  }
  handle_keys(*e);
  const view_rect view{left, top, float(win_w) - left, bottom - top};
  // A slot whose growth failed or waits marks its (older) tree stale.
  const editor_slot& slot_a = e->ab.slots[0];
  const editor_slot& slot_b = e->ab.slots[1];
  const bool ab_drag = draw_ab_overlay(e->ab, view.x, view.y, view.w, view.h, slot_label(slot_a.doc), slot_label(slot_b.doc),
                                       !ab_slot_problem(slot_a.growth, slot_a.growth_text).empty(),
                                       !ab_slot_problem(slot_b.growth, slot_b.growth_text).empty());
  // Side by side: picking and the picked branch use the selected slot's half.
  view_rect pick_view = view;
  if (ab_showing(e->ab) && e->ab.mode == ab_mode::side_by_side) {
    pick_view.w = float(std::max(1, int(view.w) / 2));
    if (e->ab.selected == 1) pick_view.x += pick_view.w, pick_view.w = view.w - pick_view.w;
  }
  // The gizmo sits in the view's corner; with A and B on screen it would cover one slot's tree only.
  const bool on_gizmo = !ab_showing(e->ab) && draw_view_gizmo(e->camera, view);
  if (!ab_drag && !on_gizmo) handle_mouse(*e, pick_view);
  draw_prune_overlay(e->prune, e->cur().shown && e->cur().shown->skeleton ? e->cur().shown->skeleton.get() : nullptr, e->step,
                     e->camera, pick_view);
  record_undo(*e);
  autosave(*e, dt);

  post_if_changed(*e);
  take_new_tree(*e);
  restore_slot_b(*e);
  ab_poll_other(e->ab, e->step);
  if (e->ab.other().worker) e->ab.other().worker->node_budget = e->cur().worker->node_budget.load();
  script_state& script = r.script;
  if (r.scripted && !script.failed && !script.finished) {
    if (script.frames_left > 0) --script.frames_left;
    else {
      script.frames_left = -1;
      if (!run_script(*e, script)) {
        if (script.failed) r.exit_code = 3;
        e->quit_confirmed = true;
        glfwSetWindowShouldClose(r.window, GLFW_TRUE);
      }
    }
  }

  advance_playback(*e, dt);
  if (e->frame_now && e->cur().shown) {
    // With A and B on screen, both trees fit (the same camera draws both).
    glm::vec3 lo = e->cur().renderer.bounds_min, hi = e->cur().renderer.bounds_max;
    if (ab_showing(e->ab) && e->ab.other().shown) {
      lo = glm::min(lo, e->ab.other().renderer.bounds_min);
      hi = glm::max(hi, e->ab.other().renderer.bounds_max);
    }
    frame_view(e->camera, lo, hi, e->view_aspect);
  }
  e->frame_now = false;
  return {left, top, bottom};
}

// The 3D view in framebuffer pixels (origin bottom-left).
struct view_pixels {
  int x, y, w, h;
};

// A frame, second half: the 3D view drawn between the panels, the selected slot's tree (or A and
// B), and the screenshot F12 or Screenshot as... asked for, before the UI is drawn over it.
view_pixels draw_view(editor_run& r, const frame_layout& at, int fb_w, int fb_h, int win_w, int win_h, double dt, int keys_fed) {
  editor_state* e = r.e.get();
  const float left = at.left, top = at.top, bottom = at.bottom;
  // The 3D view fills the area between the panels (framebuffer pixels, origin bottom-left).
  const float sx = win_w > 0 ? float(fb_w) / float(win_w) : 1, sy = win_h > 0 ? float(fb_h) / float(win_h) : 1;
  const int vx = int(left * sx), vy = int((float(win_h) - bottom) * sy);
  const int vw = std::max(1, fb_w - vx), vh = std::max(1, int((bottom - top) * sy));
  e->view_aspect = float(vw) / float(vh);   // framing fits the tree to the 3D view's own shape
  const bool side_by_side = ab_showing(e->ab) && e->ab.mode == ab_mode::side_by_side;
  if (side_by_side) e->view_aspect = float(std::max(1, vw / 2)) / float(vh);
  // Each half is half as wide as the view: going into or out of side by side frames the trees
  // again for the new shape (next frame), as F would; a camera moved meanwhile is kept otherwise.
  if (side_by_side != e->framed_side_by_side) e->frame_now = true;
  e->framed_side_by_side = side_by_side;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, fb_w, fb_h);
  glClearColor(0.1f, 0.1f, 0.11f, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  editor_slot& c = e->cur();
  if (c.renderer.ok && c.shown && c.shown->skeleton)
    editor_lod_update(c.lod, c.renderer, c.shown, c.doc.render, e->camera, e->step);
  // Wind time runs only while the wind blows, so turning it on resumes where it stopped.
  if (c.doc.render.wind.enabled) c.renderer.wind_time = float(std::fmod(double(c.renderer.wind_time) + dt, 3600.0));
  if (c.renderer.ok && ab_showing(e->ab)) {   // A/B: both slots, same camera, sun and step
    editor_slot& o = e->ab.other();
    if (o.renderer.ok && o.shown && o.shown->skeleton)
      editor_lod_update(o.lod, o.renderer, o.shown, o.doc.render, e->camera, std::min(e->step, o.shown->skeleton->steps));
    ab_draw(e->ab, e->camera, vx, vy, vw, vh, e->show_overlays ? &e->overlays : nullptr);
  } else if (c.renderer.ok) {
    // While the user drags, orbits or types, a cheaper picture (app/editor/view_quality.h); the
    // settling frames after the release draw the full one.
    // A frame whose picture would not change shows the last one again (a menu, a hover).
    const overlay_view* ov = e->show_overlays ? &e->overlays : nullptr;
    const bool cheap = !e->full_quality && interacting(ImGui::GetIO(), ImGui::IsAnyItemActive(), keys_fed) &&
                       draw_interactive(e->quick_view, c.renderer, c.doc.render, e->camera, vx, vy, vw, vh, ov);
    if (cheap) {
      ++e->cheap_frames;
      e->kept_view.valid = false;
    } else if (!e->full_quality && show_kept_view(e->kept_view, view_key_of(c.renderer, e->camera, c.doc.render, ov, vx, vy, vw, vh))) {
      ++e->kept_frames;
    } else {
      draw_frame(c.renderer, c.doc.render, e->camera, vw, vh, {}, ov, {vx, vy});
      keep_view(e->kept_view, view_key_of(c.renderer, e->camera, c.doc.render, ov, vx, vy, vw, vh));
    }
  }
  if (c.renderer.texture_message != e->texture_message) {
    e->texture_message = c.renderer.texture_message;
    if (!e->texture_message.empty()) set_status(*e, "Texture: " + e->texture_message, true);
  }
  // F12 and Screenshot as: the 3D view alone, read before the menus and panels are drawn over it.
  if (e->screenshot_requested || !e->screenshot_to.empty()) {
    std::string path = e->screenshot_to;
    if (path.empty()) {
      std::error_code ec;
      fs::create_directories(fs::path(e->home) / "screenshots", ec);
      path = (fs::path(e->home) / "screenshots" / screenshot_name()).string();
    }
    std::string err = save_region_png(vx, vy, vw, vh, path);
    if (err.empty()) note_recent(e->recent, path);
    set_status(*e, err.empty() ? "Screenshot saved to " + path : "Screenshot failed: " + err, !err.empty());
    e->screenshot_requested = false;
    e->screenshot_to.clear();
  }
  return {vx, vy, vw, vh};
}

// The whole-window screenshots, once the UI is drawn: SYLVA_SCREENSHOT's (then the editor closes)
// and the script's `shot`.
void window_shots(editor_run& r, int fb_w, int fb_h, std::chrono::steady_clock::time_point now) {
  const editor_options& o = r.o;
  editor_state* e = r.e.get();
  if (e->cur().shown) ++r.frames_with_tree;
  const bool auto_shot = !o.screenshot_path.empty() && r.frames_with_tree >= o.frames;
  const double waited = std::chrono::duration<double>(now - r.started).count();
  if (auto_shot || (!o.screenshot_path.empty() && waited > 60)) {   // SYLVA_SCREENSHOT: the whole window
    const std::string& path = o.screenshot_path;
    std::string err = save_window_png(fb_w, fb_h, path);
    set_status(*e, err.empty() ? "Screenshot saved to " + path : "Screenshot failed: " + err, !err.empty());
    {
      if (!err.empty() || !auto_shot) r.exit_code = 1;
      if (!auto_shot) std::fprintf(stderr, "sylva: no tree after 60 s; screenshot taken anyway\n");
      glfwSetWindowShouldClose(r.window, GLFW_TRUE);
    }
  }
  if (!e->script_shot.empty() && r.script.frames_left == 1) {
    if (std::string err = save_window_png(fb_w, fb_h, e->script_shot); !err.empty()) std::fprintf(stderr, "sylva: %s\n", err.c_str());
    e->script_shot.clear();
  }
}

// The frames, until the window closes. An editor with nothing to do waits for events and draws
// nothing (docs/design/09-editor.md "An editor that idles"); work finishing on another thread
// wakes it (app/common/wake.h).
void run_frames(editor_run& r) {
  editor_state* e = r.e.get();
  GLFWwindow* window = r.window;
  r.started = std::chrono::steady_clock::now();
  auto last = r.started;
  frame_pacer pacer;
  ui_waker = +[] { glfwPostEmptyEvent(); };
  while (!glfwWindowShouldClose(window)) {
    const bool busy = r.automated || (r.scripted && !r.script.idling()) || !drawing_reason(*e).empty();
    const bool draw = next_frame(pacer, e->input, busy, 0.5);
    auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - last).count();
    last = now;
    if (!draw) {   // nothing changed: no frame, but the autosave keeps its time
      autosave(*e, dt);
      continue;
    }
    ++e->frames_drawn;
    if (!pacer.waited) e->frame_ms += (dt * 1000.0 - e->frame_ms) * 0.1;   // smoothed for reading; a wait is no frame time

    if (e->rescale_to > 0 && !r.o.ui_scale) {
      apply_ui_scale(e->rescale_to);
      ImGui_ImplOpenGL3_DestroyFontsTexture();
      ImGui_ImplOpenGL3_CreateFontsTexture();
    }
    e->rescale_to = 0;
    const int keys_fed = feed_imgui(e->input, ImGui::GetIO());
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    feed_mouse(e->input, ImGui::GetIO());   // after the backend's poll: buttons and position in order
    ImGui::NewFrame();

    int fb_w = 0, fb_h = 0, win_w = 0, win_h = 0;
    glfwGetFramebufferSize(window, &fb_w, &fb_h);
    glfwGetWindowSize(window, &win_w, &win_h);
    const frame_layout at = build_ui(r, win_w, win_h, dt);

    update_thumbnails(e->browser);   // GL is main-thread only: between building the UI and drawing
    if (const std::string title = window_title_text(*e); title != e->window_title) glfwSetWindowTitle(window, (e->window_title = title).c_str());
    ImGui::Render();
    draw_view(r, at, fb_w, fb_h, win_w, win_h, dt, keys_fed);
    glViewport(0, 0, fb_w, fb_h);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    window_shots(r, fb_w, fb_h, now);
    glfwSwapBuffers(window);
    if (r.scripted) idle_mark_start(r.script, e->frames_drawn);
  }
}

// Shutdown: the window's place and the settings saved (not for automatic runs), then everything
// freed in the reverse order of start-up. Returns the exit code.
int shut_down(editor_run& r) {
  const editor_options& o = r.o;
  editor_state* e = r.e.get();
  GLFWwindow* window = r.window;
  if (r.scripted && !r.script.finished && !r.script.failed)
    std::printf("sylva script: the editor closed before line %zu\n", r.script.next + 1);
  if (r.remember_window) {
    r.settings.maximized = glfwGetWindowAttrib(window, GLFW_MAXIMIZED) == GLFW_TRUE;
    if (!r.settings.maximized) {
      glfwGetWindowPos(window, &r.settings.x, &r.settings.y);
      glfwGetWindowSize(window, &r.settings.width, &r.settings.height);
    }
  }
  if (o.screenshot_path.empty() && !r.scripted) {
    r.settings.node_budget = e->cur().worker->node_budget.load();
    r.settings.recent = e->recent;
    save_settings(e->home, r.settings);
  }
  ui_waker = nullptr;
  free_interactive(e->quick_view);
  free_view_cache(e->kept_view);
  shutdown_export_dialog(e->exporter);
  ab_free_gl(e->ab);   // both slots: workers stopped, renderers freed
  shutdown_preset_browser(e->browser);
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  int exit_code = r.exit_code;
  if (!o.screenshot_path.empty() && gl_error_count() > 0) {
    std::fprintf(stderr, "sylva: %d GL error(s): %s\n", gl_error_count(), gl_last_message().c_str());
    exit_code = 1;
  }
  return exit_code;
}

}  // namespace

int run_editor(const std::string& preset_path) { return run_editor(options_from_environment(preset_path)); }

int run_editor(const editor_options& o) {
  editor_run r{o};
  if (const int code = start_document(r); code >= 0) return code;
  if (const int code = open_window(r); code >= 0) return code;
  run_frames(r);
  return shut_down(r);
}

}  // namespace sylva
