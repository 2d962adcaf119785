// Growth budgets: how large will a request grow, before growing it? A cheap trial grows
// the spec with a small node cap and a time limit; when the trial finishes under both it is the
// tree itself, otherwise the per-step node counts it reached are extrapolated to the full step count.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "generators/tree_spec.h"

namespace sylva {

struct growth_estimate {
  bool exact = false;      // the trial grew the whole tree: `trial` is the result, nothing to extrapolate
  bool cancelled = false;  // the caller's cancel fired during the trial
  bool uncertain = false;  // the trial ran out of time before its node cap: a slow start (or a busy
                           // machine) is no evidence of a large tree, so this estimate asks nothing
  double nodes = 0;        // estimated node count of the full request (what the trial grew when it
                           // did not finish a single step)
  double seconds = 0;      // estimated time to grow and mesh it
  double bytes = 0;        // estimated memory for the tree and its mesh
  tree_skeleton trial;     // the trial tree (the real tree when `exact`)
  grow_report report;      // the trial's report
  growth_debug debug;      // the trial's debug output
  double trial_ms = 0;
  // Keyframes and cuts the trial did not reach, counted conservatively; `note` says how
  // ("" when there were none): see estimate_growth.
  int phase_trials = 0;    // extra trials, one per growth phase the trial did not reach
  int cut_steps = 0;       // steps with cuts the trial did not reach
  std::string note;
};

struct estimate_limits {
  int64_t trial_nodes = 20000;   // the trial's node cap (and 8× that as its L-system module cap)
  double trial_ms = 1000;        // a safety net for slow generators (checked once per step): the node
                                 // cap, not the clock, should end a trial, so a busy machine changes nothing
};

// Rough cost per node of the tree plus its mesh on the GPU and in memory (triangles, leaves, copies).
inline constexpr double bytes_per_node = 1500;

// Grows a trial of `spec`. `o.cancel` cancels it; `o.progress` hears the trial's progress.
// When the trial stops before the last step, keyframes and cuts after the step it reached are not
// in its node counts, so they are counted conservatively:
// - each growth phase the trial did not reach (the params in effect from a later keyframe step on)
//   gets its own trial with those params from step 1, and the largest estimate is taken (at most
//   `max_phase_trials`, evenly chosen, the last phase always);
// - each later step with cuts may make the tree grow again what it grows uncut: a pruned tree keeps
//   its cut nodes in its history and regrows into the space, light and points the cut freed, so
//   the node estimate is multiplied by 1 + the number of such steps (capped at the node cap).
growth_estimate estimate_growth(const tree_spec& spec, const grow_options& o, const estimate_limits& limits = {});
inline constexpr int max_phase_trials = 4;

// Extrapolates nodes born per step (index = step) over `complete_steps` full steps to
// `total_steps`: the last increment grows on at the recent step-to-step ratio, and a falling ratio
// goes on falling (to a constant increment), so growth that is filling its crown levels off and a
// runaway one explodes. Capped at `cap`.
// `node_steps`, when given, receives Σ over the steps of the nodes standing then (time goes with it).
double extrapolate_nodes(const std::vector<double>& born_per_step, int complete_steps, int total_steps, double cap,
                         double* node_steps = nullptr);

}  // namespace sylva
