// A/B comparison: a second document slot B beside the edited tree A, shown side by side
// or as a split view with the same camera, sun and timeline step.
//
// The editor keeps the *selected* slot in its own fields (document, undo, worker, renderer, shown
// tree), so every panel, save, export and undo action acts on the selected slot without knowing
// about A/B. The other slot waits here; selecting it swaps the two. Each slot has its own growth
// worker, so an edit regrows only its slot and the newest request wins per slot.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/editor_lod.h"
#include "app/worker.h"
#include "render/preset.h"
#include "render/gl/renderer.h"

namespace sylva {

// The document part of a slot: what is saved, undone and compared for "modified".
struct ab_doc {
  preset doc, undo_base;
  std::vector<preset> undo, redo;
  std::string path;                 // where Save writes ("" until saved)
  preset baseline;                  // as last opened or saved (the unsaved-changes mark)
  std::string baseline_path;
};

// The editor's growth states (editor.cpp's editor_state::growth), as a slot stores them.
namespace ab_growth {
inline constexpr int idle = 0, growing = 1, asking = 2, done = 3, cancelled = 4, failed = 5;
}

// The growth and drawing part of a slot (needs a GL context and a worker thread).
struct ab_view {
  std::unique_ptr<worker_state> worker;
  renderer_gpu renderer;
  editor_lod lod;
  std::shared_ptr<const grow_result> shown;
  tree_spec posted_spec;
  mesh_params posted_mesh;
  bool posted_once = false;
  uint32_t seen_generation = 0, posted_generation = 0, stale_before = 0, error_after = 0, frame_generation = 0;
  int growth = 0;                   // the editor's growth state, as an int (ab_growth)
  std::string growth_text;
  std::chrono::steady_clock::time_point posted_at{};
  int overlay_generator = -1;
};

enum class ab_mode { off, side_by_side, split };

struct ab_state {
  bool has_b = false;
  int selected = 0;                 // 0: the editor's fields hold A; 1: they hold B
  ab_mode mode = ab_mode::side_by_side;
  float divider = 0.5f;             // split view: the divider's place across the view, 0..1
  bool dragging = false;
  ab_doc other_doc;                 // the slot that is not selected
  ab_view other;
  // Split view: the left part of A is kept here while B is drawn over the whole view.
  unsigned keep_fbo = 0, keep_color = 0;
  int keep_w = 0, keep_h = 0;
  bool ask_drop = false;            // Drop B with edits in B: the prompt asks first
  bool drop_confirmed = false;      // the prompt's "Drop B": drop without asking again
  // The labels as drawn last frame over each slot's part, and whether both fit their parts.
  std::string labels_shown[2];
  bool labels_fit = true;
};

// ---- Display-free logic (app/editor_ab_doc.cpp; tests/editor_ab_test.cpp).

// Copies the current (selected) document into slot B, with an empty undo history, no file and the
// name marked " (B)". Only from A: returns false when B is selected.
bool ab_duplicate_doc(ab_state& s, const ab_doc& current);
// Makes `slot` (0 A, 1 B) the selected one by swapping `current` with the stored document. False
// when nothing changes (already selected, or no B).
bool ab_select_doc(ab_state& s, int slot, ab_doc& current);
// The document of `slot`, given the selected one.
const ab_doc& ab_slot_doc(const ab_state& s, int slot, const ab_doc& current);
// Saves slot `slot`'s document to `path` and records it as saved; returns "" or the error.
std::string ab_save_slot(ab_state& s, int slot, ab_doc& current, const std::string& path);
// Drops slot B; if B was selected, A becomes the current document again.
void ab_drop_doc(ab_state& s, ab_doc& current);

// Unsaved work in both slots (quit, window close, autosave). `current_doc` and `current_baseline`
// are the selected slot's document and its saved state (the editor keeps the baseline in its
// preset browser). Returns the slots (0 A, 1 B) with unsaved changes, the selected one first.
std::vector<int> ab_unsaved_slots(const ab_state& s, const preset& current_doc, const preset& current_baseline);
// "Slot B \"Oak (B)\" (no file yet)" for the quit prompt's list.
std::string ab_unsaved_line(const ab_state& s, int slot, const preset& current_doc, const std::string& current_path);

// The unselected slot's growth: what to do with a result its worker published (ab_poll_other).
// A newer tree is shown; a failed or over-budget answer keeps the last tree, and the slot's growth
// state and text say so ("growth stopped: ...", "over the node budget ..."), so the comparison line
// shows it and the tree is marked stale until the slot grows again.
enum class ab_result_use { ignore, show, keep };
ab_result_use ab_take_other_result(ab_view& v, const grow_result& r);
// "" when the slot's tree is its document's; else why the tree shown is an older one.
std::string ab_slot_problem(int growth, const std::string& growth_text);

struct ab_counts {
  size_t nodes = 0, leaves = 0, triangles = 0;
  double grow_ms = 0, mesh_ms = 0;
  bool present = false;
  std::string problem;   // ab_slot_problem: the counts are of the slot's last tree
};
ab_counts ab_counts_of(const grow_result* r);   // the whole tree (the final step)
// "A 1.2k nodes, 3.4k leaves, 56k tris, grow 12 ms, mesh 3 ms | B ... " for the status bar; a slot
// with a problem reads "B growth stopped: ... (last tree 1.2k nodes ...)".
std::string ab_compare_text(const ab_counts& a, const ab_counts& b);
const char* ab_mode_label(ab_mode m);
bool ab_showing(const ab_state& s);   // B exists and the mode is not off

// ---- GL and worker side (app/editor_ab.cpp), main thread.

// Sets up B's view as a copy of the shown tree: a started worker, an initialised renderer holding
// the same mesh. Returns the renderer's error or "".
std::string ab_start_view(ab_view& v, const std::shared_ptr<const grow_result>& shown, int step);
void ab_stop_view(ab_view& v);   // stops the worker, frees the renderer
// Once a frame: takes a newer result of the slot that is not selected, and follows the timeline step.
void ab_poll_other(ab_state& s, int step);
// Draws the two slots into the view rectangle (framebuffer pixels, origin bottom-left).
// `selected` is the editor's renderer and render settings (the selected slot); the sun of the
// selected slot lights both.
void ab_draw(ab_state& s, renderer_gpu& selected, const render_params& selected_render, const render_params& other_render,
             const orbit_camera& cam, int vx, int vy, int vw, int vh, const overlay_view* overlays);
void ab_free_gl(ab_state& s);

// ImGui: the A/B controls for the top of the parameter panel. Returns what the user asked for.
enum class ab_action { none, duplicate, select_a, select_b, drop };
ab_action draw_ab_controls(ab_state& s);
// ImGui: slot labels and the split divider over the 3D view (window coordinates). Returns true
// while the divider is dragged (the camera must not take that drag).
// A stale slot (its growth failed or waits: it shows an older tree) is labelled so, in red.
bool draw_ab_overlay(ab_state& s, float x, float y, float w, float h, const std::string& a_label, const std::string& b_label,
                     bool a_stale = false, bool b_stale = false);

}  // namespace sylva
