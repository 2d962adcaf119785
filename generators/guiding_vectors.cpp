// Guiding-vector shortest-path trees (Xu & Mould 2015).
#include "generators/guiding_vectors.h"

namespace sylva {

tree_skeleton grow_guiding_vectors(const guiding_vectors_params& p, const grow_options& o, grow_report* report, growth_debug*) {
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
