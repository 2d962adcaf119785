// The editor: GLFW window, ImGui panels generated from visit_params, timeline, presets, undo.
#include "app/editor.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>
#include <imgui_stdlib.h>

#include "app/editor_generators.h"
#include "app/export_dialog.h"
#include "app/headless.h"
#include "app/preset_browser.h"
#include "app/worker.h"
#include "render/export.h"
#include "render/files.h"
#include "render/gl/renderer.h"

namespace sylva {

namespace {

namespace fs = std::filesystem;

constexpr float panel_width = 420;
constexpr float timeline_height = 38;
constexpr float status_height = 26;

struct editor_state {
  preset doc;                     // the edited copy (DESIGN §9: edit a copy, commit on change)
  preset undo_base;               // doc as of the last undo step
  std::vector<preset> undo, redo;
  std::string path;               // where Save writes ("" until saved or opened)
  // Growth.
  worker_state worker;
  tree_spec posted_spec;
  mesh_params posted_mesh;
  bool posted_once = false;
  bool hold_post = false;         // an apply-on-release slider is being dragged
  uint32_t seen_generation = 0;
  std::shared_ptr<const grow_result> shown;
  int step = 0;
  bool playing = false;
  float speed = 4;                // steps per second
  double play_accum = 0;
  // View.
  renderer_state renderer;
  orbit_camera camera;
  bool frame_pending = true;      // frame the camera on the next tree
  bool show_overlays = false, show_panel = true, show_timeline = true, show_advanced = false;
  // Dialogs.
  bool open_picker = false, open_save_as = false, open_about = false;
  std::string picker_path, save_as_path;
  std::vector<std::string> preset_files;
  // Status.
  std::string message;
  bool message_is_error = false;
  double frame_ms = 0;
  bool screenshot_requested = false;
  std::string screenshot_path;
  std::string texture_message;    // the renderer's last texture error, once shown
  export_dialog_state exporter;   // app/export_dialog.h
  preset_browser_state browser;   // app/preset_browser.h; also holds the last saved preset
  generator_panel_state generator_panels;   // app/editor_generators.h
};

void set_status(editor_state& e, const std::string& m, bool error = false) {
  e.message = m;
  e.message_is_error = error;
  if (error) std::fprintf(stderr, "sylva: %s\n", m.c_str());
}

// ---------------------------------------------------------------- parameter panel

// Collects pointers to each field of a defaults struct in visit order, so the drawer can reset
// field i to its default without a second declaration of anything.
template <class P>
std::vector<const void*> default_pointers(const P& defaults) {
  std::vector<const void*> out;
  visit_params(defaults, [&](const auto& value, const param_info&) { out.push_back(&value); });
  return out;
}

struct param_drawer {
  const std::vector<const void*>& defaults;
  const char* section;     // header for parameters before the first group
  bool show_advanced;
  bool changed = false;
  bool hold = false;       // an apply-on-release item is active
  bool open = true;
  bool header_drawn = false;
  const char* pending_header = nullptr;   // drawn before the group's first shown parameter
  bool relevant = true;                   // param_relevant() for the parameter being visited
  std::vector<step_column>* steps = nullptr;   // the struct's per-step schedules, drawn as one table
  bool steps_drawn = false;
  size_t index = 0;

  // "symbol  label##key" in a fixed buffer: building the panel allocates nothing per frame.
  char buffer[256];
  const char* label(const param_info& info) {
    if (info.symbol && *info.symbol) std::snprintf(buffer, sizeof buffer, "%s  %s##%s", info.symbol, info.label, info.key);
    else std::snprintf(buffer, sizeof buffer, "%s##%s", info.label, info.key);
    return buffer;
  }

