// libFuzzer: the keyframe and cut lists of a preset ("keyframes": [...], "cuts": [...]) on each
// generator; a list that loads must save and load back equal, and the tree must grow (small) with
// its phases and cuts applied, its mesh valid.
#include <cstdint>
#include <string>

#include "tests/fuzz/fuzz_common.h"

using namespace sylva;

// Input: one byte for the generator, then the keyframes' JSON text, a newline, the cuts' JSON text.
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1 || size > 8192) return 0;
  preset base;
  base.spec.params = default_params(data[0] % generator_count);
  const std::string_view rest(reinterpret_cast<const char*>(data) + 1, size - 1);
  const size_t nl = rest.find('\n');
  std::string keys(rest.substr(0, nl)), cuts(nl == std::string_view::npos ? "" : rest.substr(nl + 1));
  if (keys.empty()) keys = "[]";
  if (cuts.empty()) cuts = "[]";
  const std::string text = std::string("{\"sylva_preset\": 1, \"generator\": \"") + generator_name(base.spec) +
                           "\", \"keyframes\": " + keys + ", \"cuts\": " + cuts + "}";
  preset p;
  const load_result r = load_preset_json(text, p);
  if (!r.ok) {
    fuzz_check(!r.error.empty(), "a failed load says why");
    return 0;
  }
  const std::string saved = save_preset_json(p);
  preset q;
  const load_result r2 = load_preset_json(saved, q);
  fuzz_check(r2.ok, "a preset with phases and cuts saves and loads");
  fuzz_check(p == q, "keyframe and cut round trip is exact");
  grow_small_and_check(p);
  return 0;
}
