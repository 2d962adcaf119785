// libFuzzer: edit sequences as the editor makes them (tests/edit_sequence.h: sliders, Growth steps,
// keys at a step, "from this step on", marker drags, cuts, deletes) on each generator; after every
// edit the document saves and loads back equal, a refused edit changes nothing, and the final
// document grows (small) and meshes.
#include <cstdint>
#include <cstdio>
#include <string>

#include "tests/edit_sequence.h"
#include "tests/fuzz/fuzz_common.h"

using namespace sylva;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1 || size > 4096) return 0;
  preset p;
  p.spec.params = default_params(data[0] % generator_count);
  const std::string broken = sylva_test::run_edit_sequence(p, data + 1, size - 1);
  if (!broken.empty()) std::fprintf(stderr, "%s", broken.c_str());
  fuzz_check(broken.empty(), "every edit leaves a document that saves and loads back equal");
  grow_small_and_check(p);
  return 0;
}