  template <class T>
  void operator()(T& value, const param_info& info) {
    const T& def = *static_cast<const T*>(defaults[index++]);
    if (info.group || !header_drawn) {
      pending_header = info.group ? info.group : section;
      header_drawn = true;
    }
    // Hidden in the current mode; multi-line texts get their own panel (draw_generator_panel).
    if (!relevant || (info.flags & param_multiline)) return;
    if (pending_header) {
      open = ImGui::CollapsingHeader(pending_header, ImGuiTreeNodeFlags_DefaultOpen);
      pending_header = nullptr;
    }
    if (!open || ((info.flags & param_advanced) && !show_advanced)) return;
    if constexpr (std::is_same_v<T, std::vector<float>>) {
      if (steps && !steps->empty()) {   // all schedules in one table, where the first one is declared
        if (!steps_drawn) changed |= draw_step_table(*steps, hold);
        steps_drawn = true;
        return;
      }
    }
    ImGui::PushID(info.key);
    const char* l = label(info);
    bool edited = false;
    const int slider_flags = (info.flags & param_log) ? ImGuiSliderFlags_Logarithmic : 0;
    if constexpr (std::is_same_v<T, float>) {
      const char* fmt = (info.flags & param_degrees) ? "%.1f°" : (info.flags & param_log) ? "%.4g" : "%.3f";
      edited = ImGui::SliderFloat(l, &value, info.min, info.max, fmt, slider_flags);
    } else if constexpr (std::is_same_v<T, int>) {
      edited = ImGui::SliderInt(l, &value, int(info.min), int(info.max), "%d", slider_flags);
    } else if constexpr (std::is_same_v<T, bool>) {
      edited = ImGui::Checkbox(l, &value);
    } else if constexpr (std::is_enum_v<T>) {
      int v = int(value);
      const int n = option_count(info);
      if (ImGui::Combo(l, &v, info.options, n)) { value = T(v); edited = true; }
    } else if constexpr (std::is_same_v<T, glm::vec3>) {
      // A colour is a vec3 on [0,1] that is not a direction; sizes and offsets get plain drags.
      const bool colour = !(info.flags & param_direction) && info.min == 0 && info.max == 1;
      if (colour) edited = ImGui::ColorEdit3(l, &value.x, ImGuiColorEditFlags_Float);
      else edited = ImGui::DragFloat3(l, &value.x, std::max((info.max - info.min) * 0.001f, 0.001f), info.min, info.max);
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (info.flags & param_multiline) {
        ImGui::TextUnformatted(info.label);
        edited = ImGui::InputTextMultiline("##text", &value, ImVec2(-1, 180));
      } else {
        edited = ImGui::InputText(l, &value);
      }
    } else if constexpr (std::is_same_v<T, std::vector<float>>) {
      ImGui::TextUnformatted(l, std::strstr(l, "##"));
      for (size_t i = 0; i < value.size(); ++i) {
        ImGui::PushID(int(i));
        if (i) ImGui::SameLine();
        ImGui::SetNextItemWidth(52);
        edited |= ImGui::DragFloat("##v", &value[i], (info.max - info.min) * 0.002f, info.min, info.max, "%.2f");
        ImGui::PopID();
      }
      ImGui::SameLine();
      if (ImGui::SmallButton("+")) { value.push_back(value.empty() ? info.min : value.back()); edited = true; }
      ImGui::SameLine();
      if (ImGui::SmallButton("-") && !value.empty()) { value.pop_back(); edited = true; }
    } else if constexpr (std::is_same_v<T, std::vector<glm::vec3>>) {
      ImGui::TextUnformatted(l, std::strstr(l, "##"));
      for (size_t i = 0; i < value.size(); ++i) {
        ImGui::PushID(int(i));
        edited |= ImGui::DragFloat3("##v", &value[i].x, 0.01f, info.min, info.max);
        ImGui::PopID();
      }
      if (ImGui::SmallButton("+")) { value.push_back(value.empty() ? glm::vec3(0) : value.back()); edited = true; }
      ImGui::SameLine();
      if (ImGui::SmallButton("-") && !value.empty()) { value.pop_back(); edited = true; }
    }
    if (ImGui::IsItemHovered() && info.help && *info.help)
      ImGui::SetTooltip("%s\n(right-click: reset to default)", info.help);
    if (ImGui::IsItemClicked(ImGuiMouseButton_Right) && !(value == def)) {
      value = def;
      edited = true;
    }
    if ((info.flags & param_on_release) && ImGui::IsItemActive()) hold = true;
    changed |= edited;
    ImGui::PopID();
  }
};

template <class P>
bool draw_params(P& p, const char* section, editor_state& e) {
  static const P defaults{};
  static const std::vector<const void*> pointers = default_pointers(defaults);
  param_drawer d{pointers, section, e.show_advanced};
  std::vector<step_column> steps = collect_step_columns(p);
  d.steps = &steps;
  visit_params(p, [&](auto& value, const param_info& info) {
    d.relevant = param_relevant(std::as_const(p), &value, info);
    d(value, info);
  });
  e.hold_post |= d.hold;
  return d.changed;
}

// ---------------------------------------------------------------- presets

std::vector<fs::path> preset_dirs() {
  std::vector<fs::path> dirs;
#ifdef SYLVA_SOURCE_DIR
  dirs.emplace_back(fs::path(SYLVA_SOURCE_DIR) / "presets");
#endif
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    dirs.push_back(exe.parent_path() / "presets");
    dirs.push_back(exe.parent_path().parent_path() / "presets");
  }
  dirs.push_back(fs::current_path(ec) / "presets");
  return dirs;
}

void scan_presets(editor_state& e) {
  e.preset_files.clear();
  for (const fs::path& d : preset_dirs()) {
    std::error_code ec;
    if (!fs::is_directory(d, ec)) continue;
    for (const auto& entry : fs::directory_iterator(d, ec))
      if (entry.path().extension() == ".json") e.preset_files.push_back(fs::weakly_canonical(entry.path(), ec).string());
  }
  std::sort(e.preset_files.begin(), e.preset_files.end());
  e.preset_files.erase(std::unique(e.preset_files.begin(), e.preset_files.end()), e.preset_files.end());
}

void open_preset(editor_state& e, const std::string& path) {
  preset loaded;
  load_result r = load_preset_file(path, loaded);
  if (!r.ok) {   // the current tree stays as it is
    set_status(e, "Cannot open " + path + ": " + r.error, true);
    return;
  }
  e.undo.push_back(e.doc);
  e.redo.clear();
  e.doc = loaded;
  e.undo_base = loaded;
  e.path = path;
  note_saved_preset(e.browser, e.doc, path);
  e.frame_pending = true;
  std::string m = "Opened " + path;
  if (!r.warnings.empty()) m += " (" + std::to_string(r.warnings.size()) + " warning(s): " + r.warnings.front() + ")";
  set_status(e, m, false);
}

void save_to(editor_state& e, const std::string& path) {
  std::string err = save_preset_file(e.doc, path);
  if (!err.empty()) return set_status(e, "Save failed: " + err, true);
  e.path = path;
  note_saved_preset(e.browser, e.doc, path);
  set_status(e, "Saved " + path);
}

// ---------------------------------------------------------------- undo

void apply_undo(editor_state& e, std::vector<preset>& from, std::vector<preset>& to) {
  if (from.empty()) return;
  to.push_back(e.doc);
  e.doc = from.back();
  from.pop_back();
  e.undo_base = e.doc;
}

// One undo step per completed edit: nothing is recorded while a widget is held.
void record_undo(editor_state& e) {
  if (ImGui::IsAnyItemActive() || e.doc == e.undo_base) return;
  e.undo.push_back(e.undo_base);
  if (e.undo.size() > 200) e.undo.erase(e.undo.begin());
  e.redo.clear();
  e.undo_base = e.doc;
}

// ---------------------------------------------------------------- UI

void draw_menu(editor_state& e, GLFWwindow* window) {
  if (!ImGui::BeginMainMenuBar()) return;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("Open preset...", "Ctrl+O")) e.open_picker = true;
    ImGui::MenuItem("Preset library", "Ctrl+L", &e.browser.open);
    if (ImGui::MenuItem("Save", "Ctrl+S")) {
      if (e.path.empty()) e.open_save_as = true;
      else save_to(e, e.path);
    }
    if (ImGui::MenuItem("Save as...")) e.open_save_as = true;
    ImGui::MenuItem("Export...", nullptr, &e.exporter.open);
    if (ImGui::MenuItem("Screenshot", "F12")) e.screenshot_requested = true;
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) glfwSetWindowShouldClose(window, GLFW_TRUE);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    if (ImGui::MenuItem("Undo", "Ctrl+Z", false, !e.undo.empty())) apply_undo(e, e.undo, e.redo);
    if (ImGui::MenuItem("Redo", "Ctrl+Shift+Z", false, !e.redo.empty())) apply_undo(e, e.redo, e.undo);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    ImGui::MenuItem("Growth overlays", nullptr, &e.show_overlays);
    draw_overlay_menu(e.renderer.overlay.view, e.renderer.overlay);
    ImGui::MenuItem("Parameter panel", nullptr, &e.show_panel);
    ImGui::MenuItem("Timeline", nullptr, &e.show_timeline);
    ImGui::MenuItem("Advanced parameters", nullptr, &e.show_advanced);
    if (ImGui::MenuItem("Frame tree", "F")) e.frame_pending = true;
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Help")) {
    if (ImGui::MenuItem("About Sylva")) e.open_about = true;
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
}

