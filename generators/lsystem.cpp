// L-system dispatch: Honda's model, or a general L-system text.
#include "generators/lsystem.h"
#include "generators/lsystem_engine.h"

namespace sylva {

tree_skeleton grow_lsystem(const lsystem_params& p, const grow_options& o, grow_report* report, growth_debug*) {
  if (p.mode == lsystem_mode::honda) return grow_honda(p, o, report);
  return grow_lsystem_text(p, o, report);
}

}  // namespace sylva
