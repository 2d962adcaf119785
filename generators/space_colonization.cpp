// Space colonization (Runions, Lane & Prusinkiewicz 2007).
#include "generators/space_colonization.h"

namespace sylva {

tree_skeleton grow_space_colonization(const space_colonization_params& p, const grow_options& o, grow_report* report, growth_debug*) {
  (void)p;
  (void)o;
  tree_skeleton t;
  t.add_node(glm::vec3(0), -1, 0.05f, 0, 0);
  if (report) {
    report->message = "this generator is not implemented yet";
    report->error = true;
  }
  return t;
}

}  // namespace sylva