void draw_panel(editor_state& e, float top, float bottom) {
  ImGui::SetNextWindowPos(ImVec2(0, top));
  ImGui::SetNextWindowSize(ImVec2(panel_width, bottom - top));
  ImGui::Begin("Parameters", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoTitleBar);
  ImGui::PushItemWidth(-205);
  tree_spec& spec = e.doc.spec;
  int g = int(spec.params.index());
  if (ImGui::Combo("Generator", &g, generator_labels, generator_count) && g != int(spec.params.index())) {
    spec.params = default_params(g);
    e.frame_pending = true;
  }
  int seed = int(spec.seed & 0x7fffffff);
  if (ImGui::InputInt("Seed", &seed)) spec.seed = uint64_t(std::max(seed, 0));
  ImGui::SameLine();
  if (ImGui::Button("Randomize")) spec.seed = std::random_device{}() & 0x7fffffff;
  std::visit([&](auto& p) { draw_params(p, generator_labels[spec.params.index()], e); }, spec.params);
  draw_generator_panel(e.generator_panels, spec, e.shown.get());
  draw_params(e.doc.mesh, "Mesh", e);
  // Time-of-day presets: a starting point for the lighting sliders below.
  render_params& rp = e.doc.render;
  ImGui::Separator();
  ImGui::TextUnformatted("Time of day");
  ImGui::SameLine();
  if (ImGui::SmallButton("Noon")) {
    rp.sun_elevation = 70, rp.sun_azimuth = 25, rp.sun_color = {1.0f, 0.97f, 0.92f}, rp.sun_intensity = 2.4f;
    rp.sky_zenith = {0.22f, 0.42f, 0.85f}, rp.sky_horizon = {0.72f, 0.83f, 0.95f};
  }
  ImGui::SameLine();
  if (ImGui::SmallButton("Golden hour")) {
    rp.sun_elevation = 10, rp.sun_azimuth = std::remainder(e.camera.yaw + 60.0f, 360.0f), rp.sun_color = {1.0f, 0.72f, 0.42f}, rp.sun_intensity = 2.0f;
    rp.sky_zenith = {0.28f, 0.38f, 0.68f}, rp.sky_horizon = {0.95f, 0.76f, 0.55f};
  }
  ImGui::SameLine();
  if (ImGui::SmallButton("Backlit rays")) {   // the sun straight behind the tree as seen now
    rp.sun_azimuth = std::remainder(e.camera.yaw + 180.0f, 360.0f), rp.sun_elevation = 12;
    rp.sun_color = {1.0f, 0.88f, 0.7f}, rp.sun_intensity = 2.2f;
    if (rp.shafts == light_shafts::off) rp.shafts = light_shafts::volumetric;
  }
  draw_params(e.doc.render, "Render", e);
  ImGui::PopItemWidth();
  ImGui::End();
}

