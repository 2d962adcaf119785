// The editor: GLFW window, ImGui panels generated from visit_params, timeline, presets, undo.
#include "app/editor.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cctype>
#include <cstring>
#include <ctime>
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

#include "app/editor_ab.h"
#include "app/editor_files.h"
#include "app/editor_generators.h"
#include "app/editor_lod.h"
#include "app/editor_keyframes.h"
#include "app/editor_prune.h"
#include "app/export_dialog.h"
#include "app/headless.h"
#include "app/input_queue.h"
#include "app/preset_browser.h"
#include "app/worker.h"
#include "render/export.h"
#include "render/preset.h"
#include "render/gl/renderer.h"

namespace sylva {

namespace {

namespace fs = std::filesystem;

// Layout sizes at a content scale of 1; multiplied by ui_scale (the monitor's content scale).
float ui_scale = 1;
float panel_width() { return 420 * ui_scale; }
bool timeline_markers = false;   // the document has keyframes: the timeline shows a row of markers
float timeline_height() { return (timeline_markers ? 54 : 38) * ui_scale; }
float status_height() { return 26 * ui_scale; }

struct editor_state {
  editor_lod lod;                 // level of detail shown in the viewport (app/editor_lod.h)
  preset doc;                     // the edited copy (DESIGN §9: edit a copy, commit on change)
  preset undo_base;               // doc as of the last undo step
  std::vector<preset> undo, redo;
  std::string path;               // where Save writes ("" until saved or opened)
  // The document before an Open whose tree has not arrived yet: a cancelled or over-budget open
  // returns to it whole (name, file, saved state), not only to its tree.
  struct document { preset doc; std::string path; preset baseline; std::string baseline_path; };
  std::unique_ptr<document> before_open;
  // Growth.
  std::unique_ptr<worker_state> worker = std::make_unique<worker_state>();   // the selected slot's (A/B)
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
  renderer_gpu renderer;
  orbit_camera camera;
  float view_aspect = 16.0f / 9.0f;  // the 3D view's width / height, for framing
  bool frame_new = true;          // frame the camera on the tree of the next request (new preset or generator)
  bool frame_now = false;         // frame the tree on screen now (F)
  bool framed_side_by_side = false;   // the A/B view was side by side when the tree was last framed
  uint32_t frame_generation = 0;  // frame the first result at or after this generation (0: none)
  int overlay_generator = -1;     // the generator whose default overlay layer is selected
  overlay_view overlays;          // which overlay layers show (UI state; the renderer only draws them)
  bool show_overlays = false, show_panel = true, show_timeline = true, show_advanced = false;
  // Dialogs.
  bool open_picker = false, open_save_as = false, open_about = false, browse_screenshot = false, browse_export = false;
  file_browser files;             // app/editor_files.h: Open, Save as, Screenshot as
  enum class browsing { open, save_as, screenshot, export_to } browse = browsing::open;
  std::vector<std::string> recent;
  std::string script_answer;      // the scripted test's click on a dialog button (see run_script)
  std::string script_shot;        // the scripted test's screenshot path, taken at the end of the frame
  // Status.
  std::string message;
  bool message_is_error = false;
  std::string toast;              // the last error in full, until dismissed or a success
  uint32_t error_after = 0;       // a tree from a newer request clears the error
  struct log_line { std::string time, text; bool error; };
  std::vector<log_line> log;      // View > Messages
  bool show_log = false, show_shortcuts = false;
  double frame_ms = 0;
  bool screenshot_requested = false;   // F12: the 3D view to ~/Sylva/screenshots/
  std::string screenshot_to;            // Screenshot as...: this path
  std::string screenshot_path;
  std::string texture_message;    // the renderer's last texture error, once shown
  export_dialog_state exporter;   // app/export_dialog.h
  preset_browser_state browser;   // app/preset_browser.h; also holds the last saved preset
  generator_panel_state generator_panels;   // app/editor_generators.h
  keyframe_panel_state keys;                // app/editor_keyframes.h: growth phases
  prune_panel_state prune;                  // app/editor_prune.h: picking, cuts, the brush
  GLFWwindow* window = nullptr;
  float rescale_to = 0;           // a new content scale to apply before the next frame (0: none)
  // Growth state (issue 14): the status bar shows exactly one of these.
  enum class growth { idle, growing, asking, done, cancelled, failed } growth_state = growth::idle;   // = ab_growth
  std::string growth_text;        // detail for done / cancelled / failed
  uint32_t posted_generation = 0; // the newest request
  uint32_t stale_before = 0;      // results older than this were cancelled
  std::chrono::steady_clock::time_point posted_at;
  std::shared_ptr<const grow_result> budget_answer;   // an over-budget estimate waiting for the user
  bool open_budget_prompt = false, approve_next = false;
  // Nodes alive at the scrubbed step (cached per tree and step).
  const tree_skeleton* counted_tree = nullptr;
  int counted_step = -1;
  size_t counted_nodes = 0;
  // Unsaved work: what to do once the user has answered save / discard / cancel.
  enum class then { nothing, quit, open } pending = then::nothing;
  std::string pending_path;
  bool open_confirm = false, continue_after_save = false, close_requested = false, quit_confirmed = false;
  bool save_all = false;          // quitting with A/B: "Save" saves every slot with changes in turn
  // Recovery: each slot's document is autosaved while modified and offered back on the next start
  // (slot A in .recovery.json, slot B in .recovery_b.json).
  std::string home;               // ~/Sylva or $SYLVA_HOME
  double autosave_wait = 0;
  preset autosaved[2];
  bool autosaved_any[2] = {false, false};
  bool open_recovery = false;
  preset recovered;
  std::string recovered_path;
  bool recovered_a = false;       // slot A's document was recovered
  bool recovered_b = false;       // slot B's too: restored as B once A's tree shows
  bool restore_b_pending = false;
  preset recovered_b_doc;
  std::string recovered_b_path;
  std::vector<std::string> prompts_shown;   // modal titles drawn this frame (for the scripted test)
  input_queue input;              // keyboard events, fed to ImGui one transition per key per frame
  ab_state ab;                    // app/editor_ab.h: slot B and the A/B view
};

// The status bar's message; errors also go to a dismissable toast, and every message to the log.
// A successful action's message replaces an earlier error, and its toast goes away.
void set_status(editor_state& e, const std::string& m, bool error = false) {
  e.message = m;
  e.message_is_error = error;
  if (error) std::fprintf(stderr, "sylva: %s\n", m.c_str());
  e.toast = error ? m : "";
  // A tree from a later request is a successful action that clears this error (the first request
  // is generation 1: an error while opening the start preset stays over its tree).
  if (error) e.error_after = e.posted_once ? e.posted_generation : 1;
  if (m.empty()) return;
  char stamp[16] = "";
  const std::time_t t = std::time(nullptr);
  std::strftime(stamp, sizeof stamp, "%H:%M:%S", std::localtime(&t));
  e.log.push_back({stamp, m, error});
  if (e.log.size() > 500) e.log.erase(e.log.begin());
}

// The next successful action clears an error left from before.
void clear_error(editor_state& e) {
  if (e.message_is_error) e.message.clear();
  e.message_is_error = false;
  e.toast.clear();
}

void handle_ab(editor_state& e, ab_action a);   // A/B comparison (defined below take_new_tree)
static_assert(int(editor_state::growth::growing) == ab_growth::growing && int(editor_state::growth::asking) == ab_growth::asking &&
              int(editor_state::growth::done) == ab_growth::done && int(editor_state::growth::cancelled) == ab_growth::cancelled &&
              int(editor_state::growth::failed) == ab_growth::failed);

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
  const char* source;      // the paper the struct's parameters come from, with a trailing newline, or nullptr
  bool show_advanced;
  bool hold = false;       // an apply-on-release item is active
  bool open = true;
  bool header_drawn = false;
  const char* pending_header = nullptr;   // drawn before the group's first shown parameter
  const char* last_header = nullptr;      // the header drawn last
  bool relevant = true;                   // param_relevant() for the parameter being visited
  std::vector<step_column>* steps = nullptr;   // the struct's per-step schedules, drawn as one table
  const tree_spec* keyed_spec = nullptr;       // growth phases: mark the parameters keyed at keyed_step
  int keyed_step = -1;
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
    // A group that continues the one just drawn (nested structs may both name "Leaves") gets no
    // second header.
    if (pending_header && last_header && std::strcmp(pending_header, last_header) == 0) pending_header = nullptr;
    if (pending_header) {
      open = ImGui::CollapsingHeader(pending_header, ImGuiTreeNodeFlags_DefaultOpen);
      last_header = pending_header;
      pending_header = nullptr;
    }
    if (!open || ((info.flags & param_advanced) && !show_advanced)) return;
    if constexpr (std::is_same_v<T, std::vector<float>>) {
      if (steps && !steps->empty()) {   // all schedules in one table, where the first one is declared
        if (!steps_drawn) draw_step_table(*steps, hold);
        steps_drawn = true;
        return;
      }
    }
    ImGui::PushID(info.key);
    const char* l = label(info);
    const int slider_flags = (info.flags & param_log) ? ImGuiSliderFlags_Logarithmic : 0;
    if constexpr (std::is_same_v<T, float>) {
      const char* fmt = (info.flags & param_degrees) ? "%.1f°" : (info.flags & param_log) ? "%.4g" : "%.3f";
      ImGui::SliderFloat(l, &value, info.min, info.max, fmt, slider_flags);
    } else if constexpr (std::is_same_v<T, int>) {
      ImGui::SliderInt(l, &value, int(info.min), int(info.max), "%d", slider_flags);
    } else if constexpr (std::is_same_v<T, bool>) {
      ImGui::Checkbox(l, &value);
    } else if constexpr (std::is_enum_v<T>) {
      int v = int(value);
      const int n = option_count(info);
      if (ImGui::Combo(l, &v, info.options, n)) value = T(v);
    } else if constexpr (std::is_same_v<T, glm::vec3>) {
      // A colour is a vec3 on [0,1] that is not a direction; sizes and offsets get plain drags.
      const bool colour = !(info.flags & param_direction) && info.min == 0 && info.max == 1;
      if (colour) ImGui::ColorEdit3(l, &value.x, ImGuiColorEditFlags_Float);
      else ImGui::DragFloat3(l, &value.x, std::max((info.max - info.min) * 0.001f, 0.001f), info.min, info.max);
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (info.flags & param_multiline) {
        ImGui::TextUnformatted(info.label);
        ImGui::InputTextMultiline("##text", &value, ImVec2(-1, 180));
      } else {
        ImGui::InputText(l, &value);
      }
    } else if constexpr (std::is_same_v<T, std::vector<float>>) {
      ImGui::TextUnformatted(l, std::strstr(l, "##"));
      for (size_t i = 0; i < value.size(); ++i) {
        ImGui::PushID(int(i));
        if (i) ImGui::SameLine();
        ImGui::SetNextItemWidth(52);
        ImGui::DragFloat("##v", &value[i], (info.max - info.min) * 0.002f, info.min, info.max, "%.2f");
        ImGui::PopID();
      }
      ImGui::SameLine();
      if (ImGui::SmallButton("+")) value.push_back(value.empty() ? info.min : value.back());
      ImGui::SameLine();
      if (ImGui::SmallButton("-") && !value.empty()) value.pop_back();
    } else if constexpr (std::is_same_v<T, std::vector<glm::vec3>>) {
      ImGui::TextUnformatted(l, std::strstr(l, "##"));
      for (size_t i = 0; i < value.size(); ++i) {
        ImGui::PushID(int(i));
        ImGui::DragFloat3("##v", &value[i].x, 0.01f, info.min, info.max);
        ImGui::PopID();
      }
      if (ImGui::SmallButton("+")) value.push_back(value.empty() ? glm::vec3(0) : value.back());
      ImGui::SameLine();
      if (ImGui::SmallButton("-") && !value.empty()) value.pop_back();
    }
    if (ImGui::IsItemHovered() && info.help && *info.help)
      ImGui::SetTooltip("%s\n%s%s(right-click: reset to default)", info.help, source ? "Source: " : "", source ? source : "");
    if (ImGui::IsItemClicked(ImGuiMouseButton_Right) && !(value == def)) value = def;
    if ((info.flags & param_on_release) && ImGui::IsItemActive()) hold = true;
    if (keyed_spec && keyed_at(*keyed_spec, info.key, keyed_step)) {
      ImGui::SameLine(0, 2);
      ImGui::TextColored(ImVec4(0.5f, 0.85f, 1, 1), "•");
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("Keyed at step %d (Growth phases)", keyed_step);
    }
    ImGui::PopID();
  }
};

