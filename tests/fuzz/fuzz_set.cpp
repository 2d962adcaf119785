// libFuzzer: `--set` assignments (sweeps included) on each generator's default preset; the result
// must always save as valid JSON that loads back equal.
#include <cstdint>
#include <string>
#include <vector>

#include "tests/fuzz/fuzz_common.h"

using namespace sylva;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1 || size > 8192) return 0;
  preset p;
  p.spec.params = default_params(data[0] % generator_count);
  std::string_view rest(reinterpret_cast<const char*>(data) + 1, size - 1);
  // One assignment per line, as repeated --set arguments would give them.
  while (!rest.empty()) {
    const size_t nl = rest.find('\n');
    const std::string_view line = rest.substr(0, nl);
    rest = nl == std::string_view::npos ? std::string_view() : rest.substr(nl + 1);
    std::vector<std::string> values;
    const preset before = p;
    if (!expand_param_sweep(p, line, values).empty()) {
      fuzz_check(values.empty(), "a refused sweep adds nothing");
      continue;
    }
    fuzz_check(!values.empty() && values.size() <= 100000, "a sweep has 1..100000 values");
    for (const std::string& v : values) {
      // A keyframe (key@step=value) is checked when it is set, after the --set before it, so the
      // sweep passes it through unchecked; refused, it must leave the preset as it was.
      const preset prior = p;
      const std::string e = set_preset_param(p, v);
      if (e.empty()) continue;
      const size_t eq = v.find('=');
      fuzz_check(v.substr(0, eq).find('@') != std::string::npos, "validated values apply");
      fuzz_check(p == prior, "a refused keyframe changes nothing");
    }
    (void)before;
  }
  const std::string saved = save_preset_json(p);
  preset q;
  const load_result r = load_preset_json(saved, q);
  fuzz_check(r.ok, "a preset changed by --set saves and loads");
  fuzz_check(p == q, "--set result round-trips");
  return 0;
}
