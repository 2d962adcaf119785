// Space colonization (Runions, Lane & Prusinkiewicz 2007).
#pragma once

#include "generators/params.h"
#include "generators/skeleton.h"

namespace sylva {

struct space_colonization_params {
  int steps = 20;
  int node_cap = 2000000;
  bool operator==(const space_colonization_params&) const = default;
};

template <params_of<space_colonization_params> P, class V>
void visit_params(P& p, V&& v) {
  v(p.steps, param_info{"steps", "Growth steps", "N", 0, 200, "Number of growth steps (iterations)", param_on_release, "Growth"});
  v(p.node_cap, param_info{"node_cap", "Node cap", "", 1000, 20000000, "Growth stops at this many nodes and says so", param_log | param_advanced});
}

tree_skeleton grow_space_colonization(const space_colonization_params& p, const grow_options& o, grow_report* report = nullptr,
                  growth_debug* debug = nullptr);

}  // namespace sylva