// True when the seed cannot change the skeleton (cached per L-system source).
bool skeleton_is_deterministic(const tree_spec& spec) {
  const auto* l = std::get_if<lsystem_params>(&spec.params);
  if (!l) return false;
  if (l->mode == lsystem_mode::honda) return true;
  static std::string cached_source;
  static bool cached = false;
  if (l->source != cached_source) {
    cached_source = l->source;
    lsystem_program prog;
    cached = compile_lsystem(l->source, prog).ok() && l->source.find("rand") == std::string::npos;
    if (cached)
      for (const lsystem_rule& r : prog.rules)
        if (r.successors.size() > 1) cached = false;
  }
  return cached;
}

// The paper each generator's parameters come from, named in every tooltip.
template <class P>
const char* param_source() {
  if constexpr (std::is_same_v<P, self_organizing_params>)
    return "Palubicki et al. 2009, Self-organizing tree models for image synthesis (SIGGRAPH)\n";
  else if constexpr (std::is_same_v<P, space_colonization_params>)
    return "Runions, Lane & Prusinkiewicz 2007, Modeling trees with a space colonization algorithm\n";
  else if constexpr (std::is_same_v<P, guiding_vectors_params>)
    return "Xu & Mould 2015, Procedural tree modeling with guiding vectors\n";
  else if constexpr (std::is_same_v<P, lsystem_params>)
    return "Honda 1971; Prusinkiewicz & Lindenmayer 1990, The Algorithmic Beauty of Plants (ch. 1-2)\n";
  else if constexpr (std::is_same_v<P, wood_params>)
    return "Beam bending with permanent set (Jirasek, Prusinkiewicz & Moulia 2000); green wood from the USDA Wood Handbook 2010\n";
  else
    return nullptr;
}

// Edits are noticed by comparing documents (record_undo, post_if_changed), so drawers return nothing.
template <class P>
void draw_params(P& p, const char* section, editor_state& e, const tree_spec* keyed = nullptr) {
  static const P defaults{};
  static const std::vector<const void*> pointers = default_pointers(defaults);
  param_drawer d{pointers, section, param_source<P>(), e.show_advanced};
  std::vector<step_column> steps = collect_step_columns(p);
  d.steps = &steps;
  d.keyed_spec = keyed;
  d.keyed_step = e.step;
  visit_params(p, [&](auto& value, const param_info& info) {
    d.relevant = param_relevant(std::as_const(p), &value, info);
    d(value, info);
  });
  e.hold_post |= d.hold;
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

void open_preset(editor_state& e, const std::string& path) {
  preset loaded;
  load_result r = load_preset_file(path, loaded);
  if (!r.ok) {   // the current tree stays as it is
    set_status(e, "Cannot open " + path + ": " + r.error, true);
    return;
  }
  if (!e.before_open) e.before_open = std::make_unique<editor_state::document>(
      editor_state::document{e.doc, e.path, e.browser.baseline, e.browser.baseline_path});
  e.undo.push_back(e.doc);
  e.redo.clear();
  e.doc = loaded;
  e.undo_base = loaded;
  e.path = path;
  note_saved_preset(e.browser, e.doc, path);
  note_recent(e.recent, path);
  e.frame_new = true;
  std::string m = "Opened " + path;
  if (!r.warnings.empty()) m += " (" + std::to_string(r.warnings.size()) + " warning(s): " + r.warnings.front() + ")";
  set_status(e, m, false);
}

bool save_to(editor_state& e, const std::string& path) {
  std::error_code ec;
  fs::create_directories(fs::path(path).parent_path(), ec);
  std::string err = save_preset_file(e.doc, path);
  if (!err.empty()) {
    set_status(e, "Save failed: " + err, true);
    return false;
  }
  e.path = path;
  note_saved_preset(e.browser, e.doc, path);
  note_recent(e.recent, path);
  set_status(e, "Saved " + path);
  return true;
}

// ---------------------------------------------------------------- settings

// ~/Sylva/settings.ini: one `key value...` per line.
struct editor_settings {
  int x = 0, y = 0, width = 0, height = 0;   // width 0: never saved
  bool maximized = false;
  int64_t node_budget = 0;
  std::vector<std::string> recent;           // newest first
};

editor_settings load_settings(const std::string& home) {
  editor_settings s;
  std::string text;
  if (!read_file((fs::path(home) / "settings.ini").string(), text).empty()) return s;
  size_t a = 0;
  while (a < text.size()) {
    size_t b = text.find('\n', a);
    if (b == std::string::npos) b = text.size();
    const std::string line = text.substr(a, b - a);
    a = b + 1;
    long long n = 0;
    int m = 0;
    if (std::sscanf(line.c_str(), "window %d %d %d %d %d", &s.x, &s.y, &s.width, &s.height, &m) >= 4) s.maximized = m != 0;
    else if (std::sscanf(line.c_str(), "node_budget %lld", &n) == 1) s.node_budget = n;
    else if (line.rfind("recent ", 0) == 0 && s.recent.size() < 10) s.recent.push_back(line.substr(7));
  }
  return s;
}

void save_settings(const std::string& home, const editor_settings& s) {
  std::string text;
  char b[128];
  if (s.width > 0) {
    std::snprintf(b, sizeof b, "window %d %d %d %d %d\n", s.x, s.y, s.width, s.height, int(s.maximized));
    text += b;
  }
  if (s.node_budget > 0) text += "node_budget " + std::to_string(s.node_budget) + "\n";
  for (const std::string& r : s.recent) text += "recent " + r + "\n";
  std::error_code ec;
  fs::create_directories(home, ec);
  (void)write_file_atomic((fs::path(home) / "settings.ini").string(), text);
}

// ---------------------------------------------------------------- unsaved work (issue 14)

// The user's own folder for saves, exports, screenshots and the recovery file: $SYLVA_HOME, else ~/Sylva.
std::string user_folder() {
  if (const char* h = std::getenv("SYLVA_HOME"); h && *h) return h;
  if (const char* h = std::getenv("HOME"); h && *h) return (fs::path(h) / "Sylva").string();
  return (fs::current_path() / "Sylva").string();
}

// A shipped preset is never overwritten by Save: it goes to Save as in the user's folder instead.
bool is_installed_preset(const std::string& path) {
  if (path.empty()) return false;
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(path, ec);
  for (const fs::path& d : preset_dirs()) {
    const fs::path c = fs::weakly_canonical(d, ec);
    if (!ec && p.parent_path() == c) return true;
  }
  return false;
}

// "My tree" -> "~/Sylva/my_tree.json".
std::string default_save_path(const editor_state& e) {
  if (!e.path.empty() && !is_installed_preset(e.path)) return e.path;
  std::string stem;
  for (char c : e.doc.name) stem += std::isalnum(static_cast<unsigned char>(c)) ? char(std::tolower(static_cast<unsigned char>(c))) : '_';
  if (stem.empty()) stem = "tree";
  return (fs::path(e.home) / (stem + ".json")).string();
}

bool modified(const editor_state& e) { return has_unsaved_changes(e.browser, e.doc); }

// The slots with unsaved changes (A/B: both slots; the selected one first).
std::vector<int> unsaved_slots(const editor_state& e) { return ab_unsaved_slots(e.ab, e.doc, e.browser.baseline); }

// Slot A's recovery file, or slot B's (hidden from the file browser).
std::string recovery_path(const editor_state& e, int slot = 0) {
  return (fs::path(e.home) / (slot == 0 ? ".recovery.json" : ".recovery_b.json")).string();
}

void remove_recovery(editor_state& e, int slot) {
  std::error_code ec;
  fs::remove(recovery_path(e, slot), ec);
  fs::remove(recovery_path(e, slot) + ".source", ec);
  e.autosaved_any[slot] = false;
}
void remove_recovery(editor_state& e) {
  remove_recovery(e, 0);
  remove_recovery(e, 1);
}

// Every few seconds while modified: each slot's document to ~/Sylva/.recovery[_b].json, its own
// path beside it. Slots are A and B, not selected and other, so a recovery names the right slot.
void autosave(editor_state& e, double dt) {
  if (e.quit_confirmed) return;
  const std::vector<int> unsaved = unsaved_slots(e);
  for (int slot = 0; slot < 2; ++slot)
    if (e.autosaved_any[slot] && std::find(unsaved.begin(), unsaved.end(), slot) == unsaved.end()) remove_recovery(e, slot);
  if (unsaved.empty()) {
    e.autosave_wait = 0;
    return;
  }
  e.autosave_wait += dt;
  if (e.autosave_wait < 3.0) return;
  e.autosave_wait = 0;
  std::error_code ec;
  fs::create_directories(e.home, ec);
  for (int slot : unsaved) {
    const bool selected = !e.ab.has_b || slot == e.ab.selected;
    const preset& doc = selected ? e.doc : e.ab.other_doc.doc;
    if (e.autosaved_any[slot] && doc == e.autosaved[slot]) continue;
    if (!save_preset_file(doc, recovery_path(e, slot)).empty()) continue;   // best effort; never interrupts
    (void)write_file_atomic(recovery_path(e, slot) + ".source", selected ? e.path : e.ab.other_doc.path);
    e.autosaved[slot] = doc;
    e.autosaved_any[slot] = true;
  }
}

void select_slot(editor_state& e, int slot);   // A/B (defined below take_new_tree)
void perform_pending(editor_state& e);

// Quit with "Save": saves the next slot with unsaved changes (the selected one first). A slot
// without its own file selects it and asks where (Save as), then goes on. Returns false when a
// slot is waiting for its Save as, or a save failed (the quit stops there).
bool save_next_slot(editor_state& e) {
  const std::vector<int> unsaved = unsaved_slots(e);
  if (unsaved.empty()) return true;
  if (e.ab.has_b && unsaved.front() != e.ab.selected) select_slot(e, unsaved.front());
  if (e.path.empty() || is_installed_preset(e.path)) {
    e.continue_after_save = true;
    e.open_save_as = true;
    return false;
  }
  if (!save_to(e, e.path)) {
    e.save_all = false;
    e.pending = editor_state::then::nothing;
    return false;
  }
  return true;
}

// Carries out what waited for the unsaved-changes question.
void perform_pending(editor_state& e) {
  // Quitting with "Save" and two slots: every slot with changes is saved before the quit.
  if (e.pending == editor_state::then::quit && e.save_all) {
    while (!unsaved_slots(e).empty())
      if (!save_next_slot(e)) return;
    e.save_all = false;
  }
  const editor_state::then what = e.pending;
  e.pending = editor_state::then::nothing;
  e.continue_after_save = false;
  if (what == editor_state::then::quit) {
    e.quit_confirmed = true;
    remove_recovery(e);
    glfwSetWindowShouldClose(e.window, GLFW_TRUE);
  } else if (what == editor_state::then::open) {
    open_preset(e, e.pending_path);
  }
}

// Quit, window close, Open and the library go through here: asks first when the document is
// modified. Open replaces the selected slot only; quitting asks about both A/B slots.
void request(editor_state& e, editor_state::then what, const std::string& path = "") {
  e.pending = what;
  e.pending_path = path;
  e.save_all = false;
  if (what == editor_state::then::quit ? unsaved_slots(e).empty() : !modified(e)) return perform_pending(e);
  e.open_confirm = true;
}

// Save: to the document's own file, or Save as when it has none or it is a shipped preset.
void save_command(editor_state& e) {
  if (e.path.empty() || is_installed_preset(e.path)) e.open_save_as = true;
  else save_to(e, e.path);
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

// "sylva-20261201-114502.png"
std::string screenshot_name() {
  char b[64];
  const std::time_t t = std::time(nullptr);
  std::strftime(b, sizeof b, "sylva-%Y%m%d-%H%M%S.png", std::localtime(&t));
  return b;
}

std::string count_text(double n) {
  char b[64];
  if (n >= 1e6) std::snprintf(b, sizeof b, "%.1f million", n / 1e6);
  else if (n >= 1e4) std::snprintf(b, sizeof b, "%.0f thousand", n / 1e3);
  else std::snprintf(b, sizeof b, "%.0f", n);
  return b;
}

std::string seconds_text(double s) {
  char b[64];
  if (s >= 120) std::snprintf(b, sizeof b, "%.0f min", s / 60);
  else if (s >= 1) std::snprintf(b, sizeof b, "%.0f s", s);
  else std::snprintf(b, sizeof b, "%.1f s", s);
  return b;
}

// A cancelled or over-budget request: the document goes back to the tree on screen, so what is
// shown is what would be saved. The edit is dropped from the undo history.
void keep_shown_tree(editor_state& e, const std::string& why) {
  if (e.before_open && e.shown && e.shown->skeleton && e.shown->skeleton->size()) {
    // The opened preset's tree never arrived: back to the document on screen, name and file too.
    e.doc = e.before_open->doc;
    e.path = e.before_open->path;
    e.browser.baseline = e.before_open->baseline;
    e.browser.baseline_path = e.before_open->baseline_path;
    e.before_open.reset();
  }
  if (e.shown && e.shown->skeleton && e.shown->skeleton->size()) {
    e.doc.spec = e.shown->spec;
    e.doc.mesh = e.shown->mesh_settings;
    if (!e.undo.empty() && e.undo.back() == e.doc) e.undo.pop_back();
    e.undo_base = e.doc;
    e.posted_spec = e.doc.spec;
    e.posted_mesh = e.doc.mesh;
  }
  e.growth_state = editor_state::growth::cancelled;
  e.growth_text = why;
}

// ---------------------------------------------------------------- UI

void draw_menu(editor_state& e) {
  if (!ImGui::BeginMainMenuBar()) return;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("Open preset...", "Ctrl+O")) e.open_picker = true;
    ImGui::MenuItem("Preset library", "Ctrl+L", &e.browser.open);
    if (ImGui::MenuItem("Save", "Ctrl+S")) save_command(e);
    if (ImGui::MenuItem("Save as...")) e.open_save_as = true;
    if (ImGui::MenuItem("Export...", nullptr, e.exporter.open)) {
      e.exporter.open = !e.exporter.open;
      // Exports land in the user's folder, named after the tree, unless a place was chosen already.
      std::error_code ec;
      if (e.exporter.open) fs::create_directories(e.home, ec);
      if (e.exporter.open && fs::path(e.exporter.path).is_relative())
        e.exporter.path = (fs::path(e.home) / (fs::path(default_save_path(e)).stem().string() + fs::path(e.exporter.path).extension().string())).string();
    }
    if (ImGui::MenuItem("Export as...")) e.browse_export = true;
    if (ImGui::MenuItem("Screenshot", "F12")) e.screenshot_requested = true;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("The 3D view, without menus, to %s/screenshots/", e.home.c_str());
    if (ImGui::MenuItem("Screenshot as...")) e.browse_screenshot = true;
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) request(e, editor_state::then::quit);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    if (ImGui::MenuItem("Undo", "Ctrl+Z", false, !e.undo.empty())) apply_undo(e, e.undo, e.redo);
    if (ImGui::MenuItem("Redo", "Ctrl+Shift+Z", false, !e.redo.empty())) apply_undo(e, e.redo, e.undo);
    ImGui::Separator();
    int64_t budget = e.worker->node_budget.load();
    const int64_t lo = 1000, hi = 50000000;
    ImGui::SetNextItemWidth(160);
    if (ImGui::SliderScalar("Node budget", ImGuiDataType_S64, &budget, &lo, &hi, "%lld", ImGuiSliderFlags_Logarithmic))
      e.worker->node_budget = std::clamp(budget, lo, hi);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("A request estimated to grow more nodes than this asks before growing");
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    ImGui::MenuItem("Growth overlays", nullptr, &e.show_overlays);
    draw_overlay_menu(e.overlays, e.renderer.overlay);
    ImGui::MenuItem("Parameter panel", nullptr, &e.show_panel);
    ImGui::MenuItem("Timeline", nullptr, &e.show_timeline);
    ImGui::MenuItem("Advanced parameters", nullptr, &e.show_advanced);
    if (ImGui::MenuItem("Frame tree", "F")) e.frame_now = true;
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Help")) {
    ImGui::MenuItem("Keyboard and mouse", "F1", &e.show_shortcuts);
    ImGui::MenuItem("Messages", nullptr, &e.show_log);
    if (ImGui::MenuItem("About Sylva")) e.open_about = true;
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
}

