// libFuzzer: L-system text -> compiler -> derivation -> turtle, with small caps.
#include <cmath>
#include <cstdint>
#include <string>

#include "generators/lsystem_engine.h"
#include "tests/fuzz/fuzz_common.h"

using namespace sylva;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 4096) return 0;  // long texts add nothing the caps do not already bound
  lsystem_params p;
  p.mode = lsystem_mode::text;
  p.source.assign(reinterpret_cast<const char*>(data), size);
  p.derivations = size ? data[0] % 6 : 3;
  p.module_cap = 5000;
  p.node_cap = 2000;
  grow_report report;
  const tree_skeleton t = grow(tree_spec{p, 1}, grow_options{}, &report);
  fuzz_check(t.parent.size() == t.position.size(), "skeleton arrays agree");
  for (size_t i = 0; i < t.size(); ++i) {
    fuzz_check(t.parent[i] < int32_t(i), "parent precedes child");
    fuzz_check(std::isfinite(t.position[i].x + t.position[i].y + t.position[i].z) || report.error,
               "finite positions");
  }
  lsystem_inspection ins = inspect_lsystem(p.source, p.derivations, 50, 1, 5000);
  (void)ins;
  return 0;
}
