// The one long-lived growth worker: latest request wins, stale work is cancelled (docs/design/09-editor.md).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "generators/estimate.h"
#include "generators/tree_spec.h"
#include "render/mesh/lod.h"
#include "render/mesh/mesh.h"
#include "render/mesh/overlay_geometry.h"

namespace sylva {

struct grow_result {
  uint32_t generation = 0;
  tree_spec spec;
  mesh_params mesh_settings;
  std::shared_ptr<const tree_skeleton> skeleton;
  std::shared_ptr<const growth_debug> debug;
  // Built from debug here, not on the UI thread. Null on a regrown result: its overlays come
  // after it (take_late_overlays), so that no slider release waits for them.
  std::shared_ptr<const overlay_geometry> overlays;
  tree_mesh mesh;
  grow_report report;
  double grow_ms = 0, mesh_ms = 0;
  bool regrown = true;   // false when only the mesh was rebuilt from the previous skeleton
  bool remeshed = true;  // false when the previous mesh was kept too (nothing the mesh reads changed)
  param_class edit = param_class::regrow;   // what the request needed against the previous result
  int resumed_at = 0;    // > 0: only keyframes from this step on changed, and growth resumed there (generators/resume.h)
  // Over the node budget: nothing was grown; the previous tree is re-published with the estimate
  // and the editor asks before growing it (post_request with approved = true).
  bool over_budget = false;
  double estimated_nodes = 0, estimated_seconds = 0, estimated_bytes = 0;
  std::string estimate_note;   // how later keyframes and cuts were counted (growth_estimate::note)
  std::string mesh_over_budget; // "": the estimated mesh fits its budget; else why it would not be meshed
  // Over the mesh budget (render/io/mesh_bound.h): not meshed. A failure (report.error, the refusal as
  // its message) that keeps the previous tree; the editor offers the settings that fit.
  bool over_mesh_budget = false;
  double mesh_bound_bytes = 0;   // the mesh's bound (estimated from the trial when refused before growth)
  int mesh_fit_segments = 0;     // the most radial segments that fit the budget (0: none does)
};

struct worker_request {
  uint32_t generation = 0;
  tree_spec spec;
  mesh_params mesh_settings;
  bool approved = false;   // grow even when over the budget
};

inline constexpr int64_t default_node_budget = 500000;

struct worker_state {
  std::thread thread;
  std::mutex mutex;
  std::condition_variable wake;
  std::optional<worker_request> pending;          // only the newest request is kept
  std::shared_ptr<const grow_result> published;   // newest finished result
  std::atomic<uint32_t> generation{0};            // moves on with every edit; cancels older growth
  std::atomic<bool> busy{false};
  std::atomic<float> progress{0};                 // of the growth in progress, 0..1 (grow_options::progress)
  std::atomic<bool> meshing{false};               // the request in progress grows nothing (a re-mesh) or is past its growth
  std::atomic<int64_t> node_budget{default_node_budget};   // larger requests ask first
  // The growth overlays of the newest published result that came without them, built once that
  // result is out and no request waits (some 5 ms on self_organizing_default), and the growth
  // debug they were built from.
  std::shared_ptr<const overlay_geometry> late_overlays;
  std::shared_ptr<const growth_debug> late_overlays_from;
  bool quit = false;
};

// What a change from (a, ma) to (b, mb) needs: the largest declared class (generators/params.h) of
// the parameters that differ, render when none does. A spec change outside visit_params (the
// generator, seed, keyframes, cuts) regrows; so does any difference no declared parameter explains.
param_class edit_class(const tree_spec& a, const mesh_params& ma, const tree_spec& b, const mesh_params& mb);

// The status bar's account of the last edit: which class it needed and what it cost, e.g.
// "regrow: grow 12.0 ms, mesh 4.1 ms, upload 0.9 ms", "re-mesh: grow kept, mesh 4.1 ms, upload
// 0.9 ms", "render: no grow, no mesh, no upload" (r: the tree on screen, may be null).
std::string edit_timing_text(param_class edit, const grow_result* r, double upload_ms);

void start_worker(worker_state& w);
// Stops the worker, cancelling what it is doing; waits for it (the UI's only wait).
void stop_worker(worker_state& w);
// ++generation and posts the spec; returns the new generation. Unless `approved`, a request whose
// estimate (generators/estimate.h) is over w.node_budget is not grown but answered with over_budget.
uint32_t post_request(worker_state& w, const tree_spec& spec, const mesh_params& mesh_settings, bool approved = false);
// Cancels the growth in progress and any pending request (nothing is published for them); returns
// the new generation: results older than it are stale.
uint32_t cancel_growth(worker_state& w);
// The newest published result if it is newer than `seen_generation`, else nullptr. Never blocks on work.
std::shared_ptr<const grow_result> take_result(worker_state& w, uint32_t seen_generation);
// The overlays of `shown` (a result without them) once the worker has built them, else nullptr.
std::shared_ptr<const overlay_geometry> take_late_overlays(worker_state& w, const grow_result& shown);

// ---- The LOD chain of a shown tree (render/mesh/lod.h build_lods: about half a second for a forest),
// built off the UI thread so that no frame waits for it. The newest request wins: a build in
// progress finishes, but only the newest request's chain is handed out.
struct lod_request {
  uint32_t id = 0;
  std::shared_ptr<const tree_skeleton> skeleton;
  std::shared_ptr<const tree_mesh> mesh;   // LOD0, which the chain reduces
  mesh_params mesh_settings;
  lod_params params;
};

struct lod_result {
  uint32_t id = 0;
  std::shared_ptr<const lod_chain> chain;
  double build_ms = 0;
};

// One thread, started by the first request and stopped (after the build in progress) with the
// worker.
struct lod_worker {
  std::thread thread;
  std::mutex mutex;
  std::condition_variable wake, built;
  std::optional<lod_request> pending;
  std::shared_ptr<const lod_result> published;
  uint32_t posted = 0;   // the newest request's id
  bool quit = false;
  lod_worker() = default;
  lod_worker(const lod_worker&) = delete;
  lod_worker& operator=(const lod_worker&) = delete;
  ~lod_worker();
};

// Asks for the chain of mesh `m` (of skeleton `t`); returns the request's id. Never blocks on a build.
uint32_t post_lod_request(lod_worker& w, std::shared_ptr<const tree_skeleton> t, std::shared_ptr<const tree_mesh> m,
                          const mesh_params& mp, const lod_params& p);
// The newest request's chain once it is built (handed out once), else nullptr. Never blocks on a build.
std::shared_ptr<const lod_result> take_lod_result(lod_worker& w);
// Waits up to `timeout_ms` until request `id`'s chain is built, without taking it (tests).
bool wait_lod_result(lod_worker& w, uint32_t id, double timeout_ms);

}  // namespace sylva