void draw_panel(editor_state& e, float top, float bottom) {
  ImGui::SetNextWindowPos(ImVec2(0, top));
  ImGui::SetNextWindowSize(ImVec2(panel_width(), bottom - top));
  ImGui::Begin("Parameters", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoTitleBar);
  ImGui::PushItemWidth(-205 * ui_scale);
  if (const ab_action a = draw_ab_controls(e.ab); a != ab_action::none) handle_ab(e, a);
  tree_spec& spec = e.doc.spec;
  int g = int(spec.params.index());
  if (ImGui::Combo("Generator", &g, generator_labels, generator_count) && g != int(spec.params.index())) {
    spec.params = default_params(g);
    spec.keyframes.clear();   // they name the old generator's parameters
    e.frame_new = true;
  }
  int seed = int(spec.seed & 0x7fffffff);
  if (ImGui::InputInt("Seed", &seed)) spec.seed = uint64_t(std::max(seed, 0));
  ImGui::SameLine();
  // Randomize only where the seed changes something: Honda's model and L-systems without
  // stochastic productions or rand() are deterministic; then only the leaf scatter uses the seed.
  const bool random_tree = !skeleton_is_deterministic(spec);
  const bool random_leaves = e.doc.mesh.leaves_enabled;
  if (!random_tree && !random_leaves) ImGui::BeginDisabled();
  if (ImGui::Button("Randomize")) spec.seed = std::random_device{}() & 0x7fffffff;
  if (!random_tree && !random_leaves) ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled) && !random_tree)
    ImGui::SetTooltip(random_leaves ? "This generator is deterministic: a new seed only scatters the leaves differently"
                                    : "This generator is deterministic and leaves are off: the seed changes nothing");
  // Growth phases: with "from this step on", the panel shows the values in effect at the scrubbed
  // step and an edit keys the new value there (app/editor_keyframes.h).
  std::string key_error;
  if (draw_keyframe_panel(e.keys, spec, e.step, key_error)) clear_error(e);
  if (draw_prune_panel(e.prune, spec, e.shown.get(), e.step, key_error)) clear_error(e);
  if (e.keys.from_step && e.step >= 1) {
    const generator_params before = params_at_step(spec, e.step);
    generator_params shown = before;
    std::visit([&](auto& p) { draw_params(p, generator_labels[spec.params.index()], e, &spec); }, shown);
    if (!(shown == before)) key_error = key_edits(spec, before, shown, e.step);
  } else {
    std::visit([&](auto& p) { draw_params(p, generator_labels[spec.params.index()], e, &spec); }, spec.params);
  }
  if (!key_error.empty()) set_status(e, key_error, true);
  draw_generator_panel(e.generator_panels, spec, e.shown.get());
  draw_params(spec.wood, "Wood", e);
  draw_params(e.doc.mesh, "Mesh", e);
  // Time-of-day presets: a starting point for the lighting sliders below.
  render_params& rp = e.doc.render;
  ImGui::Separator();
  ImGui::TextUnformatted("Time of day");
  ImGui::SameLine();
  if (ImGui::SmallButton("Noon")) {
    rp.sun_elevation = 70, rp.sun_azimuth = 25, rp.sun_color = {1.0f, 0.97f, 0.92f}, rp.sun_intensity = 2.4f;
    rp.sky_zenith = {0.22f, 0.42f, 0.85f}, rp.sky_horizon = {0.72f, 0.83f, 0.95f};
    rp.fog_density = 0.005f, rp.haze = 0.0003f;   // a clear midday: little air to light up
  }
  ImGui::SameLine();
  if (ImGui::SmallButton("Golden hour")) {
    rp.sun_elevation = 10, rp.sun_azimuth = std::remainder(e.camera.yaw + 60.0f, 360.0f), rp.sun_color = {1.0f, 0.72f, 0.42f}, rp.sun_intensity = 2.0f;
    rp.sky_zenith = {0.28f, 0.38f, 0.68f}, rp.sky_horizon = {0.95f, 0.76f, 0.55f};
    rp.fog_density = 0.018f, rp.haze = 0.0005f;
  }
  ImGui::SameLine();
  if (ImGui::SmallButton("Backlit rays")) {   // the sun straight behind the tree as seen now
    place_sun_behind(rp, e.camera.yaw);
    rp.sun_color = {1.0f, 0.88f, 0.7f}, rp.sun_intensity = 2.2f;
    if (rp.shafts == light_shafts::off) rp.shafts = light_shafts::volumetric;
    rp.fog_density = std::max(rp.fog_density, 0.025f);   // enough air for the shafts to show
  }
  draw_params(e.doc.render, "Render", e);
  ImGui::PopItemWidth();
  ImGui::End();
}

