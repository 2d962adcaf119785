// Growth requests to the worker (app/worker.h) and the trees it sends back.
#include "app/editor_state.h"

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
  return e.growth_state == editor_state::growth::growing && seconds_since(e.posted_at) > 0.2;
}

void cancel_request(editor_state& e) {
  e.stale_before = cancel_growth(*e.worker);
  keep_shown_tree(e, "the previous tree stays");
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

// Posts the document when its spec or mesh settings changed; render settings only touch uniforms.
void post_if_changed(editor_state& e) {
  if (e.hold_post) return;
  const bool render_changed = !(e.doc.render == e.posted_render);
  e.posted_render = e.doc.render;
  if (e.posted_once && e.doc.spec == e.posted_spec && e.doc.mesh == e.posted_mesh) {
    if (render_changed) e.last_edit = param_class::render;   // nothing to grow or mesh: drawn next frame
    return;
  }
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
  if (r->over_mesh_budget && newest) {   // shown as a failure that keeps the tree; the prompt offers a fit
    e.mesh_answer = r;
    e.open_mesh_prompt = true;
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
  e.last_edit = r->edit;
  const auto upload_start = std::chrono::steady_clock::now();
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
  e.upload_ms = ms_since(upload_start);
  if (e.frame_generation != 0 && int32_t(r->generation - e.frame_generation) >= 0) {
    frame_view(e.camera, e.renderer.bounds_min, e.renderer.bounds_max, e.view_aspect);
    e.frame_generation = 0;
  }
  if (newest && !r->report.error && int32_t(r->generation - e.error_after) > 0) clear_error(e);
  else if (newest && r->report.error) set_status(e, r->report.message, true);
}

}  // namespace sylva::ed
