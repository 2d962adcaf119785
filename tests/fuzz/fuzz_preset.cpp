// libFuzzer: preset JSON loader; a loaded preset must save, load back equal, and grow (small).
#include <cstdint>
#include <string>

#include "tests/fuzz/fuzz_common.h"

using namespace sylva;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  preset p;
  const load_result r = load_preset_json(text, p);
  if (!r.ok) {
    fuzz_check(!r.error.empty(), "a failed load says why");
    return 0;
  }
  const std::string saved = save_preset_json(p);
  fuzz_check(valid_utf8(saved), "saved preset is UTF-8");
  preset q;
  const load_result r2 = load_preset_json(saved, q);
  fuzz_check(r2.ok, "a saved preset loads");
  fuzz_check(r2.warnings.empty(), "a saved preset loads without warnings");
  fuzz_check(p == q, "save/load round trip is exact");
  grow_small_and_check(p);
  return 0;
}