void draw_timeline(editor_state& e, float x, float y, float w) {
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowSize(ImVec2(w, timeline_height()));
  ImGui::Begin("Timeline", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoTitleBar |
                   ImGuiWindowFlags_NoScrollbar);
  const int steps = e.shown && e.shown->skeleton ? e.shown->skeleton->steps : 0;
  if (ImGui::Button("|<")) e.step = 0;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Jump to the start (Home)");
  ImGui::SameLine();
  if (ImGui::Button("<")) e.step = std::max(0, e.step - 1);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("One step back (Left)");
  ImGui::SameLine();
  if (ImGui::Button(e.playing ? "Pause" : "Play")) {
    e.playing = !e.playing;
    if (e.playing && e.step >= steps) e.step = 0;
  }
  ImGui::SameLine();
  if (ImGui::Button(">")) e.step = std::min(steps, e.step + 1);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("One step forward (Right)");
  ImGui::SameLine();
  if (ImGui::Button(">|")) e.step = steps;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Jump to the end (End)");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(110);
  ImGui::SliderFloat("##speed", &e.speed, 0.25f, 30, "%.2g steps/s", ImGuiSliderFlags_Logarithmic);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1);
  ImGui::SliderInt("##step", &e.step, 0, std::max(steps, 0), "step %d");
  if (timeline_markers) {   // growth phases: a marker per keyed step under the slider
    const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    const float grab = ImGui::GetStyle().GrabMinSize * 0.5f + ImGui::GetStyle().FramePadding.x;
    std::string key_error;
    draw_keyframe_markers(e.keys, e.doc.spec, std::max(steps, last_keyframe_step(e.doc.spec)), lo.x + grab,
                          hi.x - grab, hi.y + 2, e.step, key_error);
    if (!key_error.empty()) set_status(e, key_error, true);
  }
  ImGui::End();
}

// The overlays' legend in the viewport's bottom left corner: each visible layer, its colour and units.
void draw_overlay_legend(editor_state& e, float left, float bottom) {
  const overlay_gpu& g = e.renderer.overlay;
  const overlay_view& v = e.overlays;
  const uint32_t shown = v.kinds & g.present;
  if (!e.show_overlays || !shown) return;
  ImGui::SetNextWindowPos(ImVec2(left + 10, bottom - 10), 0, ImVec2(0, 1));
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("##legend", nullptr,
               ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_AlwaysAutoResize |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoInputs);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const float h = ImGui::GetTextLineHeight();
  auto swatch = [&](const glm::vec3& c) {
    const ImVec2 p = ImGui::GetCursorScreenPos();
    dl->AddRectFilled(ImVec2(p.x, p.y + 2), ImVec2(p.x + h - 4, p.y + h - 2), ImGui::ColorConvertFloat4ToU32(ImVec4(c.x, c.y, c.z, 1)));
    ImGui::Dummy(ImVec2(h - 2, h));
    ImGui::SameLine();
  };
  auto ramp = [&](const char* lo, const char* hi) {
    ImGui::TextUnformatted(lo);
    ImGui::SameLine();
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float w = 120 * ui_scale;
    for (int i = 0; i < 24; ++i) {
      const glm::vec3 c = overlay_ramp((float(i) + 0.5f) / 24);
      dl->AddRectFilled(ImVec2(p.x + w * float(i) / 24, p.y + 2), ImVec2(p.x + w * float(i + 1) / 24, p.y + h - 2),
                        ImGui::ColorConvertFloat4ToU32(ImVec4(c.x, c.y, c.z, 1)));
    }
    ImGui::Dummy(ImVec2(w, h));
    ImGui::SameLine();
    ImGui::TextUnformatted(hi);
  };
  char hi[64];
  for (int k = 0; k < overlay_kind_count; ++k) {
    if (!((shown >> k) & 1u)) continue;
    switch (k) {
      case overlay_shadow_grid:
        ImGui::Text("Shadow grid: shade s of each voxel%s", v.shadow_slice ? "" : " (whole grid)");
        if (v.shadow_slice) ImGui::Text("  slice at %.2f m of %.2f to %.2f m", v.slice_height, g.shadow_min_y, g.shadow_max_y);
        std::snprintf(hi, sizeof hi, "%.3g (densest)", g.max_shade);
        ramp("  0", hi);
        break;
      case overlay_flow:
        ImGui::TextUnformatted("Resource flow per internode (point area ∝ flow)");
        std::snprintf(hi, sizeof hi, "%.3g", g.max_flow);
        ramp("  0", hi);
        break;
      case overlay_fates:
        swatch(overlay_fate_colour[0]); ImGui::TextUnformatted("bud grew");
        swatch(overlay_fate_colour[1]); ImGui::TextUnformatted("bud dormant");
        swatch(overlay_fate_colour[2]); ImGui::TextUnformatted("branch shed");
        break;
      case overlay_markers: swatch(overlay_marker_colour); ImGui::TextUnformatted("attraction points / markers alive"); break;
      case overlay_killed: swatch(overlay_killed_colour); ImGui::TextUnformatted("points killed in this step"); break;
      case overlay_endpoints:
        swatch(overlay_source_colour); ImGui::TextUnformatted("sources of the step");
        swatch(overlay_endpoint_colour); ImGui::TextUnformatted("endpoints of the step");
        break;
      default: ImGui::TextUnformatted(overlay_kind_labels[k]); break;
    }
  }
  ImGui::End();
}

// The last error, whole, in the viewport's top right corner until dismissed or a success.
void draw_toast(editor_state& e, float left, float top, float right) {
  if (e.toast.empty()) return;
  const float w = std::min(520.0f * ui_scale, right - left - 20);
  ImGui::SetNextWindowPos(ImVec2(right - w - 10, top + 10));
  ImGui::SetNextWindowSize(ImVec2(w, 0));
  ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.35f, 0.08f, 0.08f, 1));
  ImGui::Begin("##toast", nullptr,
               ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                   ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing);
  ImGui::PushTextWrapPos(w - 70 * ui_scale);
  ImGui::TextUnformatted(e.toast.c_str());
  ImGui::PopTextWrapPos();
  ImGui::SameLine(w - 60 * ui_scale);
  if (ImGui::SmallButton("Dismiss")) e.toast.clear();
  if (ImGui::SmallButton("Messages...")) e.show_log = true;
  ImGui::End();
  ImGui::PopStyleColor();
}

void draw_shortcuts(editor_state& e) {
  if (!e.show_shortcuts) return;
  ImGui::SetNextWindowSize(ImVec2(560 * ui_scale, 0), ImGuiCond_Appearing);
  if (ImGui::Begin("Keyboard and mouse", &e.show_shortcuts, ImGuiWindowFlags_AlwaysAutoResize)) {
    static const char* rows[][2] = {
        {"Left-drag", "orbit"}, {"Right- or middle-drag", "pan"}, {"Wheel", "zoom"}, {"F", "frame the tree"},
        {"Ctrl+Z", "undo"}, {"Ctrl+Shift+Z, Ctrl+Y", "redo"}, {"Ctrl+S", "save (Save as for shipped presets)"},
        {"Ctrl+O", "open a preset"}, {"Ctrl+L", "preset library"}, {"Ctrl+Q", "quit (asks about unsaved changes)"},
        {"Space", "play / pause the growth"}, {"Home, End", "first / last step"}, {"Left, Right", "one step back / forward"},
        {"Esc", "cancel a long regrow; close a dialog"}, {"F12", "screenshot of the 3D view"}, {"F1", "this list"},
        {"Right-click a slider", "reset it to its default"}};
    if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg)) {
      for (const auto& r : rows) {
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(r[0]);
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(r[1]);
      }
      ImGui::EndTable();
    }
    ImGui::Separator();
    ImGui::TextWrapped("README.md explains more: \"The editor\" (panels, timeline, presets), \"The four "
                       "generators\" (the papers behind the parameters), \"Command line\" and \"Rendering at scale\".");
  }
  ImGui::End();
}

void draw_message_log(editor_state& e) {
  if (!e.show_log) return;
  ImGui::SetNextWindowSize(ImVec2(640 * ui_scale, 300 * ui_scale), ImGuiCond_FirstUseEver);
  if (ImGui::Begin("Messages", &e.show_log)) {
    if (ImGui::SmallButton("Clear")) e.log.clear();
    ImGui::SameLine();
    if (ImGui::SmallButton("Copy all")) {
      std::string all;
      for (const auto& l : e.log) all += l.time + "  " + l.text + "\n";
      ImGui::SetClipboardText(all.c_str());
    }
    ImGui::Separator();
    ImGui::BeginChild("lines");
    for (const auto& l : e.log) {
      ImGui::TextDisabled("%s", l.time.c_str());
      ImGui::SameLine();
      ImGui::PushTextWrapPos(0);
      if (l.error) ImGui::TextColored(ImVec4(1, 0.5f, 0.45f, 1), "%s", l.text.c_str());
      else ImGui::TextUnformatted(l.text.c_str());
      ImGui::PopTextWrapPos();
    }
    if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY()) ImGui::SetScrollHereY(1.0f);
    ImGui::EndChild();
  }
  ImGui::End();
}

// Nodes alive at the scrubbed step, like the leaf and triangle counts (O(n), once per step change).
size_t nodes_at_step(editor_state& e) {
  const tree_skeleton* t = e.shown ? e.shown->skeleton.get() : nullptr;
  if (!t) return 0;
  if (t != e.counted_tree || e.step != e.counted_step) {
    size_t n = 0;
    for (size_t i = 0; i < t->size(); ++i) n += t->alive(i, e.step);
    e.counted_tree = t, e.counted_step = e.step, e.counted_nodes = n;
  }
  return e.counted_nodes;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// The growth in progress has run long enough to show a progress bar with Cancel (~200 ms).
bool long_growth(const editor_state& e) {
  return e.growth_state == editor_state::growth::growing && seconds_since(e.posted_at) > 0.2;
}

void cancel_request(editor_state& e) {
  e.stale_before = cancel_growth(*e.worker);
  keep_shown_tree(e, "the previous tree stays");
}

void draw_status(editor_state& e, float y, float w) {
  ImGui::SetNextWindowPos(ImVec2(0, y));
  ImGui::SetNextWindowSize(ImVec2(w, status_height()));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8, 4));
  ImGui::Begin("Status", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoTitleBar |
                   ImGuiWindowFlags_NoScrollbar);
  const grow_result* r = e.shown.get();
  // One state: growing (with progress and Cancel once it takes a while), done, cancelled or failed.
  using g = editor_state::growth;
  switch (e.growth_state) {
    case g::growing:
      if (long_growth(e)) {
        ImGui::TextUnformatted("growing");
        ImGui::SameLine();
        ImGui::ProgressBar(e.worker->progress.load(), ImVec2(160, 0));
        ImGui::SameLine();
        if (ImGui::SmallButton("Cancel (Esc)")) cancel_request(e);
      } else {
        ImGui::TextUnformatted("growing...");
      }
      break;
    case g::asking: ImGui::TextColored(ImVec4(1, 0.8f, 0.4f, 1), "%s", e.growth_text.c_str()); break;
    case g::done: ImGui::TextColored(ImVec4(0.6f, 0.9f, 0.6f, 1), "done: %s", e.growth_text.c_str()); break;
    case g::cancelled: ImGui::TextColored(ImVec4(1, 0.8f, 0.4f, 1), "cancelled: %s", e.growth_text.c_str()); break;
    case g::failed: ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "failed: %s", e.growth_text.c_str()); break;
    case g::idle: ImGui::TextDisabled("no tree yet"); break;
  }
  ImGui::SameLine();
  if (ab_showing(e.ab)) {   // A/B: both slots' counts and timings in place of the one tree's
    ab_counts mine = ab_counts_of(e.shown.get()), other = ab_counts_of(e.ab.other.shown.get());
    // A slot whose last growth failed or waits shows it, with the counts of the tree it still shows.
    mine.problem = ab_slot_problem(int(e.growth_state), e.growth_text);
    other.problem = ab_slot_problem(e.ab.other.growth, e.ab.other.growth_text);
    ImGui::Text("   %s   frame %.1f ms", (e.ab.selected == 0 ? ab_compare_text(mine, other) : ab_compare_text(other, mine)).c_str(),
                e.frame_ms);
  } else {
    ImGui::Text("   nodes %zu   leaves %zu   triangles %zu   grow %.1f ms   mesh %.1f ms   frame %.1f ms", nodes_at_step(e),
                e.renderer.leaves_drawn, e.renderer.triangles_drawn, r ? r->grow_ms : 0.0, r ? r->mesh_ms : 0.0, e.frame_ms);
    // The hidden slot's failure still shows (A/B view off).
    if (const std::string p = e.ab.has_b ? ab_slot_problem(e.ab.other.growth, e.ab.other.growth_text) : ""; !p.empty()) {
      ImGui::SameLine();
      ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "   %s: %s", e.ab.selected == 0 ? "B" : "A", p.c_str());
    }
  }
  if (const std::string lod = editor_lod_status(e.lod); !lod.empty()) {
    ImGui::SameLine();
    ImGui::Text("   %s", lod.c_str());
  }
  if (!e.message.empty()) {
    ImGui::SameLine();
    ImGui::TextColored(e.message_is_error ? ImVec4(1, 0.45f, 0.4f, 1) : ImVec4(0.75f, 0.85f, 0.75f, 1), "   %s", e.message.c_str());
  }
  if (r && !r->mesh.message.empty()) {   // the leaf cap: growth went on, the foliage stopped
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(1, 0.8f, 0.4f, 1), "   %s", r->mesh.message.c_str());
  }
  ImGui::End();
  ImGui::PopStyleVar();
}