void draw_timeline(editor_state& e, float x, float y, float w) {
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowSize(ImVec2(w, timeline_height));
  ImGui::Begin("Timeline", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoTitleBar |
                   ImGuiWindowFlags_NoScrollbar);
  const int steps = e.shown && e.shown->skeleton ? e.shown->skeleton->steps : 0;
  if (ImGui::Button("|<")) e.step = std::max(0, e.step - 1);
  ImGui::SameLine();
  if (ImGui::Button(e.playing ? "Pause" : "Play")) {
    e.playing = !e.playing;
    if (e.playing && e.step >= steps) e.step = 0;
  }
  ImGui::SameLine();
  if (ImGui::Button(">|")) e.step = std::min(steps, e.step + 1);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(110);
  ImGui::SliderFloat("##speed", &e.speed, 0.25f, 30, "%.2g steps/s", ImGuiSliderFlags_Logarithmic);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1);
  ImGui::SliderInt("##step", &e.step, 0, std::max(steps, 0), "step %d");
  ImGui::End();
}

void draw_status(editor_state& e, float y, float w) {
  ImGui::SetNextWindowPos(ImVec2(0, y));
  ImGui::SetNextWindowSize(ImVec2(w, status_height));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8, 4));
  ImGui::Begin("Status", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoTitleBar |
                   ImGuiWindowFlags_NoScrollbar);
  const grow_result* r = e.shown.get();
  ImGui::Text("nodes %zu   leaves %zu   triangles %zu   grow %.1f ms   mesh %.1f ms   frame %.1f ms%s",
              r && r->skeleton ? r->skeleton->size() : size_t(0), e.renderer.leaves_drawn, e.renderer.triangles_drawn,
              r ? r->grow_ms : 0.0, r ? r->mesh_ms : 0.0, e.frame_ms, e.worker.busy ? "   growing..." : "");
  ImGui::SameLine();
  const std::string& m = !e.message.empty() || !r ? e.message : r->report.message;
  const bool err = e.message_is_error || (e.message.empty() && r && r->report.error);
  ImGui::TextColored(err ? ImVec4(1, 0.45f, 0.4f, 1) : ImVec4(0.75f, 0.85f, 0.75f, 1), "   %s", m.c_str());
  if (r && !r->mesh.message.empty()) {   // the leaf cap: growth went on, the foliage stopped
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(1, 0.8f, 0.4f, 1), "   %s", r->mesh.message.c_str());
  }
  if (r && !r->report.stop_reason.empty()) {   // why growth ended: points used up, cap, step limit ...
    ImGui::SameLine();
    ImGui::TextDisabled("   ended: %s", r->report.stop_reason.c_str());
  }
  ImGui::End();
  ImGui::PopStyleVar();
}

