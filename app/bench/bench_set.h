// `sylva bench --set KEY=VALUE` (repeatable): the assignments of `sylva export --set`, applied to
// every preset benched after it is loaded (e.g. `--set render.wind=true` to time the wind's cost).
#pragma once

#include <string>
#include <vector>

namespace sylva {

struct preset;

// Checks the assignments' form before anything is measured: each is key=value or key@STEP=value,
// a keyframe's key@STEP at most once. Sweeps (key=a:b:n) are refused per preset by apply_bench_sets.
// Returns "" or the error; on success they are kept for apply_bench_sets.
std::string set_bench_sets(const std::vector<std::string>& sets);

// Applies the kept assignments to a loaded preset with export's checks (set_preset_param after
// expand_param_sweep, one value each). Returns "" or the error; on an error `p` may be partly set.
std::string apply_bench_sets(preset& p);

// Loads one preset for a bench mode: its warnings go to stderr, then the kept assignments are
// applied. On a failure prints "sylva CMD: PATH: why" and returns false (the caller counts it).
bool load_bench_preset(const char* cmd, const std::string& path, preset& p);

// The kept assignments joined by ", " ("" when none), for the bench's footer.
std::string bench_sets_label();

}  // namespace sylva
