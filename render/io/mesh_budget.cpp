// Growth under the mesh budget (mesh_bound.h: grow_for_mesh).
#include "generators/estimate.h"
#include "render/io/mesh_bound.h"

namespace sylva {

budgeted_growth grow_for_mesh(const tree_spec& spec, const mesh_params& mesh, const export_format* format,
                              const grow_options& o) {
  budgeted_growth g;
  int64_t node_cap = 0;
  std::visit([&](const auto& p) { node_cap = p.node_cap; }, spec.params);
  const int steps = o.steps >= 0 ? o.steps : default_steps(spec.params);
  if (mesh_budget_refusal(with_writer(mesh_bound_for_nodes(double(node_cap), mesh, steps), format), mesh).empty()) {
    g.tree = grow(spec, o, &g.report);
  } else {
    growth_estimate est = estimate_growth(spec, o);
    if (est.exact) {
      g.tree = std::move(est.trial);
      g.report = std::move(est.report);
    } else if (!est.cancelled && !est.uncertain) {
      g.refusal = mesh_budget_refusal(with_writer(mesh_estimate_like(est.trial, est.nodes, mesh), format), mesh, true);
      if (!g.refusal.empty()) {
        g.estimated = true;
        return g;
      }
    }
    if (!est.exact) {
      est = growth_estimate{};   // the trial's tree and debug output go before the real growth
      g.tree = grow(spec, o, &g.report);
    }
  }
  if (!g.report.error && !g.report.cancelled) g.refusal = mesh_budget_refusal(with_writer(mesh_bound(g.tree, mesh), format), mesh);
  return g;
}

}  // namespace sylva