// A dialog button that the scripted test can press too (`answer LABEL`).
bool scripted_button(editor_state& e, const char* label) {
  const bool clicked = ImGui::Button(label);
  if (!e.script_answer.empty() && e.script_answer == label) {
    e.script_answer.clear();
    return true;
  }
  return clicked;
}

void draw_dialogs(editor_state& e) {
  // Open, Save as and Screenshot as share the file browser; places: the user's folder, the
  // shipped presets (read-only for Save) and home.
  auto places = [&](file_browser& b) {
    b.places.clear();
    b.places.push_back({"My trees", e.home});
    for (const fs::path& d : preset_dirs())
      if (std::error_code ec; fs::is_directory(d, ec)) {
        b.places.push_back({"Shipped presets", fs::weakly_canonical(d, ec).string()});
        break;
      }
    if (const char* h = std::getenv("HOME")) b.places.push_back({"Home", h});
    b.forbidden_folders.clear();
    for (const fs::path& d : preset_dirs()) b.forbidden_folders.push_back(d.string());
    b.forbidden_folder_note = "The shipped presets are read-only: save your own copy in " + e.home;
  };
  if (e.open_picker) {
    std::string folder = !e.path.empty() && !is_installed_preset(e.path) ? fs::path(e.path).parent_path().string() : e.home;
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) {   // nothing of the user's yet: the shipped presets
      folder.clear();
      for (const fs::path& d : preset_dirs())
        if (fs::is_directory(d, ec)) { folder = d.string(); break; }
      if (folder.empty()) folder = e.home;
    }
    places(e.files);
    open_file_browser(e.files, "Open preset", false, folder, "", {".json"});
    e.browse = editor_state::browsing::open;
    e.open_picker = false;
  }
  if (e.open_save_as) {
    const fs::path p = default_save_path(e);
    places(e.files);
    open_file_browser(e.files, "Save preset as", true, p.parent_path().string(), p.filename().string(), {".json"});
    e.browse = editor_state::browsing::save_as;
    e.open_save_as = false;
  }
  if (e.browse_screenshot) {
    places(e.files);
    open_file_browser(e.files, "Save screenshot as", true, (fs::path(e.home) / "screenshots").string(),
                      screenshot_name(), {".png"});
    e.browse = editor_state::browsing::screenshot;
    e.browse_screenshot = false;
  }
  if (e.browse_export) {   // the export dialog then opens on the chosen path
    places(e.files);
    const fs::path current = fs::path(e.exporter.path).is_relative() ? fs::path(e.home) / e.exporter.path : fs::path(e.exporter.path);
    const std::string stem = fs::path(default_save_path(e)).stem().string();
    open_file_browser(e.files, "Export as", true, current.parent_path().string(),
                      stem + (current.has_extension() ? current.extension().string() : ".glb"),
                      {std::begin(export_formats), std::end(export_formats)});
    e.browse = editor_state::browsing::export_to;
    e.browse_export = false;
  }
  if (!e.files.title.empty()) e.prompts_shown.push_back(e.files.title);
  const bool was_open = !e.files.title.empty();
  if (const std::string chosen = draw_file_browser(e.files, e.recent, e.script_answer); !chosen.empty()) {
    if (e.browse == editor_state::browsing::open) {
      request(e, editor_state::then::open, chosen);
    } else if (e.browse == editor_state::browsing::save_as) {
      const bool saved = save_to(e, chosen);
      if (saved && e.continue_after_save) perform_pending(e);
      e.continue_after_save = false;
    } else if (e.browse == editor_state::browsing::export_to) {
      e.exporter.path = chosen;
      e.exporter.open = true;
    } else {
      e.screenshot_to = chosen;
    }
  } else if (was_open && e.files.title.empty()) {   // cancelled
    if (e.browse == editor_state::browsing::save_as) {
      e.continue_after_save = false;
      e.save_all = false;
      e.pending = editor_state::then::nothing;
    }
  }
  if (e.open_confirm) {
    ImGui::OpenPopup("Unsaved changes");
    e.open_confirm = false;
  }
  if (e.open_about) {
    ImGui::OpenPopup("About Sylva");
    e.open_about = false;
  }
  if (ImGui::BeginPopupModal("Unsaved changes", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    e.prompts_shown.push_back("Unsaved changes");
    const bool quitting = e.pending == editor_state::then::quit;
    // Quitting with A/B asks about both slots: the list names each slot with changes.
    const std::vector<int> unsaved = quitting ? unsaved_slots(e) : std::vector<int>{e.ab.has_b ? e.ab.selected : 0};
    if (unsaved.size() == 1) {
      ImGui::Text("%s has changes that are not saved.", ab_unsaved_line(e.ab, unsaved[0], e.doc, e.path).c_str());
    } else {
      ImGui::TextUnformatted("These have changes that are not saved:");
      for (int slot : unsaved) ImGui::BulletText("%s", ab_unsaved_line(e.ab, slot, e.doc, e.path).c_str());
    }
    ImGui::TextUnformatted(quitting ? (unsaved.size() > 1 ? "Save them all before quitting? (A slot without a file asks where.)"
                                                          : "Save them before quitting?")
                                    : "Save them before opening another preset?");
    ImGui::Spacing();
    if (scripted_button(e, unsaved.size() > 1 ? "Save all" : "Save")) {
      ImGui::CloseCurrentPopup();
      if (quitting) {   // every slot with changes, in turn (perform_pending)
        e.save_all = true;
        perform_pending(e);
      } else if (e.path.empty() || is_installed_preset(e.path)) {
        e.continue_after_save = true;
        e.open_save_as = true;
      } else if (save_to(e, e.path)) {
        perform_pending(e);
      }
    }
    ImGui::SameLine();
    if (scripted_button(e, "Discard")) {
      ImGui::CloseCurrentPopup();
      perform_pending(e);
    }
    ImGui::SameLine();
    if (scripted_button(e, "Cancel") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) {
      e.pending = editor_state::then::nothing;
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
  if (e.open_budget_prompt) {
    ImGui::OpenPopup("Large tree");
    e.open_budget_prompt = false;
  }
  if (ImGui::BeginPopupModal("Large tree", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    e.prompts_shown.push_back("Large tree");
    const grow_result* b = e.budget_answer.get();
    // The question belongs to the slot that asked: switching A/B drops it (the slot asks again
    // when it is selected again).
    if (!b) ImGui::CloseCurrentPopup();
    if (b) {
      ImGui::Text("This will grow about %s nodes, ~%s, ~%.1f GB.", count_text(b->estimated_nodes).c_str(),
                  seconds_text(b->estimated_seconds).c_str(), b->estimated_bytes / 1e9);
      if (!b->estimate_note.empty()) ImGui::TextDisabled("Keyframes and cuts after the trial's reach are %s.", b->estimate_note.c_str());
      ImGui::Text("The node budget is %s (Edit > Preferences).", count_text(double(e.worker->node_budget.load())).c_str());
      ImGui::TextDisabled("The tree on screen stays until you choose.");
    }
    if (scripted_button(e, "Grow anyway") && b) {
      e.approve_next = true;
      e.posted_once = false;   // post again, approved
      e.budget_answer.reset();
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (scripted_button(e, "Keep the current tree") || ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) {
      keep_shown_tree(e, "over budget: the previous tree stays");
      e.budget_answer.reset();
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
  if (e.open_recovery) {
    ImGui::OpenPopup("Restore unsaved work?");
    e.open_recovery = false;
  }
  if (ImGui::BeginPopupModal("Restore unsaved work?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    e.prompts_shown.push_back("Restore unsaved work?");
    if (e.recovered_a)
      ImGui::Text("Sylva closed with unsaved changes to \"%s\"%s%s.", e.recovered.name.c_str(),
                  e.recovered_path.empty() ? "" : " from ", e.recovered_path.c_str());
    if (e.recovered_b)
      ImGui::Text("%s unsaved changes to slot B \"%s\"%s%s (restored as slot B).", e.recovered_a ? "And" : "Sylva closed with",
                  e.recovered_b_doc.name.c_str(), e.recovered_b_path.empty() ? "" : " from ", e.recovered_b_path.c_str());
    ImGui::TextDisabled("Autosaved in %s", recovery_path(e, e.recovered_a ? 0 : 1).c_str());
    if (scripted_button(e, "Restore")) {
      if (e.recovered_a) {
        e.undo.push_back(e.doc);
        e.doc = e.recovered;
        e.undo_base = e.doc;
        e.path = e.recovered_path;
        e.frame_new = true;
      }
      e.restore_b_pending = e.recovered_b;   // once slot A's tree is shown (restore_slot_b)
      set_status(e, "Restored unsaved work; save it to keep it");
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (scripted_button(e, "Discard")) {
      remove_recovery(e);
      ImGui::CloseCurrentPopup();
    }
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

void handle_keys(editor_state& e) {
  ImGuiIO& io = ImGui::GetIO();
  if (long_growth(e) && ImGui::IsKeyPressed(GLFW_KEY_ESCAPE) && !ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId)) cancel_request(e);
  if (io.WantTextInput) return;
  const bool ctrl = io.KeyCtrl, shift = io.KeyShift;
  if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_Z)) {
    if (shift) apply_undo(e, e.redo, e.undo);
    else apply_undo(e, e.undo, e.redo);
  }
  if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_Y)) apply_undo(e, e.redo, e.undo);
  if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_S)) save_command(e);
  if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_O)) e.open_picker = true;
  if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_L)) e.browser.open = !e.browser.open;
  if (ctrl && ImGui::IsKeyPressed(GLFW_KEY_Q)) request(e, editor_state::then::quit);
  if (!ctrl && ImGui::IsKeyPressed(GLFW_KEY_F)) e.frame_now = true;
  if (ImGui::IsKeyPressed(GLFW_KEY_F12)) e.screenshot_requested = true;
  if (ImGui::IsKeyPressed(GLFW_KEY_F1)) e.show_shortcuts = !e.show_shortcuts;
  if (!ctrl && ImGui::IsKeyPressed(GLFW_KEY_SPACE)) e.playing = !e.playing;
  const int steps = e.shown && e.shown->skeleton ? e.shown->skeleton->steps : 0;
  if (ImGui::IsKeyPressed(GLFW_KEY_HOME)) e.step = 0;
  if (ImGui::IsKeyPressed(GLFW_KEY_END)) e.step = steps;
  if (ImGui::IsKeyPressed(GLFW_KEY_LEFT)) e.step = std::max(0, e.step - 1);
  if (ImGui::IsKeyPressed(GLFW_KEY_RIGHT)) e.step = std::min(steps, e.step + 1);
}

