// Growth budgets: a capped, time-limited trial growth and its extrapolation (estimate.h).
#include "generators/estimate.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "generators/keyframes.h"
#include "generators/pruning.h"
#include "generators/timing.h"

namespace sylva {

double extrapolate_nodes(const std::vector<double>& born, int complete_steps, int total_steps, double cap,
                         double* node_steps) {
  const int k = std::min(complete_steps, int(born.size()) - 1);
  double n = 0;
  double sum = 0;   // Σ over steps of the nodes standing then
  for (int s = 0; s <= k; ++s) sum += (n += born[size_t(s)]);
  if (node_steps) *node_steps = sum;
  if (k < 0) return 0;
  const int remaining = total_steps - k;
  if (remaining <= 0) return std::min(n, cap);
  // Step-to-step log ratios of the increments over the last (up to) three steps. Healthy growth
  // turns from exponential to linear as the crown fills (the ratio falls toward 1); a runaway keeps
  // its ratio. So the log ratio goes on falling at its recent rate, down to 0 (a constant increment).
  std::vector<double> logs;   // newest first
  for (int s = k; s >= 1 && logs.size() < 3; --s) {
    if (born[size_t(s - 1)] <= 0) break;
    logs.push_back(std::log(std::max(born[size_t(s)], 0.5) / born[size_t(s - 1)]));
  }
  double log_q = logs.empty() ? std::log(2.0) : logs.front();
  double slope = logs.size() >= 2 ? (logs.front() - logs.back()) / double(logs.size() - 1) : 0.0;
  slope = std::min(slope, 0.0);
  const double floor = std::min(log_q, 0.0);   // already shrinking increments keep shrinking
  log_q = std::min(log_q, std::log(4.0));
  double d = std::max(born[size_t(k)], 1.0);
  for (int s = 0; s < remaining && n < cap; ++s) {
    log_q = std::max(log_q + slope, floor);
    d *= std::exp(log_q);
    n = std::min(n + d, cap);
    sum += n;
  }
  if (node_steps) *node_steps = sum;
  return std::min(n, cap);
}

namespace {

// What a trial saw, to read its node count at any step.
struct trial_curve {
  int reached = 0;             // the last step the trial grew into (partial)
  std::vector<double> born;    // nodes born per step in the trial
  double cap = 0, whole = 0;   // the real node cap; the trial's node count
  bool extrapolated = false;
  // Nodes standing by the end of step `s`: counted where the trial has complete steps, extrapolated after.
  double at(int s) const {
    if (!extrapolated) {
      double n = 0;
      for (int i = 0; i <= s && i < int(born.size()); ++i) n += born[size_t(i)];
      return n;
    }
    if (s <= reached - 1) {
      double n = 0;
      for (int i = 0; i <= s; ++i) n += born[size_t(i)];
      return n;
    }
    return std::max(extrapolate_nodes(born, reached - 1, s, cap), s >= reached ? whole : 0.0);
  }
};

// One trial of `spec` and its extrapolation.
growth_estimate estimate_one(const tree_spec& spec, const grow_options& o, const estimate_limits& limits, trial_curve& curve) {
  growth_estimate e;
  curve = trial_curve{};
  tree_spec trial = spec;
  int64_t real_node_cap = 0, real_module_cap = 0, trial_node_cap = 0, trial_module_cap = 0;
  std::visit(
      [&](auto& p) {
        real_node_cap = p.node_cap;
        p.node_cap = int(std::min<int64_t>(p.node_cap, limits.trial_nodes));
        trial_node_cap = p.node_cap;
        if constexpr (std::is_same_v<std::decay_t<decltype(p)>, lsystem_params>) {
          real_module_cap = p.module_cap;
          p.module_cap = int(std::min<int64_t>(p.module_cap, limits.trial_nodes * 8));
          trial_module_cap = p.module_cap;
        }
      },
      trial.params);
  std::atomic<uint32_t> stop{0};
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed_ms = [&] { return ms_since(t0); };
  grow_options to;
  to.steps = o.steps;
  to.cancel = &stop;
  to.cancel_value = 0;
  // Generators report progress once per step: the time limit and the caller's cancel are checked there.
  to.progress = [&](float f) {
    if (o.progress) o.progress(f);
    if (o.cancelled() || elapsed_ms() > limits.trial_ms) stop.store(1);
  };
  e.trial = grow(trial, to, &e.report, &e.debug);
  e.trial_ms = elapsed_ms();
  e.cancelled = o.cancelled();
  const bool timed_out = stop.load() != 0 && !e.cancelled;
  const bool node_capped = e.report.hit_node_cap && trial_node_cap < real_node_cap;
  const bool module_capped = e.report.stop == grow_stop::module_cap && trial_module_cap < real_module_cap;
  e.exact = !e.cancelled && !timed_out && !node_capped && !module_capped;
  e.uncertain = !e.exact && !e.cancelled && !node_capped && !module_capped;
  const double n = double(e.trial.size());
  double ms_per_node = e.trial_ms / std::max(n, 1.0);
  curve.whole = n;
  curve.cap = double(real_node_cap);
  for (size_t i = 0; i < e.trial.size(); ++i) {
    const int b = e.trial.born[i];
    if (b >= int(curve.born.size())) curve.born.resize(size_t(b) + 1, 0);
    curve.born[size_t(b)] += 1;
  }
  curve.reached = int(curve.born.size()) - 1;
  if (e.exact) {
    e.nodes = n;
  } else {
    const int total = o.steps >= 0 ? o.steps : default_steps(spec.params);
    std::vector<double> born;
    int last = -1;
    for (size_t i = 0; i < e.trial.size(); ++i) {
      const int b = e.trial.born[i];
      if (b >= int(born.size())) born.resize(size_t(b) + 1, 0);
      born[size_t(b)] += 1;
      last = std::max(last, b);
    }
    // The last step reached is partial. With no full step to go by the estimate is what the trial
    // grew: the request then grows unasked, and the progress bar's Cancel is the safeguard.
    if (last >= 1) {
      // Generators visit the standing tree every step, so time goes with Σ nodes × steps.
      double trial_node_steps = 0, node_steps = 0;
      extrapolate_nodes(born, last, last, double(real_node_cap), &trial_node_steps);
      e.nodes = std::max(extrapolate_nodes(born, last - 1, total, double(real_node_cap), &node_steps), n);
      curve.extrapolated = true;
      if (trial_node_steps > 0) ms_per_node = e.trial_ms * node_steps / trial_node_steps / std::max(e.nodes, 1.0);
    } else {
      e.nodes = n;
    }
  }
  // Growth, then the mesh: about 5 µs per node with its leaves on one core.
  e.seconds = e.nodes * (ms_per_node + 0.005) / 1000.0;
  e.bytes = e.nodes * bytes_per_node;
  return e;
}

}  // namespace

growth_estimate estimate_growth(const tree_spec& spec, const grow_options& o, const estimate_limits& limits) {
  trial_curve curve;
  growth_estimate e = estimate_one(spec, o, limits, curve);
  const int reached = curve.reached;
  if (e.exact || e.cancelled || (spec.keyframes.empty() && spec.cuts.empty())) return e;
  const int total = o.steps >= 0 ? o.steps : default_steps(spec.params);
  // The growth phases the trial did not reach: the distinct keyframe steps after `reached`.
  std::vector<int> phases;
  for (const keyframe& k : spec.keyframes)
    if (k.step > reached && k.step <= total && (phases.empty() || phases.back() != k.step)) phases.push_back(k.step);
  std::sort(phases.begin(), phases.end());
  phases.erase(std::unique(phases.begin(), phases.end()), phases.end());
  if (int(phases.size()) > max_phase_trials) {   // evenly chosen, the last phase kept
    std::vector<int> chosen;
    for (int i = 0; i < max_phase_trials; ++i)
      chosen.push_back(phases[size_t((i + 1) * phases.size() / max_phase_trials - 1)]);
    phases = chosen;
  }
  double real_node_cap = 0;
  std::visit([&](const auto& p) { real_node_cap = double(p.node_cap); }, spec.params);
  bool certain = !e.uncertain;
  for (int step : phases) {
    tree_spec phase = spec;
    std::visit([&](auto& p) { p = params_at_step(p, spec.keyframes, step); }, phase.params);
    phase.keyframes.clear();
    phase.cuts.clear();
    grow_options po;
    po.steps = total;
    po.cancel = o.cancel;
    po.cancel_value = o.cancel_value;
    trial_curve phase_curve;
    const growth_estimate pe = estimate_one(phase, po, limits, phase_curve);
    if (pe.cancelled) {
      e.cancelled = true;
      return e;
    }
    ++e.phase_trials;
    e.trial_ms += pe.trial_ms;
    certain = certain || !pe.uncertain;
    // The tree as grown up to step k − 1, then what the phase's params grow from step k to the end
    // on a tree grown with them from the start (larger when they raise growth: conservative; when
    // they lower it, the unkeyed estimate stays the larger).
    const double before = curve.at(step - 1);
    const double phase_nodes =
        std::min(before + std::max(phase_curve.at(total) - phase_curve.at(step - 1), 0.0), std::max(curve.cap, before));
    if (phase_nodes > e.nodes) {
      e.seconds *= phase_nodes / std::max(e.nodes, 1.0);
      e.nodes = phase_nodes;
    }
  }
  std::vector<int> cut_steps;
  for (const prune_cut& c : spec.cuts)
    if (c.step > reached && c.step <= total) cut_steps.push_back(c.step);
  std::sort(cut_steps.begin(), cut_steps.end());
  e.cut_steps = int(std::unique(cut_steps.begin(), cut_steps.end()) - cut_steps.begin());
  if (e.cut_steps > 0) {
    const double grown = e.nodes;
    e.nodes = std::min(e.nodes * (1 + e.cut_steps), std::max(real_node_cap, grown));
    e.seconds *= e.nodes / std::max(grown, 1.0);
  }
  e.uncertain = !certain;
  e.bytes = e.nodes * bytes_per_node;
  if (e.phase_trials > 0 || e.cut_steps > 0) {
    e.note = "counted conservatively:";
    if (e.phase_trials > 0)
      e.note += " the largest of the growth phases from step " + std::to_string(phases.front()) + " on (" +
                std::to_string(e.phase_trials) + " more trial" + (e.phase_trials > 1 ? "s" : "") + ")";
    if (e.cut_steps > 0)
      e.note += std::string(e.phase_trials > 0 ? ";" : "") + " regrowth after cuts in " + std::to_string(e.cut_steps) +
                " later step" + (e.cut_steps > 1 ? "s" : "");
  }
  return e;
}

}  // namespace sylva
