// Growth requests to the worker (app/common/worker.h) and the trees it sends back.
#include "app/editor/editor_state.h"

#include "generators/timing.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>


namespace sylva::ed {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// The growth in progress has run long enough to show a progress bar with Cancel (~200 ms).
bool long_growth(const editor_state& e) {
  const editor_slot& s = e.cur();
  return s.growth == slot_growth::growing && seconds_since(s.posted_at) > 0.2;
}

void cancel_request(editor_state& e) {
  editor_slot& s = e.cur();
  s.stale_before = cancel_growth(*s.worker);
  keep_shown_tree(e, "the previous tree stays");
}

// A cancelled or over-budget request: the document goes back to the tree on screen, so what is
// shown is what would be saved. The edit is dropped from the undo history.
void keep_shown_tree(editor_state& e, const std::string& why) {
  editor_slot& s = e.cur();
  if (e.before_open && s.shown && s.shown->skeleton && s.shown->skeleton->size()) {
    // The opened preset's tree never arrived: back to the document on screen, name and file too.
    s.doc = e.before_open->doc;
    s.path = e.before_open->path;
    s.baseline = e.before_open->baseline;
    s.baseline_path = e.before_open->baseline_path;
    e.before_open.reset();
  }
  if (s.shown && s.shown->skeleton && s.shown->skeleton->size()) {
    s.doc.spec = s.shown->spec;
    s.doc.mesh = s.shown->mesh_settings;
    if (!s.undo.empty() && s.undo.back() == s.doc) s.undo.pop_back();
    s.undo_base = s.doc;
    s.posted_spec = s.doc.spec;
    s.posted_mesh = s.doc.mesh;
  }
  s.growth = slot_growth::cancelled;
  s.growth_text = why;
}

// Posts the document when its spec or mesh settings changed; render settings only touch uniforms.
void post_if_changed(editor_state& e) {
  editor_slot& s = e.cur();
  if (e.hold_post) return;
  const bool render_changed = !(s.doc.render == e.posted_render);
  e.posted_render = s.doc.render;
  if (s.posted_once && s.doc.spec == s.posted_spec && s.doc.mesh == s.posted_mesh) {
    if (render_changed) e.last_edit = param_class::render;   // nothing to grow or mesh: drawn next frame
    return;
  }
  // A new generator (switched or undone) is a new tree: frame it. Edits and opened presets keep the camera.
  if (s.posted_once && s.doc.spec.params.index() != s.posted_spec.params.index() && !e.keep_view) e.frame_new = true;
  e.keep_view = false;
  s.posted_spec = s.doc.spec;
  s.posted_mesh = s.doc.mesh;
  s.posted_once = true;
  s.posted_generation = post_request(*s.worker, s.posted_spec, s.posted_mesh, e.approve_next);
  e.approve_next = false;
  s.posted_at = std::chrono::steady_clock::now();
  s.growth = slot_growth::growing;
  if (e.frame_new) s.frame_generation = s.posted_generation;
  e.frame_new = false;
}

// Keeps the pitch off the poles, then fits the box from the current direction (never top-down).
void frame_view(orbit_camera& c, const glm::vec3& lo, const glm::vec3& hi, float aspect) {
  if (c.pitch > 50 || c.pitch < -30) c.pitch = 10;
  frame_camera(c, lo, hi, aspect);
}

// The shown tree's growth overlays (null: none yet, the old tree's are cleared); a new generator
// selects its own first layer once its overlays are there.
void apply_overlays(editor_state& e, editor_slot& s, std::shared_ptr<const overlay_geometry> geo) {
  const bool have = geo != nullptr;
  set_overlays(s.renderer, std::move(geo));
  fit_shadow_slice(e.overlays, s.renderer.overlay);
  if (have && s.shown && int(s.shown->spec.params.index()) != s.overlay_generator) {
    s.overlay_generator = int(s.shown->spec.params.index());
    overlay_view& v = e.overlays;
    if (!v.combine) v.kinds = 1u << overlay_default_kind(s.overlay_generator, s.renderer.overlay.present);
  }
}

// Shows a newer worker result: upload in the same frame it is seen (DESIGN §5).
void take_new_tree(editor_state& e) {
  editor_slot& s = e.cur();
  if (std::shared_ptr<const overlay_geometry> geo = take_late_overlays(s)) apply_overlays(e, s, std::move(geo));
  std::shared_ptr<const grow_result> r = take_result(*s.worker, s.seen_generation);
  if (!r) return;
  s.seen_generation = r->generation;
  if (int32_t(r->generation - s.stale_before) < 0) return;   // cancelled before it arrived
  const bool newest = r->generation == s.posted_generation;
  if (r->over_budget) {
    if (!newest) return;
    e.budget_answer = r;
    e.ask(dialog::large_tree);
    s.growth = slot_growth::asking;
    s.growth_text = "over the node budget: grow it anyway?";
    return;
  }
  if (r->over_mesh_budget && newest) {   // shown as a failure that keeps the tree; the prompt offers a fit
    e.mesh_answer = r;
    e.ask(dialog::large_mesh);
  }
  if (newest) {
    s.growth = r->report.error ? slot_growth::failed : slot_growth::done;
    s.growth_text = r->report.error ? r->report.message : r->report.stop_reason;
    if (!r->report.error && !r->report.message.empty()) s.growth_text += " (" + r->report.message + ")";
    if (r->resumed_at > 0) s.growth_text += ", resumed at step " + std::to_string(r->resumed_at);
  }
  if (s.shown && keeps_last_tree(*r)) return set_status(e, r->report.message, true);
  if (newest) e.before_open.reset();   // the opened preset's own tree (or a later edit's) is shown
  const int old_steps = s.shown && s.shown->skeleton ? s.shown->skeleton->steps : -1;
  const bool at_end = !s.shown || e.step >= old_steps;
  s.shown = r;
  e.last_edit = r->edit;
  const auto upload_start = std::chrono::steady_clock::now();
  upload_tree(s.renderer, r->mesh);
  editor_lod_new_tree(s.lod);
  upload_wind(s.renderer, *r->skeleton);
  apply_overlays(e, s, r->overlays);   // null on a regrown tree: take_late_overlays brings them
  const int steps = r->skeleton->steps;
  e.step = at_end ? steps : std::min(e.step, steps);
  set_tree_step(s.renderer, *r->skeleton, r->mesh_settings.min_radius, e.step);
  e.upload_ms = ms_since(upload_start);
  if (s.frame_generation != 0 && int32_t(r->generation - s.frame_generation) >= 0) {
    frame_view(e.camera, s.renderer.bounds_min, s.renderer.bounds_max, e.view_aspect);
    s.frame_generation = 0;
  }
  if (newest && !r->report.error && int32_t(r->generation - s.error_after) > 0) clear_error(e);
  else if (newest && r->report.error) set_status(e, r->report.message, true);
}

}  // namespace sylva::ed