void handle_mouse(editor_state& e, const view_rect& view) {
  const int viewport_height = int(view.h);
  ImGuiIO& io = ImGui::GetIO();
  if (io.WantCaptureMouse) return;
  // A click that did not drag picks the branch under the mouse (Pruning).
  if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) && io.MouseDragMaxDistanceSqr[0] < 9 && e.shown && e.shown->skeleton)
    pick_in_view(e.prune, *e.shown->skeleton, e.step, e.camera, view, io.MousePos.x, io.MousePos.y);
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
    if (fs::exists(candidates[i]) && io.Fonts->AddFontFromFileTTF(candidates[i], 16.0f * ui_scale, nullptr, ranges)) return;
  std::fprintf(stderr, "sylva: DejaVu Sans not found (install fonts-dejavu-core); Greek symbols will not show\n");
  io.Fonts->AddFontDefault();
}

// The style and the font at a content scale (fonts and sizes follow the monitor, issue 14).
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

// Posts the document when its spec or mesh settings changed; render settings only touch uniforms.
void post_if_changed(editor_state& e) {
  if (e.hold_post) return;
  if (e.posted_once && e.doc.spec == e.posted_spec && e.doc.mesh == e.posted_mesh) return;
  // A new generator (switched, opened or undone) is a new tree: frame it. Edits keep the camera.
  if (e.posted_once && e.doc.spec.params.index() != e.posted_spec.params.index()) e.frame_new = true;
  e.posted_spec = e.doc.spec;
  e.posted_mesh = e.doc.mesh;
  e.posted_once = true;
  e.posted_generation = post_request(*e.worker, e.posted_spec, e.posted_mesh, e.approve_next);
  e.approve_next = false;
  e.posted_at = std::chrono::steady_clock::now();
  e.growth_state = editor_state::growth::growing;
  if (e.frame_new) e.frame_generation = e.posted_generation;
  e.frame_new = false;
}

// Keeps the pitch off the poles, then fits the box from the current direction (never top-down).
void frame_view(orbit_camera& c, const glm::vec3& lo, const glm::vec3& hi, float aspect) {
  if (c.pitch > 50 || c.pitch < -30) c.pitch = 10;
  frame_camera(c, lo, hi, aspect);
}

// Shows a newer worker result: upload in the same frame it is seen (DESIGN §5).
void take_new_tree(editor_state& e) {
  std::shared_ptr<const grow_result> r = take_result(*e.worker, e.seen_generation);
  if (!r) return;
  e.seen_generation = r->generation;
  if (int32_t(r->generation - e.stale_before) < 0) return;   // cancelled before it arrived
  const bool newest = r->generation == e.posted_generation;
  if (r->over_budget) {
    if (!newest) return;
    e.budget_answer = r;
    e.open_budget_prompt = true;
    e.growth_state = editor_state::growth::asking;
    e.growth_text = "over the node budget: grow it anyway?";
    return;
  }
  if (newest) {
    e.growth_state = r->report.error ? editor_state::growth::failed : editor_state::growth::done;
    e.growth_text = r->report.error ? r->report.message : r->report.stop_reason;
    if (!r->report.error && !r->report.message.empty()) e.growth_text += " (" + r->report.message + ")";
    if (r->resumed_at > 0) e.growth_text += ", resumed at step " + std::to_string(r->resumed_at);
  }
  if (e.shown && keeps_last_tree(*r)) return set_status(e, r->report.message, true);
  if (newest) e.before_open.reset();   // the opened preset's own tree (or a later edit's) is shown
  const int old_steps = e.shown && e.shown->skeleton ? e.shown->skeleton->steps : -1;
  const bool at_end = !e.shown || e.step >= old_steps;
  e.shown = r;
  upload_tree(e.renderer, r->mesh);
  editor_lod_new_tree(e.lod);
  upload_wind(e.renderer, *r->skeleton);
  set_overlays(e.renderer, r->overlays);
  fit_shadow_slice(e.overlays, e.renderer.overlay);
  if (int(r->spec.params.index()) != e.overlay_generator) {   // a new generator: its own first layer
    e.overlay_generator = int(r->spec.params.index());
    overlay_view& v = e.overlays;
    if (!v.combine) v.kinds = 1u << overlay_default_kind(e.overlay_generator, e.renderer.overlay.present);
  }
  const int steps = r->skeleton->steps;
  e.step = at_end ? steps : std::min(e.step, steps);
  set_tree_step(e.renderer, *r->skeleton, r->mesh_settings.min_radius, e.step);
  if (e.frame_generation != 0 && int32_t(r->generation - e.frame_generation) >= 0) {
    frame_view(e.camera, e.renderer.bounds_min, e.renderer.bounds_max, e.view_aspect);
    e.frame_generation = 0;
  }
  if (newest && !r->report.error && int32_t(r->generation - e.error_after) > 0) clear_error(e);
  else if (newest && r->report.error) set_status(e, r->report.message, true);
}

// ---------------------------------------------------------------- A/B comparison (app/editor_ab.h)

ab_doc take_doc(editor_state& e) {
  ab_doc d;
  d.doc = std::move(e.doc);
  d.undo_base = std::move(e.undo_base);
  d.undo = std::move(e.undo);
  d.redo = std::move(e.redo);
  d.path = std::move(e.path);
  d.baseline = e.browser.baseline;
  d.baseline_path = e.browser.baseline_path;
  return d;
}

void put_doc(editor_state& e, ab_doc&& d) {
  e.doc = std::move(d.doc);
  e.undo_base = std::move(d.undo_base);
  e.undo = std::move(d.undo);
  e.redo = std::move(d.redo);
  e.path = std::move(d.path);
  e.browser.baseline = std::move(d.baseline);
  e.browser.baseline_path = std::move(d.baseline_path);
}

// Swaps the selected slot's growth and drawing state with the stored slot's.
void swap_views(editor_state& e, ab_view& v) {
  // A slot waiting on the over-budget question asks again when it is selected again.
  if (e.growth_state == editor_state::growth::asking) e.posted_once = false;
  e.budget_answer.reset();
  e.open_budget_prompt = false;
  e.before_open.reset();
  std::swap(e.worker, v.worker);
  std::swap(e.renderer, v.renderer);
  std::swap(e.lod, v.lod);
  std::swap(e.shown, v.shown);
  std::swap(e.posted_spec, v.posted_spec);
  std::swap(e.posted_mesh, v.posted_mesh);
  std::swap(e.posted_once, v.posted_once);
  std::swap(e.seen_generation, v.seen_generation);
  std::swap(e.posted_generation, v.posted_generation);
  std::swap(e.stale_before, v.stale_before);
  std::swap(e.error_after, v.error_after);
  std::swap(e.frame_generation, v.frame_generation);
  std::swap(e.growth_text, v.growth_text);
  std::swap(e.posted_at, v.posted_at);
  std::swap(e.overlay_generator, v.overlay_generator);
  const int g = int(e.growth_state);
  e.growth_state = editor_state::growth(v.growth);
  v.growth = g;
  e.counted_tree = nullptr;
  e.prune.selected = -1;   // a pick or a marker drag belongs to the other slot's tree
  e.prune.picked_in = nullptr;
  e.keys.drag_from = e.keys.drag_to = e.keys.popup_step = -1;
}

void select_slot(editor_state& e, int slot) {
  ab_doc cur = take_doc(e);
  const bool changed = ab_select_doc(e.ab, slot, cur);
  put_doc(e, std::move(cur));
  if (!changed) return;
  swap_views(e, e.ab.other);
  set_status(e, std::string("Editing slot ") + (slot == 0 ? "A" : "B") + ": the panel, undo, Save and Export act on it");
}

void handle_ab(editor_state& e, ab_action a) {
  switch (a) {
    case ab_action::none: return;
    case ab_action::duplicate: {
      if (!e.shown || !e.shown->skeleton) return set_status(e, "Duplicate to B: wait for the tree to grow first", true);
      if (e.ab.has_b && e.ab.selected != 0) return set_status(e, "Duplicate to B: select slot A first", true);
      ab_doc cur = take_doc(e);
      ab_duplicate_doc(e.ab, cur);
      put_doc(e, std::move(cur));
      if (std::string err = ab_start_view(e.ab.other, e.shown, e.step); !err.empty()) {
        ab_doc back = take_doc(e);
        ab_drop_doc(e.ab, back);
        put_doc(e, std::move(back));
        ab_stop_view(e.ab.other);
        return set_status(e, "Duplicate to B failed: " + err, true);
      }
      e.ab.other.worker->node_budget = e.worker->node_budget.load();
      e.ab.other.growth = int(editor_state::growth::done);
      e.ab.other.growth_text = e.growth_text;
      if (e.ab.mode == ab_mode::off) e.ab.mode = ab_mode::side_by_side;
      select_slot(e, 1);
      return set_status(e, "Duplicated to slot B, now edited; the generator combo, Save and Export act on B");
    }
    case ab_action::select_a: return select_slot(e, 0);
    case ab_action::select_b: return select_slot(e, 1);
    case ab_action::drop: {
      select_slot(e, 0);
      ab_doc cur = take_doc(e);
      ab_drop_doc(e.ab, cur);
      put_doc(e, std::move(cur));
      ab_stop_view(e.ab.other);
      return set_status(e, "Slot B dropped");
    }
  }
}

// A recovered slot B comes back as B once slot A's tree is shown (B starts as A's duplicate).
void restore_slot_b(editor_state& e) {
  if (!e.restore_b_pending || !e.shown || !e.shown->skeleton || e.growth_state == editor_state::growth::growing) return;
  e.restore_b_pending = false;
  if (e.ab.has_b && e.ab.selected != 0) select_slot(e, 0);
  handle_ab(e, ab_action::duplicate);   // selects B
  if (!e.ab.has_b || e.ab.selected != 1) return;
  e.doc = e.recovered_b_doc;
  e.undo_base = e.doc;
  e.path = e.recovered_b_path;
  // B stays selected so its restored document is grown (post_if_changed); Edit A switches back.
  set_status(e, "Restored unsaved work in slot B (and A); save them to keep them");
}

std::string slot_label(const preset& p) {
  const size_t g = p.spec.params.index();
  return p.name + " - " + (g < size_t(generator_count) ? generator_labels[g] : "?");
}

// ---------------------------------------------------------------- scripted driving (tests)

