// Self-organizing trees (Palubicki et al. 2009) with the extensions of seed 001.
#pragma once

#include "generators/params.h"
#include "generators/skeleton.h"

namespace sylva {

struct self_organizing_params {
  int steps = 20;
  int node_cap = 2000000;
  bool operator==(const self_organizing_params&) const = default;
};

template <params_of<self_organizing_params> P, class V>
void visit_params(P& p, V&& v) {
  v(p.steps, param_info{"steps", "Growth steps", "N", 0, 200, "Number of growth steps (iterations)", param_on_release, "Growth"});
  v(p.node_cap, param_info{"node_cap", "Node cap", "", 1000, 20000000, "Growth stops at this many nodes and says so", param_log | param_advanced});
}

tree_skeleton grow_self_organizing(const self_organizing_params& p, const grow_options& o, grow_report* report = nullptr,
                  growth_debug* debug = nullptr);

}  // namespace sylva
