// A/B comparison: a second document slot B beside the edited tree A, shown side by side
// or as a split view with the same camera, sun and timeline step.
//
// The editor holds two slots of one struct (ab_state::slots) and the index of the selected one;
// every panel, save, export and undo action reaches the selected slot through editor_state::cur(),
// so nothing is copied between slots when the selection changes. Each slot has its own growth
// worker, so an edit regrows only its slot and the newest request wins per slot.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/editor/editor_lod.h"
#include "app/common/worker.h"
#include "render/io/preset.h"
#include "render/gl/renderer.h"

namespace sylva {

// What a slot's growth is doing; the status bar shows exactly one of these.
enum class slot_growth { idle, growing, asking, done, cancelled, failed };

// The document part of a slot: what is saved, undone and compared for "modified".
struct slot_document {
  preset doc;                       // the edited copy (DESIGN §9: edit a copy, commit on change)
  preset undo_base;                 // doc as of the last undo step
  std::vector<preset> undo, redo;
  std::string path;                 // where Save writes ("" until saved or opened)
  preset baseline;                  // as last opened or saved (the unsaved-changes mark)
  std::string baseline_path;
};

// The growth and drawing part of a slot (needs a GL context and a worker thread once started).
struct slot_view {
  std::unique_ptr<worker_state> worker;
  tree_spec posted_spec;
  mesh_params posted_mesh;
  bool posted_once = false;
  uint32_t seen_generation = 0;
  uint32_t posted_generation = 0;   // the newest request
  uint32_t stale_before = 0;        // results older than this were cancelled
  uint32_t error_after = 0;         // a tree from a newer request clears the error
  uint32_t frame_generation = 0;    // frame the first result at or after this generation (0: none)
  slot_growth growth = slot_growth::idle;
  std::string growth_text;          // detail for done / cancelled / failed / asking
  std::chrono::steady_clock::time_point posted_at{};
  renderer_gpu renderer;
  editor_lod lod;                   // level of detail shown in the view (app/editor/editor_lod.h)
  std::shared_ptr<const grow_result> shown;
  int overlay_generator = -1;       // the generator whose default overlay layer is selected
};

// Once a frame: the shown tree's overlays if its result came without them, the view has none yet
// and its worker has now built them (take_late_overlays), else null.
std::shared_ptr<const overlay_geometry> take_late_overlays(slot_view& v);

// One slot, A or B: its document and its view.
struct editor_slot : slot_document, slot_view {};

enum class ab_mode { off, side_by_side, split };

struct ab_state {
  editor_slot slots[2];             // A and B
  bool has_b = false;
  int selected = 0;                 // the slot the panel, undo, Save and Export act on (0 A, 1 B)
  ab_mode mode = ab_mode::side_by_side;
  float divider = 0.5f;             // split view: the divider's place across the view, 0..1
  bool dragging = false;
  // Split view: the left part of A is kept here while B is drawn over the whole view.
  unsigned keep_fbo = 0, keep_color = 0;
  int keep_w = 0, keep_h = 0;
  bool drop_confirmed = false;      // the prompt's "Drop B": drop without asking again
  // The labels as drawn last frame over each slot's part, and whether both fit their parts.
  std::string labels_shown[2];
  bool labels_fit = true;
  editor_slot& cur() { return slots[selected]; }
  const editor_slot& cur() const { return slots[selected]; }
  editor_slot& other() { return slots[1 - selected]; }
  const editor_slot& other() const { return slots[1 - selected]; }
};

// ---- Display-free logic (app/editor/editor_ab_doc.cpp; tests/app/editor_ab_test.cpp).

// Copies slot A's document into slot B, with an empty undo history, no file and the name marked
// " (B)". Only from A: returns false when B is selected.
bool ab_duplicate_doc(ab_state& s);
// Makes `slot` (0 A, 1 B) the selected one. False when nothing changes (already selected, or no B).
bool ab_select_doc(ab_state& s, int slot);
// Saves slot `slot`'s document to `path` and records it as saved; returns "" or the error.
std::string ab_save_slot(ab_state& s, int slot, const std::string& path);
// Drops slot B's document; A is selected again. (Its view: ab_stop_view.)
void ab_drop_doc(ab_state& s);

// Unsaved work in both slots (quit, window close, autosave): the slots (0 A, 1 B) with unsaved
// changes, the selected one first.
std::vector<int> ab_unsaved_slots(const ab_state& s);
// "Slot B \"Oak (B)\" (no file yet)" for the quit prompt's list.
std::string ab_unsaved_line(const ab_state& s, int slot);

// The unselected slot's growth: what to do with a result its worker published (ab_poll_other).
// A newer tree is shown; a failed or over-budget answer keeps the last tree, and the slot's growth
// state and text say so ("growth stopped: ...", "over the node budget ..."), so the comparison line
// shows it and the tree is marked stale until the slot grows again.
enum class ab_result_use { ignore, show, keep };
ab_result_use ab_take_other_result(slot_view& v, const grow_result& r);
// "" when the slot's tree is its document's; else why the tree shown is an older one.
std::string ab_slot_problem(slot_growth growth, const std::string& growth_text);

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

// ---- GL and worker side (app/editor/editor_ab.cpp), main thread.

// Sets up B's view as a copy of the shown tree: a started worker, an initialised renderer holding
// the same mesh, drawn with `shared` (A's programs and textures: one GL context). Returns the
// renderer's error or "". `overlays`: the ones A shows, for a tree whose result came without them.
std::string ab_start_view(slot_view& v, const std::shared_ptr<const grow_result>& shown, int step,
                          std::shared_ptr<gl_shared> shared, std::shared_ptr<const overlay_geometry> overlays = {});
void ab_stop_view(slot_view& v);   // stops the worker, frees the renderer
// Once a frame: takes a newer result of the slot that is not selected, and follows the timeline step.
void ab_poll_other(ab_state& s, int step);
// Draws the two slots into the view rectangle (framebuffer pixels, origin bottom-left), each with
// its own document's render settings; the sun and the wind time of the selected slot serve both.
void ab_draw(ab_state& s, const orbit_camera& cam, int vx, int vy, int vw, int vh, const overlay_view* overlays);
void ab_free_gl(ab_state& s);   // both slots' views and the split view's buffer

// ImGui: the A/B controls for the top of the parameter panel. Returns what the user asked for.
enum class ab_action { none, duplicate, select_a, select_b, drop };
ab_action draw_ab_controls(ab_state& s);
// ImGui: slot labels and the split divider over the 3D view (window coordinates). Returns true
// while the divider is dragged (the camera must not take that drag).
// A stale slot (its growth failed or waits: it shows an older tree) is labelled so, in red.
bool draw_ab_overlay(ab_state& s, float x, float y, float w, float h, const std::string& a_label, const std::string& b_label,
                     bool a_stale = false, bool b_stale = false);

}  // namespace sylva