void draw_dialogs(editor_state& e) {
  if (e.open_picker) {
    scan_presets(e);
    ImGui::OpenPopup("Open preset");
    e.open_picker = false;
  }
  if (e.open_save_as) {
    if (e.save_as_path.empty()) e.save_as_path = e.path.empty() ? "my_tree.json" : e.path;
    ImGui::OpenPopup("Save preset as");
    e.open_save_as = false;
  }
  if (e.open_about) {
    ImGui::OpenPopup("About Sylva");
    e.open_about = false;
  }
  ImGui::SetNextWindowSize(ImVec2(620, 420), ImGuiCond_Appearing);
  if (ImGui::BeginPopupModal("Open preset")) {
    ImGui::BeginChild("list", ImVec2(0, -60), true);
    for (const std::string& f : e.preset_files) {
      const std::string name = fs::path(f).filename().string();
      if (ImGui::Selectable(name.c_str(), e.picker_path == f, ImGuiSelectableFlags_AllowDoubleClick)) {
        e.picker_path = f;
        if (ImGui::IsMouseDoubleClicked(0)) {
          open_preset(e, f);
          ImGui::CloseCurrentPopup();
        }
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", f.c_str());
    }
    if (e.preset_files.empty()) ImGui::TextDisabled("No presets/ folder found; type a path below.");
    ImGui::EndChild();
    ImGui::SetNextItemWidth(-130);
    ImGui::InputText("##path", &e.picker_path);
    ImGui::SameLine();
    if (ImGui::Button("Open") && !e.picker_path.empty()) {
      open_preset(e, e.picker_path);
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  if (ImGui::BeginPopupModal("Save preset as", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::InputText("Name", &e.doc.name);
    ImGui::SetNextItemWidth(480);
    ImGui::InputText("Path", &e.save_as_path);
    if (ImGui::Button("Save") && !e.save_as_path.empty()) {
      save_to(e, e.save_as_path);
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  if (ImGui::BeginPopupModal("About Sylva", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::TextUnformatted("Sylva: a tree designer.");
    ImGui::TextUnformatted("Left-drag orbits, right/middle-drag pans, the wheel zooms, F frames the tree.");
    ImGui::TextUnformatted("Ctrl+Z undo, Ctrl+Shift+Z / Ctrl+Y redo, Ctrl+S save, Ctrl+O open, F12 screenshot.");
    ImGui::TextUnformatted("Right-click a slider to reset it. Symbols: λ σ τ κ φ α s₀ w₀ r₁ r₂");
    if (ImGui::Button("Close")) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
}

void handle_keys(editor_state& e, GLFWwindow* window) {
  ImGuiIO& io = ImGui::GetIO();
  if (io.WantTextInput) return;
  const bool ctrl = io.KeyCtrl, shift = io.KeyShift;
  if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_Z)) {
    if (shift) apply_undo(e, e.redo, e.undo);
    else apply_undo(e, e.undo, e.redo);
  }
  if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_Y)) apply_undo(e, e.redo, e.undo);
  if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_S)) {
    if (e.path.empty()) e.open_save_as = true;
    else save_to(e, e.path);
  }
  if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_O)) e.open_picker = true;
  if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_L)) e.browser.open = !e.browser.open;
  if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_Q)) glfwSetWindowShouldClose(window, GLFW_TRUE);
  if (!ctrl && ImGui::IsKeyPressed(GLFW_KEY_F)) e.frame_pending = true;
  if (ImGui::IsKeyPressed(GLFW_KEY_F12)) e.screenshot_requested = true;
  if (!ctrl && ImGui::IsKeyPressed(GLFW_KEY_SPACE)) e.playing = !e.playing;
}

