// Growth worker: grows and meshes off the UI thread; publishes immutable results.
#include "app/common/worker.h"
#include "app/common/wake.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <new>

#include "generators/memory_bound.h"
#include "generators/resume.h"
#include "generators/timing.h"
#include "render/io/mesh_bound.h"

namespace sylva {

namespace {

// A growth too large for memory: the tree on screen stays (the previous result, re-published under
// the new generation) and the status bar says why. The worker's own `last` stays the good result.
// With `over_budget`, not a failure: the request was not grown because its estimate is over the budget.
// With `mesh`, the refusal of a mesh over the mesh budget (why: mesh_budget_refusal's line).
void publish_failure(worker_state& w, const std::shared_ptr<const grow_result>& last, const worker_request& req,
                     const std::string& why, const growth_estimate* over_budget = nullptr,
                     const mesh_estimate* mesh = nullptr) {
  std::shared_ptr<const grow_result> keep;
  try {
    auto r = std::make_shared<grow_result>();
    if (last) {
      r->skeleton = last->skeleton;
      r->debug = last->debug;
      r->overlays = last->overlays;
      r->mesh = last->mesh;
      r->spec = last->spec;
      r->mesh_settings = last->mesh_settings;
    } else {
      r->skeleton = std::make_shared<tree_skeleton>();
    }
    r->generation = req.generation;
    if (over_budget) {
      r->over_budget = true;
      r->estimated_nodes = over_budget->nodes;
      r->estimated_seconds = over_budget->seconds;
      r->estimated_bytes = over_budget->bytes;
      r->estimate_note = over_budget->note;
      r->mesh_over_budget = why;
      r->report = last ? last->report : grow_report{};
    } else {
      r->report.error = true;
      r->report.message = why;
    }
    if (mesh) {
      r->over_mesh_budget = true;
      r->mesh_bound_bytes = mesh->total_bytes();
      r->mesh_fit_segments = mesh_fit_segments(*mesh, req.mesh_settings);
    }
    keep = std::move(r);
  } catch (const std::bad_alloc&) {
    // Not even the copy fits: publish nothing; the UI keeps what it shows.
  }
  std::lock_guard<std::mutex> lock(w.mutex);
  if (keep) w.published = std::move(keep);
  w.busy = false;
  wake_ui();
}

// The largest class of the parameters of one params struct that differ between a and b, or
// `none` when none does. Each visited value is a member of a (nested structs included), so the
// same offset in b holds the other value.
template <class P>
std::optional<param_class> changed_class(const P& a, const P& b) {
  std::optional<param_class> out;
  visit_params(a, [&](const auto& value, const param_info& info) {
    using T = std::remove_cvref_t<decltype(value)>;
    const std::ptrdiff_t at = reinterpret_cast<const char*>(&value) - reinterpret_cast<const char*>(&a);
    const T& other = *reinterpret_cast<const T*>(reinterpret_cast<const char*>(&b) + at);
    if (!(value == other)) out = std::max(out.value_or(param_class::render), class_of(info));
  });
  return out;
}

}  // namespace

param_class edit_class(const tree_spec& a, const mesh_params& ma, const tree_spec& b, const mesh_params& mb) {
  param_class c = param_class::render;
  if (!(a == b)) {
    if (a.params.index() != b.params.index() || a.seed != b.seed || a.keyframes != b.keyframes || a.cuts != b.cuts)
      return param_class::regrow;
    std::optional<param_class> g = std::visit(
        [&](const auto& pa) { return changed_class(pa, std::get<std::remove_cvref_t<decltype(pa)>>(b.params)); }, a.params);
    std::optional<param_class> wd = changed_class(a.wood, b.wood);
    if (!g && !wd) return param_class::regrow;   // a difference no declared parameter explains
    c = std::max({c, g.value_or(c), wd.value_or(c)});
  }
  if (!(ma == mb)) c = std::max(c, changed_class(ma, mb).value_or(param_class::remesh));
  return c;
}

std::string edit_timing_text(param_class edit, const grow_result* r, double upload_ms) {
  const std::string name = param_class_names[int(edit)];
  if (edit == param_class::render || !r) return name + ": no grow, no mesh, no upload";
  char text[160];
  if (edit == param_class::remesh || !r->regrown)
    std::snprintf(text, sizeof text, "%s: grow kept, mesh %.1f ms, upload %.1f ms", name.c_str(), r->mesh_ms, upload_ms);
  else
    std::snprintf(text, sizeof text, "%s: grow %.1f ms, mesh %.1f ms, upload %.1f ms", name.c_str(), r->grow_ms, r->mesh_ms,
                  upload_ms);
  return text;
}

namespace {

void run_worker(worker_state& w) {
  std::shared_ptr<const grow_result> last;   // the worker's own previous result, for skeleton reuse
  // The states recorded at the keyframe steps of the last growth (Honda, self-organizing, space
  // colonization; generators/resume.h): an edit of keyframes from step k on resumes at k.
  growth_resume resume;
  tree_spec resume_spec;
  bool have_resume = false;
  // w.late_overlays and w.late_overlays_from are written only here (under the lock, for the UI),
  // so this thread reads them without it.
  for (;;) {
    worker_request req;
    {
      std::unique_lock<std::mutex> lock(w.mutex);
      const bool overlays_due = last && !last->overlays && last->debug && w.late_overlays_from != last->debug;
      w.wake.wait(lock, [&] { return w.quit || w.pending || overlays_due; });
      if (w.quit) return;
      if (!w.pending) {   // idle, and the tree out has no overlays yet: build them now
        lock.unlock();
        std::shared_ptr<const overlay_geometry> geo;
        try {
          geo = std::make_shared<overlay_geometry>(build_overlays(*last->debug, last->skeleton.get()));
        } catch (const std::bad_alloc&) {
          geo = std::make_shared<overlay_geometry>();   // none, rather than a crash; the tree stays
        }
        lock.lock();
        w.late_overlays = std::move(geo);
        w.late_overlays_from = last->debug;
        wake_ui();
        continue;
      }
      req = std::move(*w.pending);
      w.pending.reset();
      w.busy = true;
    }
    auto result = std::make_shared<grow_result>();
    result->generation = req.generation;
    result->spec = req.spec;
    result->mesh_settings = req.mesh_settings;
    // What the edit needs, from the classes its parameters declare (generators/params.h).
    const param_class need = last && !last->report.cancelled
                                 ? edit_class(last->spec, last->mesh_settings, req.spec, req.mesh_settings)
                                 : param_class::regrow;
    result->edit = need;
    w.meshing = need != param_class::regrow;
    if (need != param_class::regrow) {
      // Nothing the generator reads changed: the tree is the same, so skip growth.
      result->skeleton = last->skeleton;
      result->debug = last->debug;
      // A re-mesh of the same growth carries its overlays, built with it or after it.
      result->overlays = last->overlays ? last->overlays : w.late_overlays_from == last->debug ? w.late_overlays : nullptr;
      result->report = last->report;
      result->grow_ms = last->grow_ms;
      result->regrown = false;
    } else {
      grow_options o;
      o.cancel = &w.generation;
      o.cancel_value = req.generation;
      auto debug = std::make_shared<growth_debug>();
      auto t0 = std::chrono::steady_clock::now();
      std::shared_ptr<tree_skeleton> skeleton;
      w.progress = 0;
      o.progress = [&w](float f) { w.progress.store(f, std::memory_order_relaxed); };
      const int changed = have_resume && can_resume(req.spec) ? first_changed_step(resume_spec, req.spec) : 0;
      const bool resumable = changed >= 1 && changed != INT_MAX;
      try {
        if (resumable) {
          // Only keyframes from step `changed` on differ from the recorded growth: the node cap and
          // derivation count are the ones that growth ran under, so no new estimate is asked for.
          have_resume = false;
          skeleton = std::make_shared<tree_skeleton>(grow_resumable(req.spec, o, resume_spec, resume, &result->report, debug.get()));
          resume_spec = req.spec;
          have_resume = !result->report.cancelled;
          result->resumed_at = resume.resumed_at;
        } else {
          // A capped trial first: small trees are done by it, large ones get an estimate.
          growth_estimate est = estimate_growth(req.spec, o);
          if (est.cancelled) {
            w.busy = false;
            continue;
          }
          // The tree and its mesh as the trial foresees them (render/io/mesh_bound.h). An estimate is
          // no bound (a growth may stop sooner at another cap), so a mesh estimated over the mesh
          // budget asks as a tree over the node budget does; grown anyway, the skeleton's own
          // mesh bound decides before meshing.
          std::string mesh_over;
          if (!est.exact && !est.uncertain) {
            const mesh_estimate me = with_writer(mesh_estimate_like(est.trial, est.nodes, req.mesh_settings), nullptr);
            est.bytes = est.nodes * growth_memory_bound(req.spec).per_node + me.total_bytes();
            mesh_over = mesh_budget_refusal(me, req.mesh_settings, true);
          }
          if (!est.exact && !est.uncertain && !req.approved &&
              (est.nodes > double(w.node_budget.load()) || !mesh_over.empty())) {
            publish_failure(w, last, req, mesh_over, &est);
            continue;
          }
          if (est.exact) {
            skeleton = std::make_shared<tree_skeleton>(std::move(est.trial));
            result->report = std::move(est.report);
            *debug = std::move(est.debug);
          } else if (can_resume(req.spec)) {   // recorded, so that a later keyframe edit resumes
            have_resume = false;
            skeleton = std::make_shared<tree_skeleton>(grow_resumable(req.spec, o, tree_spec{}, resume, &result->report, debug.get()));
            resume_spec = req.spec;
            have_resume = !result->report.cancelled;
          } else {
            skeleton = std::make_shared<tree_skeleton>(grow(req.spec, o, &result->report, debug.get()));
          }
        }
      } catch (const std::bad_alloc&) {
        publish_failure(w, last, req, "out of memory while growing: lower the node cap or the step count");
        continue;
      }
      result->grow_ms = ms_since(t0);
      if (o.cancelled()) {   // a newer edit or a cancel arrived: drop this one unseen
        w.busy = false;
        continue;
      }
      result->skeleton = std::move(skeleton);   // its overlays follow once it is out (late_overlays)
      result->debug = std::move(debug);
    }
    w.meshing = true;
    auto t0 = std::chrono::steady_clock::now();
    try {
      if (need == param_class::render) {   // nothing the mesh reads changed either: keep it
        result->mesh = last->mesh;
        result->remeshed = false;
      } else {
        // Over the mesh budget nothing is meshed: the previous tree stays and the editor says why.
        const mesh_estimate me = with_writer(mesh_bound(*result->skeleton, req.mesh_settings), nullptr);   // with the upload
        if (std::string why = mesh_budget_refusal(me, req.mesh_settings); !why.empty()) {
          publish_failure(w, last, req, why, nullptr, &me);
          continue;
        }
        result->mesh = mesh_tree(*result->skeleton, req.mesh_settings, req.spec.seed);
      }
    } catch (const std::bad_alloc&) {
      publish_failure(w, last, req, "out of memory while meshing: lower the radial segments or the node cap");
      continue;
    }
    result->mesh_ms = result->remeshed ? ms_since(t0) : 0.0;
    last = result;
    {
      std::lock_guard<std::mutex> lock(w.mutex);
      w.published = std::move(result);
      w.busy = false;
    }
    wake_ui();
  }
}

}  // namespace

void start_worker(worker_state& w) {
  w.quit = false;
  w.thread = std::thread(run_worker, std::ref(w));
}

void stop_worker(worker_state& w) {
  {
    std::lock_guard<std::mutex> lock(w.mutex);
    w.quit = true;
  }
  ++w.generation;   // cancels a growth in progress
  w.wake.notify_all();
  if (w.thread.joinable()) w.thread.join();
}

uint32_t post_request(worker_state& w, const tree_spec& spec, const mesh_params& mesh_settings, bool approved) {
  uint32_t g;
  {
    std::lock_guard<std::mutex> lock(w.mutex);
    g = ++w.generation;
    w.pending = worker_request{g, spec, mesh_settings, approved};
  }
  w.wake.notify_one();
  return g;
}

uint32_t cancel_growth(worker_state& w) {
  std::lock_guard<std::mutex> lock(w.mutex);
  w.pending.reset();
  return ++w.generation;
}

std::shared_ptr<const grow_result> take_result(worker_state& w, uint32_t seen_generation) {
  std::lock_guard<std::mutex> lock(w.mutex);
  if (w.published && w.published->generation != seen_generation) return w.published;
  return nullptr;
}

std::shared_ptr<const overlay_geometry> take_late_overlays(worker_state& w, const grow_result& shown) {
  std::lock_guard<std::mutex> lock(w.mutex);
  if (shown.overlays || !shown.debug || w.late_overlays_from != shown.debug) return nullptr;
  return w.late_overlays;
}

// ---------------------------------------------------------------- LOD chains

namespace {

void run_lod_worker(lod_worker& w) {
  for (;;) {
    lod_request req;
    {
      std::unique_lock<std::mutex> lock(w.mutex);
      w.wake.wait(lock, [&] { return w.quit || w.pending.has_value(); });
      if (w.quit) return;
      req = std::move(*w.pending);
      w.pending.reset();
    }
    auto r = std::make_shared<lod_result>();
    r->id = req.id;
    const auto t0 = std::chrono::steady_clock::now();
    r->chain = std::make_shared<const lod_chain>(build_lods(*req.skeleton, *req.mesh, req.mesh_settings, req.params));
    r->build_ms = ms_since(t0);
    {
      std::lock_guard<std::mutex> lock(w.mutex);
      w.published = std::move(r);
    }
    w.built.notify_all();
    wake_ui();
  }
}

}  // namespace

lod_worker::~lod_worker() {
  {
    std::lock_guard<std::mutex> lock(mutex);
    quit = true;
  }
  wake.notify_all();
  if (thread.joinable()) thread.join();
}

uint32_t post_lod_request(lod_worker& w, std::shared_ptr<const tree_skeleton> t, std::shared_ptr<const tree_mesh> m,
                          const mesh_params& mp, const lod_params& p) {
  uint32_t id;
  {
    std::lock_guard<std::mutex> lock(w.mutex);
    id = ++w.posted;
    w.pending = lod_request{id, std::move(t), std::move(m), mp, p};
    if (!w.thread.joinable()) w.thread = std::thread(run_lod_worker, std::ref(w));
  }
  w.wake.notify_one();
  return id;
}

std::shared_ptr<const lod_result> take_lod_result(lod_worker& w) {
  std::lock_guard<std::mutex> lock(w.mutex);
  if (!w.published) return nullptr;
  std::shared_ptr<const lod_result> r = std::move(w.published);
  w.published.reset();
  return r->id == w.posted ? r : nullptr;   // an older request's chain is dropped
}

bool wait_lod_result(lod_worker& w, uint32_t id, double timeout_ms) {
  std::unique_lock<std::mutex> lock(w.mutex);
  return w.built.wait_for(lock, std::chrono::duration<double, std::milli>(timeout_ms),
                          [&] { return w.published && w.published->id == id; });
}

}  // namespace sylva
