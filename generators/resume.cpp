// Resuming a regrow from a recorded step (resume.h).
#include "generators/resume.h"

#include <algorithm>

#include "generators/keyframes.h"
#include "generators/lsystem.h"
#include "generators/pruning.h"

namespace sylva {

int first_changed_step(const tree_spec& a, const tree_spec& b) {
  if (!(a.params == b.params) || a.seed != b.seed || !(a.wood == b.wood) || !(a.cuts == b.cuts)) return 0;
  int first = INT_MAX;
  // Keyframes are compared step by step: the lists of one step, in order (a step's keys apply in
  // list order, so a reordering is a change of that step).
  auto at = [](const std::vector<keyframe>& ks, int step) {
    std::vector<keyframe> out;
    for (const keyframe& k : ks)
      if (k.step == step) out.push_back(k);
    return out;
  };
  for (const std::vector<keyframe>* list : {&a.keyframes, &b.keyframes})
    for (const keyframe& k : *list)
      if (k.step < first && at(a.keyframes, k.step) != at(b.keyframes, k.step)) first = k.step;
  return first;
}

bool can_resume(const tree_spec& spec) {
  if (std::holds_alternative<self_organizing_params>(spec.params) ||
      std::holds_alternative<space_colonization_params>(spec.params))
    return true;
  const auto* p = std::get_if<lsystem_params>(&spec.params);
  return p && p->mode == lsystem_mode::honda;
}

namespace {
// The latest recorded state at or before step k (0: none).
template <class S>
int latest_at_or_before(const std::vector<std::shared_ptr<const S>>& v, int k) {
  for (int from = int(std::min<int64_t>(k, int64_t(v.size()) - 1)); k >= 1 && from >= 1; --from)
    if (v[size_t(from)]) return from;
  return 0;
}
}  // namespace

tree_skeleton grow_resumable(const tree_spec& spec, const grow_options& o, const tree_spec& recorded, growth_resume& r,
                             grow_report* report, growth_debug* debug) {
  r.from_step = 0;
  r.resumed_at = 0;
  r.skipped = 0;
  const bool so = std::holds_alternative<self_organizing_params>(spec.params);
  const bool sc = std::holds_alternative<space_colonization_params>(spec.params);
  // Only the recording of this spec's generator is kept.
  if (!so) r.self_organizing.clear();
  if (!sc) r.space_colonization.clear();
  if (so || sc) r.honda.clear();
  if (can_resume(spec)) {
    const int k = first_changed_step(recorded, spec);
    // Step k's own state is recorded before its keyframes apply, so the latest state at or before
    // k will do; INT_MAX (no change) regrows from the last recorded step, the same tree again.
    r.from_step = so   ? latest_at_or_before(r.self_organizing, k)
                  : sc ? latest_at_or_before(r.space_colonization, k)
                       : latest_at_or_before(r.honda, k);
    r.record_steps.clear();
    for (const keyframe& kf : spec.keyframes) r.record_steps.push_back(kf.step);
    if (r.record_steps.empty()) r.record_steps.push_back(INT_MAX);   // nothing to record
  } else {
    r.honda.clear();
    r.self_organizing.clear();
    r.space_colonization.clear();
  }
  grow_options opt = o;
  opt.resume = can_resume(spec) ? &r : nullptr;
  return grow(spec, opt, report, debug);
}

}  // namespace sylva