void handle_mouse(editor_state& e, int viewport_height) {
  ImGuiIO& io = ImGui::GetIO();
  if (io.WantCaptureMouse) return;
  const ImVec2 d = io.MouseDelta;
  if (ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0)) orbit_camera_rotate(e.camera, d.x, d.y);
  if (ImGui::IsMouseDragging(ImGuiMouseButton_Right, 0) || ImGui::IsMouseDragging(ImGuiMouseButton_Middle, 0))
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
    if (fs::exists(candidates[i]) && io.Fonts->AddFontFromFileTTF(candidates[i], 16.0f, nullptr, ranges)) return;
  std::fprintf(stderr, "sylva: DejaVu Sans not found (install fonts-dejavu-core); Greek symbols will not show\n");
  io.Fonts->AddFontDefault();
}

std::string save_window_png(int width, int height, const std::string& path) {
  std::vector<unsigned char> pixels(size_t(width) * size_t(height) * 4), flipped(pixels.size());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  const size_t row = size_t(width) * 4;
  for (int y = 0; y < height; ++y) std::copy_n(&pixels[size_t(height - 1 - y) * row], row, &flipped[size_t(y) * row]);
  for (size_t i = 3; i < flipped.size(); i += 4) flipped[i] = 255;
  return save_png_rgba(path, width, height, flipped.data());
}

// Shows a newer worker result: upload in the same frame it is seen (DESIGN §5).
void take_new_tree(editor_state& e) {
  std::shared_ptr<const grow_result> r = take_result(e.worker, e.seen_generation);
  if (!r) return;
  e.seen_generation = r->generation;
  if (e.shown && keeps_last_tree(*r)) return set_status(e, r->report.message, true);
  const int old_steps = e.shown && e.shown->skeleton ? e.shown->skeleton->steps : -1;
  const bool at_end = !e.shown || e.step >= old_steps;
  e.shown = r;
  upload_tree(e.renderer, r->mesh);
  upload_overlays(e.renderer, r->debug ? *r->debug : growth_debug{}, r->skeleton.get(), int(r->spec.params.index()));
  const int steps = r->skeleton->steps;
  e.step = at_end ? steps : std::min(e.step, steps);
  set_tree_step(e.renderer, *r->skeleton, r->mesh_settings.min_radius, e.step);
  if (e.frame_pending) {
    frame_camera(e.camera, e.renderer.bounds_min, e.renderer.bounds_max);
    e.frame_pending = false;
  }
  if (e.message_is_error && e.message.rfind("Cannot open", 0) != 0) e.message.clear();
}

}  // namespace