// SYLVA_SCRIPT=FILE drives the real window from a script, one command per line, for the editor's
// end-to-end test (tests/editor_test.cpp). Commands that wait give up after a timeout and fail.
//   wait_tree                  until no growth is in progress and a tree is shown
//   set KEY=VALUE              an edit, as the panel would make it (set_preset_param)
//   key [ctrl+][shift+]NAME    a press and release queued between two frames (NAME: a-z, escape, f12, ...)
//   taps N [ctrl+]NAME         N presses and releases queued at once
//   expect_recovery 0|1        whether the autosaved recovery file exists (waits for it)
//   answer LABEL               press a button of the open dialog
//   expect_prompt TITLE / expect_no_prompt
//   expect_modified 0|1 / expect_state growing|done|cancelled|failed / expect_param KEY=VALUE
//   wait_progress              until the progress bar with Cancel shows
//   remember / expect_same_tree / expect_new_tree
//   budget N / shot PATH / frames N / open PATH (as the library does) / quit (as Ctrl+Q)
//   ab_duplicate / ab_select a|b / ab_mode off|side|split / ab_divider F / ab_wait (the other slot's tree)
//   expect_other_state STATE   until the unselected A/B slot's growth state is STATE (as expect_state)
//   expect_recovery_b 0|1      whether slot B's autosaved recovery file exists (waits for it)
//   wait_growing S             until the growth in progress has run S seconds (fails if it ends first)
//   frame_median N             prints the median (and the longest) time of the next N frames
// At the end of the script the editor closes (exit 0); a failed expectation exits with 3.
struct script_state {
  std::vector<std::string> lines;
  size_t next = 0;
  std::chrono::steady_clock::time_point started_line = std::chrono::steady_clock::now();
  int frames_left = -1;
  const tree_skeleton* remembered = nullptr;
  std::shared_ptr<const grow_result> remembered_hold;   // keeps the remembered tree alive
  bool failed = false, finished = false;
  std::vector<std::chrono::steady_clock::time_point> frame_times;   // frame_median: one per frame
};

int glfw_key(const std::string& name) {
  if (name.size() == 1 && std::isalpha(static_cast<unsigned char>(name[0]))) return GLFW_KEY_A + (std::tolower(name[0]) - 'a');
  if (name.size() == 1 && std::isdigit(static_cast<unsigned char>(name[0]))) return GLFW_KEY_0 + (name[0] - '0');
  if (name == "escape") return GLFW_KEY_ESCAPE;
  if (name == "enter") return GLFW_KEY_ENTER;
  if (name == "backspace") return GLFW_KEY_BACKSPACE;
  if (name == "space") return GLFW_KEY_SPACE;
  if (name == "f12") return GLFW_KEY_F12;
  return GLFW_KEY_UNKNOWN;
}

