// L-system dispatch: Honda's model, or a general L-system text.
#include "generators/lsystem.h"

namespace sylva {

tree_skeleton grow_lsystem(const lsystem_params& p, const grow_options& o, grow_report* report, growth_debug*) {
  if (p.mode == lsystem_mode::honda) return grow_honda(p, o, report);
  tree_skeleton t;
  t.add_node(glm::vec3(0), -1, 0.05f, 0, 0);
  if (report) {
    report->message = "general L-system texts are not implemented yet";
    report->error = true;
  }
  return t;
}

}  // namespace sylva
