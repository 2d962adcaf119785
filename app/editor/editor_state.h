// The editor's state and the functions its parts share (app/editor/editor*.cpp). One editor_state per
// window; every part reads and edits it on the UI thread, between two frames.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "app/editor/editor_ab.h"
#include "app/editor/editor_files.h"
#include "app/editor/editor_generators.h"
#include "app/editor/editor_keyframes.h"
#include "app/editor/editor_lod.h"
#include "app/editor/editor_prune.h"
#include "app/editor/editor_sliders.h"
#include "app/editor/export_dialog.h"
#include "app/editor/input_queue.h"
#include "app/editor/preset_browser.h"
#include "app/editor/view_quality.h"
#include "app/common/worker.h"
#include "render/io/preset.h"
#include "render/gl/renderer.h"

struct GLFWwindow;

namespace sylva::ed {

// The editor's keys and mouse gestures, in the order the F1 list shows them: one table
// (app/editor/editor_shortcuts.cpp) gives the list, the menus' key labels and the keys read.
enum class shortcut { orbit, pan, zoom, frame, undo, redo, save, open, library, quit, play, first_last, step, escape,
                      screenshot, help, views, gizmo, slider_drag, slider_reset, count };

// The editor's dialogs: the file browser's four uses, then the modal prompts. Each is asked for
// (editor_state::ask) and opened on the next frame by draw_dialogs (editor_dialogs.cpp).
enum class dialog { open_preset, save_as, screenshot_as, export_as, unsaved_changes, large_tree, large_mesh, drop_b,
                    not_restored, restore, about, count };

namespace fs = std::filesystem;

// Layout sizes at a content scale of 1; multiplied by ui_scale (the monitor's content scale).
inline float ui_scale = 1;
inline bool timeline_markers = false;   // the document has keyframes: the timeline shows a row of markers
inline float panel_width() { return 420 * ui_scale; }
inline float timeline_height() { return (timeline_markers ? 54 : 38) * ui_scale; }
inline float status_height() { return 26 * ui_scale; }

struct editor_state {
  // The document before an Open whose tree has not arrived yet: a cancelled or over-budget open
  // returns to it whole (name, file, saved state), not only to its tree.
  struct document { preset doc; std::string path; preset baseline; std::string baseline_path; };
  std::unique_ptr<document> before_open;
  // Growth.
  render_params posted_render;    // the render settings the last edit left (a render-only edit posts nothing)
  param_class last_edit = param_class::regrow;   // what the last edit on screen needed (status bar)
  double upload_ms = 0;           // the last new tree's upload to the renderer
  bool hold_post = false;         // an apply-on-release slider is being dragged
  int step = 0;
  bool playing = false;
  float speed = 4;                // steps per second
  double play_accum = 0;
  // View.
  orbit_camera camera;
  float view_aspect = 16.0f / 9.0f;  // the 3D view's width / height, for framing
  bool frame_new = true;          // frame the camera on the tree of the next request (new preset or generator)
  bool frame_now = false;         // frame the tree on screen now (F)
  bool keep_view = false;         // the next request is an opened preset: the camera stays (F frames)
  bool framed_side_by_side = false;   // the A/B view was side by side when the tree was last framed
  overlay_view overlays;          // which overlay layers show (UI state; the renderer only draws them)
  bool show_overlays = false, show_panel = true, show_timeline = true, show_advanced = false;
  std::string panel_search;       // the parameter panel's search box
  std::string searched;           // the search the panel last drew (a new one may open another tab)
  int search_matches = -1;        // parameters the search matches in every tab (-1: no search)
  int panel_tab_shown = 0;        // the panel's open tab (panel_tab)
  path_field_edit path_edit;      // a file path being typed in the panel (app/editor/editor_sliders.h)
  std::map<std::string, std::array<float, 2>> path_field_at;   // where each path field was drawn (the scripted test's click)
  // Dialogs.
  std::array<bool, size_t(dialog::count)> asked{};   // the dialogs to open on the next frame
  void ask(dialog d, bool yes = true) { asked[size_t(d)] = yes; }   // (no: the question is withdrawn)
  file_browser files;             // app/editor/editor_files.h: Open, Save as, Screenshot as, Export as
  dialog browse = dialog::open_preset;   // what the file browser is open for (one of the first four)
  std::vector<std::string> recent;
  std::string script_answer;      // the scripted test's click on a dialog button (see run_script)
  std::string script_shot;        // the scripted test's screenshot path, taken at the end of the frame
  // Status.
  std::string message;
  bool message_is_error = false;
  // A plain message goes stale: once the document is edited after it ("Saved" while modified) or
  // after half a minute ("Slot B dropped" minutes later). Errors stay until a success clears them.
  size_t message_edits = 0;                           // undo + redo depth when it was set
  std::chrono::steady_clock::time_point message_at;
  float status_right = 0;         // the status bar's text ends here (window x), cut to fit
  std::string status_cut;         // a piece of it cut with "…" this frame, whole (its tooltip)
  std::string window_title;       // as last set ("Sylva - oak *")
  std::string toast;              // the last error in full, until dismissed or a success
  struct log_line { std::string time, text; bool error; };
  std::vector<log_line> log;      // View > Messages
  bool show_log = false, show_shortcuts = false;
  double frame_ms = 0;
  uint64_t frames_drawn = 0;      // since start (an idle editor draws none: the frame loop waits)
  uint64_t cheap_frames = 0;      // of them, drawn cheaper while the user interacted (view_quality.h)
  interactive_view quick_view;    // the cheaper view's half-resolution target
  uint64_t kept_frames = 0;       // frames that showed the last picture again (nothing in it changed)
  view_cache kept_view;           // that picture (view_quality.h)
  bool full_quality = false;      // every frame drawn in full (the scripted measurement's baseline)
  bool screenshot_requested = false;   // F12: the 3D view to ~/Sylva/screenshots/
  std::string screenshot_to;            // Screenshot as...: this path
  std::string screenshot_path;
  std::string texture_message;    // the renderer's last texture error, once shown
  export_dialog_state exporter;   // app/editor/export_dialog.h
  preset_browser_state browser;   // app/editor/preset_browser.h; also holds the last saved preset
  generator_panel_state generator_panels;   // app/editor/editor_generators.h
  keyframe_panel_state keys;                // app/editor/editor_keyframes.h: growth phases
  prune_panel_state prune;                  // app/editor/editor_prune.h: picking, cuts, the brush
  GLFWwindow* window = nullptr;
  float rescale_to = 0;           // a new content scale to apply before the next frame (0: none)
  std::shared_ptr<const grow_result> budget_answer;   // an over-budget estimate waiting for the user
  bool approve_next = false;
  std::shared_ptr<const grow_result> mesh_answer;     // a tree over the mesh budget, not meshed, waiting for the user
  // Nodes alive at the scrubbed step (cached per tree and step).
  const tree_skeleton* counted_tree = nullptr;
  int counted_step = -1;
  size_t counted_nodes = 0;
  // Unsaved work: what to do once the user has answered save / discard / cancel.
  enum class then { nothing, quit, open } pending = then::nothing;
  std::string pending_path;
  bool continue_after_save = false, close_requested = false, quit_confirmed = false;
  bool save_all = false;          // quitting with A/B: "Save" saves every slot with changes in turn
  // Recovery: each slot's document is autosaved while modified and offered back on the next start
  // (slot A in .recovery.json, slot B in .recovery_b.json).
  std::string home;               // ~/Sylva or $SYLVA_HOME
  double autosave_wait = 0;
  preset autosaved[2];
  bool autosaved_any[2] = {false, false};
  preset recovered;
  std::string recovered_path;
  bool recovered_a = false;       // slot A's document was recovered
  bool recovered_b = false;       // slot B's too: restored as B once A's tree shows
  bool restore_b_pending = false;
  preset recovered_b_doc;
  std::string recovered_b_path;
  // Autosaves that could not be offered back: why, and where each was kept (never overwritten).
  std::vector<std::string> unrestored;
  bool autosave_off[2] = {false, false};   // a slot's unusable autosave could not be moved aside
  std::vector<std::string> prompts_shown;   // modal titles drawn this frame (for the scripted test)
  input_queue input;              // keyboard events, fed to ImGui one transition per key per frame
  // The two document slots, A and B (app/editor/editor_ab.h), and the A/B view. Everything about the
  // document, its growth and its drawing is the selected slot's: reach it through cur().
  ab_state ab;
  editor_slot& cur() { return ab.cur(); }
  const editor_slot& cur() const { return ab.cur(); }
};

// Status (editor_status.cpp): the status bar, the error toast, the overlay legend.
// The status bar's message; errors also go to a dismissable toast, and every message to the log.
void set_status(editor_state& e, const std::string& m, bool error = false);
void clear_error(editor_state& e);   // the next successful action clears an error left from before
std::string count_text(double n);    // "1.2 million"
std::string seconds_text(double s);  // "3 min"
// `text` as it fits in `width` (measure: a string's width): whole, or its longest prefix that fits
// with "…" after it, cut between UTF-8 characters.
std::string elide_text(const std::string& text, float width, const std::function<float(std::string_view)>& measure);
void draw_status(editor_state& e, float y, float w);
void draw_toast(editor_state& e, float left, float top, float right);
void draw_overlay_legend(editor_state& e, float left, float bottom);
// Why the next frame is drawn without waiting for input: "wind", "playback", "growing",
// "thumbnails", "export", "derivation", "levels of detail" or "a command"; "" when the editor may
// wait for events (the frame loop in editor.cpp). The status bar names wind and playback.
std::string drawing_reason(const editor_state& e);

// Parameters (editor_params.cpp): the left panel.
void draw_panel(editor_state& e, float top, float bottom);
// The Generator selector: a new generator is a new tree, with that generator's defaults and no
// keyframes, and none of the previous species' look (leaves, cones and fruit, bark materials and
// textures) or name; it is framed when it arrives.
void switch_generator(editor_state& e, int generator);

// The document (editor_document.cpp): presets, saving, unsaved work, recovery and undo.
std::vector<fs::path> preset_dirs();
void open_preset(editor_state& e, const std::string& path);
void note_saved(editor_state& e, const std::string& path);
bool save_to(editor_state& e, const std::string& path);
std::string user_folder();
bool is_installed_preset(const std::string& path);
std::string default_save_path(const editor_state& e);
// A preset's name as a file name: lower-case letters and digits, each run of anything else one "_",
// none at either end ("Hazel fan (guiding vectors)" -> "hazel_fan_guiding_vectors"); "tree" if empty.
std::string file_stem_for(const std::string& name);
bool modified(const editor_state& e);
std::string window_title_text(const editor_state& e);   // "Sylva - [B] oak *": the slot, the name, unsaved changes
std::vector<int> unsaved_slots(const editor_state& e);
std::string recovery_path(const editor_state& e, int slot = 0);
void remove_recovery(editor_state& e, int slot);
void remove_recovery(editor_state& e);
void find_recovery(editor_state& e);   // at start: autosaved work left by a crash, offered back
void autosave(editor_state& e, double dt);
void perform_pending(editor_state& e);
void request(editor_state& e, editor_state::then what, const std::string& path = "");
void save_command(editor_state& e);
void apply_undo(editor_state& e, std::vector<preset>& from, std::vector<preset>& to);
void record_undo(editor_state& e);

// Growth (editor_growth.cpp): requests to the worker and the trees it sends back.
double seconds_since(std::chrono::steady_clock::time_point t);
bool long_growth(const editor_state& e);
void cancel_request(editor_state& e);
void keep_shown_tree(editor_state& e, const std::string& why);
void post_if_changed(editor_state& e);
void frame_view(orbit_camera& c, const glm::vec3& lo, const glm::vec3& hi, float aspect);
void take_new_tree(editor_state& e);

// The timeline (editor_timeline.cpp): transport, scrubbing, keyframe markers and playback.
void draw_timeline(editor_state& e, float x, float y, float w);
size_t nodes_at_step(editor_state& e);
void advance_playback(editor_state& e, double dt);

// Menus and dialogs (editor_dialogs.cpp).
std::string screenshot_name();
void draw_menu(editor_state& e);
void draw_dialogs(editor_state& e);
void draw_shortcuts(editor_state& e);   // the F1 list (editor_shortcuts.cpp)
void handle_keys(editor_state& e);      // this frame's keys, as the shortcut table says
const char* shortcut_keys(shortcut s);  // its keys as a menu shows them: "Ctrl+O"
void open_export_dialog(editor_state& e);   // File > Export...: in the user's folder, named after the tree
void draw_node_budget(editor_state& e);     // the node budget: typed (Enter applies) or picked
void draw_output_extras(editor_state& e);   // the Output tab: node budget and export
void draw_message_log(editor_state& e);

// A/B slots (editor_slots.cpp).
void select_slot(editor_state& e, int slot);
void handle_ab(editor_state& e, ab_action a);
void restore_slot_b(editor_state& e);
std::string slot_label(const preset& p);

}  // namespace sylva::ed