// Runs the script's current command; returns false once the script is over.
bool run_script(editor_state& e, script_state& sc) {
  using clock = std::chrono::steady_clock;
  auto fail = [&](const std::string& why) {
    std::fprintf(stderr, "sylva script: FAIL at line %zu (%s): %s\n", sc.next + 1, sc.lines[sc.next].c_str(), why.c_str());
    sc.failed = true;
    return false;
  };
  while (sc.next < sc.lines.size()) {
    const std::string& line = sc.lines[sc.next];
    const size_t sp = line.find(' ');
    const std::string cmd = line.substr(0, sp), arg = sp == std::string::npos ? "" : line.substr(sp + 1);
    const double waited = std::chrono::duration<double>(clock::now() - sc.started_line).count();
    const bool growing = e.growth_state == editor_state::growth::growing;
    bool done = true;   // false: wait and try again next frame
    auto shown_prompt = [&](const std::string& t) {
      return std::find(e.prompts_shown.begin(), e.prompts_shown.end(), t) != e.prompts_shown.end();
    };
    if (line.empty() || line[0] == '#') {
    } else if (cmd == "wait_tree") {
      done = !growing && e.shown;
      if (!done && waited > 120) return fail("no tree after 120 s");
    } else if (cmd == "set") {
      if (std::string err = set_preset_param(e.doc, arg); !err.empty()) return fail(err);
      sc.frames_left = 2;   // posted on the next frame
    } else if (cmd == "expect_recovery" || cmd == "expect_recovery_b") {
      std::error_code ec;
      done = fs::exists(recovery_path(e, cmd == "expect_recovery" ? 0 : 1), ec) == (arg == "1");
      if (!done && waited > 20) return fail(arg == "1" ? "no recovery file" : "the recovery file stays");
    } else if (cmd == "wait_growing") {
      if (!growing) return fail("the growth ended before " + arg + " s");
      done = seconds_since(e.posted_at) >= std::atof(arg.c_str());
    } else if (cmd == "expect_other_state") {
      static const char* names[] = {"idle", "growing", "asking", "done", "cancelled", "failed"};
      const int st = e.ab.has_b ? e.ab.other.growth : 0;
      done = arg == names[std::clamp(st, 0, 5)];
      if (!done && waited > 60) return fail(std::string("the other slot's state is ") + names[std::clamp(st, 0, 5)]);
    } else if (cmd == "key" || cmd == "taps") {
      std::string name = arg;
      int taps = 1;
      if (cmd == "taps") {   // taps N KEY: N press/release pairs queued at once between two frames
        taps = std::atoi(arg.c_str());
        name = arg.substr(std::min(arg.size(), arg.find(' ') + 1));
      }
      bool ctrl = false, shift = false;
      for (;;) {
        if (name.rfind("ctrl+", 0) == 0) ctrl = true, name = name.substr(5);
        else if (name.rfind("shift+", 0) == 0) shift = true, name = name.substr(6);
        else break;
      }
      const int k = glfw_key(name);
      if (k == GLFW_KEY_UNKNOWN) return fail("unknown key");
      if (ctrl) e.input.push_key(GLFW_KEY_LEFT_CONTROL, GLFW_PRESS);
      if (shift) e.input.push_key(GLFW_KEY_LEFT_SHIFT, GLFW_PRESS);
      for (int i = 0; i < taps; ++i) {
        e.input.push_key(k, GLFW_PRESS);
        e.input.push_key(k, GLFW_RELEASE);
      }
      if (shift) e.input.push_key(GLFW_KEY_LEFT_SHIFT, GLFW_RELEASE);
      if (ctrl) e.input.push_key(GLFW_KEY_LEFT_CONTROL, GLFW_RELEASE);
      sc.frames_left = 2 * taps + 3;   // let the queued events drain before the next command
    } else if (cmd == "answer") {
      e.script_answer = arg;
      sc.frames_left = 2;
    } else if (cmd == "expect_prompt") {
      done = shown_prompt(arg);
      if (!done && waited > 30) return fail("the dialog did not appear");
    } else if (cmd == "expect_no_prompt") {
      if (!e.prompts_shown.empty()) return fail("a dialog is open: " + e.prompts_shown.front());
    } else if (cmd == "expect_modified") {
      if (modified(e) != (arg == "1")) return fail(modified(e) ? "the document is modified" : "the document is not modified");
    } else if (cmd == "expect_state") {
      static const char* names[] = {"idle", "growing", "asking", "done", "cancelled", "failed"};
      if (arg != names[int(e.growth_state)]) return fail(std::string("the state is ") + names[int(e.growth_state)]);
    } else if (cmd == "expect_param") {
      preset copy = e.doc;
      if (std::string err = set_preset_param(copy, arg); !err.empty()) return fail(err);
      if (!(copy == e.doc)) return fail("the parameter differs");
    } else if (cmd == "wait_progress") {
      done = long_growth(e) && e.worker->busy;
      if (!done && waited > 30) return fail("no progress bar");
    } else if (cmd == "remember") {
      sc.remembered_hold = e.shown;
      sc.remembered = e.shown ? e.shown->skeleton.get() : nullptr;
    } else if (cmd == "expect_same_tree" || cmd == "expect_new_tree") {
      const bool same = e.shown && e.shown->skeleton.get() == sc.remembered;
      if (same != (cmd == "expect_same_tree")) return fail(same ? "the tree did not change" : "the tree changed");
    } else if (cmd == "ab_duplicate") {
      handle_ab(e, ab_action::duplicate);
      if (!e.ab.has_b) return fail("no slot B: " + e.message);
      sc.frames_left = 2;
    } else if (cmd == "ab_select") {
      handle_ab(e, arg == "b" ? ab_action::select_b : ab_action::select_a);
      sc.frames_left = 2;
    } else if (cmd == "ab_mode") {
      e.ab.mode = arg == "split" ? ab_mode::split : arg == "side" ? ab_mode::side_by_side : ab_mode::off;
    } else if (cmd == "ab_divider") {
      e.ab.divider = std::clamp(float(std::atof(arg.c_str())), 0.0f, 1.0f);
    } else if (cmd == "ab_wait") {   // until slot B's tree (in whichever slot is not selected) matches its document
      const preset& other = e.ab.other_doc.doc;
      done = e.ab.has_b && e.ab.other.shown && e.ab.other.shown->spec == other.spec && !growing && e.shown;
      if (!done && waited > 120) return fail("the other slot's tree did not arrive");
    } else if (cmd == "frame_median") {   // prints the median of N frame times (the A/B figure)
      sc.frame_times.push_back(clock::now());
      const size_t n = size_t(std::max(1, std::atoi(arg.c_str())));
      done = sc.frame_times.size() > n;
      if (done) {
        std::vector<double> ms;
        for (size_t i = 1; i < sc.frame_times.size(); ++i)
          ms.push_back(std::chrono::duration<double, std::milli>(sc.frame_times[i] - sc.frame_times[i - 1]).count());
        const double worst = *std::max_element(ms.begin(), ms.end());   // the impostor atlas's hitch (issue 17)
        std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
        std::printf("sylva script: frame median %.2f ms over %zu frames (A/B %s)\n", ms[ms.size() / 2], ms.size(),
                    ab_showing(e.ab) ? ab_mode_label(e.ab.mode) : "off");
        std::printf("sylva script: frame max %.2f ms\n", worst);
        std::fflush(stdout);
        sc.frame_times.clear();
      }
    } else if (cmd == "budget") {
      e.worker->node_budget = std::atoll(arg.c_str());
    } else if (cmd == "shot") {
      e.script_shot = arg;
      sc.frames_left = 2;   // the UI is built before the script runs: the shot shows the next frame
    } else if (cmd == "frames") {
      if (sc.frames_left < 0) sc.frames_left = std::atoi(arg.c_str());
    } else if (cmd == "open") {
      request(e, editor_state::then::open, arg);
      sc.frames_left = 2;
    } else if (cmd == "quit") {
      request(e, editor_state::then::quit);
      sc.frames_left = 2;
    } else {
      return fail("unknown command");
    }
    if (!done) return true;
    static const auto script_start = clock::now();
    std::printf("sylva script: ok %s (%.1f s)\n", line.c_str(), std::chrono::duration<double>(clock::now() - script_start).count());
    std::fflush(stdout);
    ++sc.next;
    sc.started_line = clock::now();
    if (sc.frames_left > 0) return true;   // continue after that many frames
  }
  sc.finished = true;
  return false;
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
      o.fit_screen = false;
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
  e->home = user_folder();
  script_state script;
  if (const char* s = std::getenv("SYLVA_SCRIPT")) {
    std::string text;
    if (std::string err = read_file(s, text); !err.empty()) {
      std::fprintf(stderr, "sylva: %s\n", err.c_str());
      return 2;
    }
    size_t a = 0;
    while (a <= text.size()) {
      size_t b = text.find('\n', a);
      if (b == std::string::npos) b = text.size();
      script.lines.push_back(text.substr(a, b - a));
      a = b + 1;
    }
  }
  const bool scripted = !script.lines.empty();
  const bool automated = !o.screenshot_path.empty();
  if (const char* s = std::getenv("SYLVA_NODE_BUDGET")) e->worker->node_budget = std::max<int64_t>(1000, std::atoll(s));
  // Work left unsaved by a crash or a killed session: offered back (not in automatic screenshots).
  if (std::error_code ec; !automated && fs::exists(recovery_path(*e), ec)) {
    if (load_preset_file(recovery_path(*e), e->recovered).ok) {
      std::string source;
      (void)read_file(recovery_path(*e) + ".source", source);
      e->recovered_path = source;
      e->recovered_a = e->open_recovery = true;
    }
  }
  if (std::error_code ec; !automated && fs::exists(recovery_path(*e, 1), ec)) {   // slot B's (A/B)
    if (load_preset_file(recovery_path(*e, 1), e->recovered_b_doc).ok) {
      std::string source;
      (void)read_file(recovery_path(*e, 1) + ".source", source);
      e->recovered_b_path = source;
      e->recovered_b = e->open_recovery = true;
    }
  }
  e->show_overlays = o.overlays;
  if (const char* s = std::getenv("SYLVA_SHOW_BROWSER")) e->browser.open = std::atoi(s) != 0;
  if (const char* s = std::getenv("SYLVA_SHOW_EXPORT")) e->exporter.open = std::atoi(s) != 0;

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
  // The window fits the monitor's work area on the first start and keeps its place afterwards.
  editor_settings settings = load_settings(e->home);
  if (!std::getenv("SYLVA_NODE_BUDGET") && settings.node_budget > 0) e->worker->node_budget = settings.node_budget;
  if (!scripted) e->recent = settings.recent;
  const bool remember_window = o.fit_screen && o.screenshot_path.empty() && !scripted;
  int width = o.width, height = o.height, pos_x = -1, pos_y = -1;
  if (o.fit_screen) {
    int ax = 0, ay = 0, aw = 0, ah = 0;
    if (GLFWmonitor* m = glfwGetPrimaryMonitor()) glfwGetMonitorWorkarea(m, &ax, &ay, &aw, &ah);
    if (aw > 0 && ah > 0) {
      const int frame = 40;   // room for the window manager's title bar
      if (remember_window && settings.width > 0) {
        width = std::min(settings.width, aw), height = std::min(settings.height, ah - frame);
        pos_x = std::clamp(settings.x, ax, ax + aw - width), pos_y = std::clamp(settings.y, ay, ay + ah - height);
      } else {
        width = std::min(o.width, aw), height = std::min(o.height, ah - frame);
        pos_x = ax + (aw - width) / 2, pos_y = ay + std::max(0, (ah - frame - height) / 2) + frame;
      }
    }
  }
  std::string why;   // shown once placed, so that it does not jump
  GLFWwindow* window = create_gl33_window({width, height, "Sylva", false, false, remember_window && settings.maximized}, why);
  if (window && pos_x >= 0) glfwSetWindowPos(window, pos_x, pos_y);
  if (window) glfwShowWindow(window);
  if (!window) {
    std::fprintf(stderr, "sylva: %s\n", why.c_str());
    glfwTerminate();
    return 1;
  }
  e->window = window;
  // Closing the window asks first when there are unsaved changes (issue 14).
  glfwSetWindowUserPointer(window, e.get());
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
    if (const char* sc = std::getenv("SYLVA_UI_SCALE")) xs = float(std::atof(sc));
    apply_ui_scale(xs);
  }
  // Moved to a monitor with another scale: the style and fonts follow before the next frame.
  glfwSetWindowContentScaleCallback(window, [](GLFWwindow* w, float xs, float) {
    if (auto* ed = static_cast<editor_state*>(glfwGetWindowUserPointer(w))) ed->rescale_to = xs;
  });
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  install_input_queue(window, &e->input);
  ImGui_ImplOpenGL3_Init("#version 330 core");

  if (!init_renderer(e->renderer)) set_status(*e, e->renderer.error, true);
  start_worker(*e->worker);
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

    if (e->rescale_to > 0 && !std::getenv("SYLVA_UI_SCALE")) {
      apply_ui_scale(e->rescale_to);
      ImGui_ImplOpenGL3_DestroyFontsTexture();
      ImGui_ImplOpenGL3_CreateFontsTexture();
    }
    e->rescale_to = 0;
    feed_imgui(e->input, ImGui::GetIO());
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();

    int fb_w = 0, fb_h = 0, win_w = 0, win_h = 0;
    glfwGetFramebufferSize(window, &fb_w, &fb_h);
    glfwGetWindowSize(window, &win_w, &win_h);

    // Build the UI first; only then read the state for drawing (DESIGN §9).
    e->hold_post = false;
    timeline_markers = !e->doc.spec.keyframes.empty();
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
    if (std::string p = draw_preset_browser(e->browser, e->doc); !p.empty()) request(*e, editor_state::then::open, p);
    draw_export_dialog(e->exporter, export_context{e->shown, e->step, e->doc, e->renderer, e->camera}, e->message, e->message_is_error);
    handle_keys(*e);
    const view_rect view{left, top, float(win_w) - left, bottom - top};
    // A slot whose growth failed or waits marks its (older) tree stale.
    const bool stale_mine = !ab_slot_problem(int(e->growth_state), e->growth_text).empty();
    const bool stale_other = !ab_slot_problem(e->ab.other.growth, e->ab.other.growth_text).empty();
    const bool ab_drag = draw_ab_overlay(e->ab, view.x, view.y, view.w, view.h, slot_label(e->ab.selected == 0 ? e->doc : e->ab.other_doc.doc),
                                         slot_label(e->ab.selected == 0 ? e->ab.other_doc.doc : e->doc),
                                         e->ab.selected == 0 ? stale_mine : stale_other, e->ab.selected == 0 ? stale_other : stale_mine);
    // Side by side: picking and the picked branch use the selected slot's half.
    view_rect pick_view = view;
    if (ab_showing(e->ab) && e->ab.mode == ab_mode::side_by_side) {
      pick_view.w = float(std::max(1, int(view.w) / 2));
      if (e->ab.selected == 1) pick_view.x += pick_view.w, pick_view.w = view.w - pick_view.w;
    }
    if (!ab_drag) handle_mouse(*e, pick_view);
    draw_prune_overlay(e->prune, e->shown && e->shown->skeleton ? e->shown->skeleton.get() : nullptr, e->step,
                       e->camera, pick_view);
    record_undo(*e);
    autosave(*e, dt);

    post_if_changed(*e);
    take_new_tree(*e);
    restore_slot_b(*e);
    ab_poll_other(e->ab, e->step);
    if (e->ab.other.worker) e->ab.other.worker->node_budget = e->worker->node_budget.load();
    if (scripted && !script.failed && !script.finished) {
      if (script.frames_left > 0) --script.frames_left;
      else {
        script.frames_left = -1;
        if (!run_script(*e, script)) {
          if (script.failed) exit_code = 3;
          e->quit_confirmed = true;
          glfwSetWindowShouldClose(window, GLFW_TRUE);
        }
      }
    }

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
    if (e->frame_now && e->shown) {
      // With A and B on screen, both trees fit (the same camera draws both).
      glm::vec3 lo = e->renderer.bounds_min, hi = e->renderer.bounds_max;
      if (ab_showing(e->ab) && e->ab.other.shown) {
        lo = glm::min(lo, e->ab.other.renderer.bounds_min);
        hi = glm::max(hi, e->ab.other.renderer.bounds_max);
      }
      frame_view(e->camera, lo, hi, e->view_aspect);
    }
    e->frame_now = false;

    update_thumbnails(e->browser);   // GL is main-thread only: between building the UI and drawing
    const std::string title = std::string("Sylva - ") + (e->ab.has_b ? (e->ab.selected == 0 ? "[A] " : "[B] ") : "") + e->doc.name + (has_unsaved_changes(e->browser, e->doc) ? " *" : "");
    if (title != window_title) glfwSetWindowTitle(window, (window_title = title).c_str());
    ImGui::Render();
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
    if (e->renderer.ok && e->shown && e->shown->skeleton)
      editor_lod_update(e->lod, e->renderer, *e->shown->skeleton, e->shown->mesh, e->shown->mesh_settings, e->doc.render,
                        e->camera, e->step);
    // Wind time runs only while the wind blows, so turning it on resumes where it stopped.
    if (e->doc.render.wind.enabled) e->renderer.wind_time = float(std::fmod(double(e->renderer.wind_time) + dt, 3600.0));
    if (e->renderer.ok && ab_showing(e->ab)) {   // A/B: both slots, same camera, sun and step
      ab_view& o = e->ab.other;
      if (o.renderer.ok && o.shown && o.shown->skeleton)
        editor_lod_update(o.lod, o.renderer, *o.shown->skeleton, o.shown->mesh, o.shown->mesh_settings, e->ab.other_doc.doc.render,
                          e->camera, std::min(e->step, o.shown->skeleton->steps));
      ab_draw(e->ab, e->renderer, e->doc.render, e->ab.other_doc.doc.render, e->camera, vx, vy, vw, vh, e->show_overlays ? &e->overlays : nullptr);
    } else if (e->renderer.ok) {
      draw_frame(e->renderer, e->doc.render, e->camera, vw, vh, {}, e->show_overlays ? &e->overlays : nullptr, {vx, vy});
    }
    if (e->renderer.texture_message != e->texture_message) {
      e->texture_message = e->renderer.texture_message;
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
    glViewport(0, 0, fb_w, fb_h);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

    if (e->shown) ++frames_with_tree;
    const bool auto_shot = !o.screenshot_path.empty() && frames_with_tree >= o.frames;
    const double waited = std::chrono::duration<double>(now - started).count();
    if (auto_shot || (!o.screenshot_path.empty() && waited > 60)) {   // SYLVA_SCREENSHOT: the whole window
      const std::string& path = o.screenshot_path;
      std::string err = save_window_png(fb_w, fb_h, path);
      set_status(*e, err.empty() ? "Screenshot saved to " + path : "Screenshot failed: " + err, !err.empty());
      {
        if (!err.empty() || !auto_shot) exit_code = 1;
        if (!auto_shot) std::fprintf(stderr, "sylva: no tree after 60 s; screenshot taken anyway\n");
        glfwSetWindowShouldClose(window, GLFW_TRUE);
      }
    }
    if (!e->script_shot.empty() && script.frames_left == 1) {
      if (std::string err = save_window_png(fb_w, fb_h, e->script_shot); !err.empty()) std::fprintf(stderr, "sylva: %s\n", err.c_str());
      e->script_shot.clear();
    }
    glfwSwapBuffers(window);
  }

  if (scripted && !script.finished && !script.failed)
    std::printf("sylva script: the editor closed before line %zu\n", script.next + 1);
  if (remember_window) {
    settings.maximized = glfwGetWindowAttrib(window, GLFW_MAXIMIZED) == GLFW_TRUE;
    if (!settings.maximized) {
      glfwGetWindowPos(window, &settings.x, &settings.y);
      glfwGetWindowSize(window, &settings.width, &settings.height);
    }
  }
  if (o.screenshot_path.empty() && !scripted) {
    settings.node_budget = e->worker->node_budget.load();
    settings.recent = e->recent;
    save_settings(e->home, settings);
  }
  shutdown_export_dialog(e->exporter);
  stop_worker(*e->worker);
  ab_free_gl(e->ab);
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
