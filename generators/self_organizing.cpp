// Self-organizing trees (Palubicki et al. 2009) with the extensions of seed 001.
#include "generators/self_organizing.h"

namespace sylva {

tree_skeleton grow_self_organizing(const self_organizing_params& p, const grow_options& o, grow_report* report, growth_debug*) {
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