int run_editor(const std::string& preset_path) {
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
    }
  }
  return run_editor(o);
}

int run_editor(const editor_options& o) {
  auto e = std::make_unique<editor_state>();
  e->doc = default_preset();
  if (!o.preset_path.empty()) {
    preset loaded;
    load_result r = load_preset_file(o.preset_path, loaded);
    if (!r.ok) {
      std::fprintf(stderr, "sylva: cannot open %s: %s\n", o.preset_path.c_str(), r.error.c_str());
      set_status(*e, "Cannot open " + o.preset_path + ": " + r.error + " (showing the default tree)", true);
    } else {
      e->doc = loaded;
      e->path = o.preset_path;
      if (!r.warnings.empty()) set_status(*e, r.warnings.front());
    }
  }
  e->undo_base = e->doc;
  note_saved_preset(e->browser, e->doc, e->path);
  e->show_overlays = o.overlays;
  if (const char* s = std::getenv("SYLVA_SHOW_BROWSER")) e->browser.open = std::atoi(s) != 0;
  if (const char* s = std::getenv("SYLVA_SHOW_EXPORT")) e->exporter.open = std::atoi(s) != 0;

  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!display || !*display) && (!wayland || !*wayland)) {
    std::fprintf(stderr, "sylva: the editor needs a display (DISPLAY is not set); try `sylva export` instead\n");
    return 1;
  }
  bool up = glfwInit();
  if (!up) {   // a display shared with other clients now and then refuses one connection: retry once
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    up = glfwInit();
  }
  if (!up) {
    const char* why = nullptr;
    glfwGetError(&why);
    std::fprintf(stderr, "sylva: cannot initialise GLFW: %s\n", why ? why : "unknown reason");
    return 1;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(o.width, o.height, "Sylva", nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "sylva: cannot create an OpenGL 3.3 core window\n");
    glfwTerminate();
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(o.screenshot_path.empty() ? 1 : 0);
  install_gl_debug_output();

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;   // the layout is fixed; no imgui.ini litter
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 0;
  load_fonts();
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");

  if (!init_renderer(e->renderer)) set_status(*e, e->renderer.error, true);
  start_worker(e->worker);
  {
    std::vector<std::string> folders;
    for (const fs::path& d : preset_dirs()) folders.push_back(d.string());
    init_preset_browser(e->browser, folders);
  }
  std::string window_title;

  int exit_code = 0, frames_with_tree = 0;
  auto started = std::chrono::steady_clock::now();
  auto last = started;
  while (!glfwWindowShouldClose(window)) {
    glfwPollEvents();
    auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - last).count();
    last = now;
    e->frame_ms += (dt * 1000.0 - e->frame_ms) * 0.1;   // smoothed for reading

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();

    int fb_w = 0, fb_h = 0, win_w = 0, win_h = 0;
    glfwGetFramebufferSize(window, &fb_w, &fb_h);
    glfwGetWindowSize(window, &win_w, &win_h);

    // Build the UI first; only then read the state for drawing (DESIGN §9).
    e->hold_post = false;
    draw_menu(*e, window);
    const float top = ImGui::GetFrameHeight();
    const float bottom = float(win_h) - status_height - (e->show_timeline ? timeline_height : 0);
    if (e->show_panel) draw_panel(*e, top, float(win_h) - status_height);
    const float left = e->show_panel ? panel_width : 0;
    if (e->show_timeline) draw_timeline(*e, left, bottom, float(win_w) - left);
    draw_status(*e, float(win_h) - status_height, float(win_w));
    draw_dialogs(*e);
    if (std::string p = draw_preset_browser(e->browser, e->doc); !p.empty()) open_preset(*e, p);
    draw_export_dialog(e->exporter, export_context{e->shown, e->step, e->doc, e->renderer, e->camera}, e->message, e->message_is_error);
    handle_keys(*e, window);
    handle_mouse(*e, int(bottom - top));
    record_undo(*e);

    // Post growth when the spec or mesh settings changed; render settings only touch uniforms.
    if (!e->hold_post && (!e->posted_once || !(e->doc.spec == e->posted_spec) || !(e->doc.mesh == e->posted_mesh))) {
      e->posted_spec = e->doc.spec;
      e->posted_mesh = e->doc.mesh;
      e->posted_once = true;
      post_request(e->worker, e->posted_spec, e->posted_mesh);
    }
    take_new_tree(*e);

    // Playback and scrubbing: draw counts plus a small per-node upload, never a re-mesh.
    if (e->shown && e->shown->skeleton) {
      const int steps = e->shown->skeleton->steps;
      if (e->playing) {
        e->play_accum += dt * e->speed;
        while (e->play_accum >= 1.0) {
          e->play_accum -= 1.0;
          if (++e->step > steps) e->step = 0;
        }
      }
      e->step = std::clamp(e->step, 0, steps);
      if (e->step != e->renderer.step) set_tree_step(e->renderer, *e->shown->skeleton, e->shown->mesh_settings.min_radius, e->step);
    }
    if (e->frame_pending && e->shown) {
      frame_camera(e->camera, e->renderer.bounds_min, e->renderer.bounds_max);
      e->frame_pending = false;
    }

    update_thumbnails(e->browser);   // GL is main-thread only: between building the UI and drawing
    const std::string title = "Sylva - " + e->doc.name + (has_unsaved_changes(e->browser, e->doc) ? " *" : "");
    if (title != window_title) glfwSetWindowTitle(window, (window_title = title).c_str());
    ImGui::Render();
    // The 3D view fills the area between the panels (framebuffer pixels, origin bottom-left).
    const float sx = win_w > 0 ? float(fb_w) / float(win_w) : 1, sy = win_h > 0 ? float(fb_h) / float(win_h) : 1;
    const int vx = int(left * sx), vy = int((float(win_h) - bottom) * sy);
    const int vw = std::max(1, fb_w - vx), vh = std::max(1, int((bottom - top) * sy));
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fb_w, fb_h);
    glClearColor(0.1f, 0.1f, 0.11f, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    if (e->renderer.ok) draw_frame(e->renderer, e->doc.render, e->camera, vw, vh, {}, e->show_overlays, {vx, vy});
    if (e->renderer.texture_message != e->texture_message) {
      e->texture_message = e->renderer.texture_message;
      if (!e->texture_message.empty()) set_status(*e, "Texture: " + e->texture_message, true);
    }
    glViewport(0, 0, fb_w, fb_h);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

    if (e->shown) ++frames_with_tree;
    const bool auto_shot = !o.screenshot_path.empty() && frames_with_tree >= o.frames;
    const double waited = std::chrono::duration<double>(now - started).count();
    if (e->screenshot_requested || auto_shot || (!o.screenshot_path.empty() && waited > 60)) {
      std::string path = !o.screenshot_path.empty() ? o.screenshot_path : "sylva_screenshot.png";
      std::string err = save_window_png(fb_w, fb_h, path);
      set_status(*e, err.empty() ? "Screenshot saved to " + path : "Screenshot failed: " + err, !err.empty());
      e->screenshot_requested = false;
      if (!o.screenshot_path.empty()) {
        if (!err.empty() || !auto_shot) exit_code = 1;
        if (!auto_shot) std::fprintf(stderr, "sylva: no tree after 60 s; screenshot taken anyway\n");
        glfwSetWindowShouldClose(window, GLFW_TRUE);
      }
    }
    glfwSwapBuffers(window);
  }

  shutdown_export_dialog(e->exporter);
  stop_worker(e->worker);
  shutdown_preset_browser(e->browser);
  destroy_renderer(e->renderer);
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  if (!o.screenshot_path.empty() && gl_error_count() > 0) {
    std::fprintf(stderr, "sylva: %d GL error(s): %s\n", gl_error_count(), gl_last_message().c_str());
    exit_code = 1;
  }
  return exit_code;
}

}  // namespace sylva
