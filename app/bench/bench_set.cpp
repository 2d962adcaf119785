// `sylva bench --set`: the CLI's assignments, kept for the bench loops (app/bench/bench.cpp and friends).
#include "app/bench/bench_set.h"

#include <algorithm>
#include <cstdio>

#include "app/common/messages.h"
#include "render/io/preset.h"

namespace sylva {

namespace {
std::vector<std::string>& kept() {
  static std::vector<std::string> sets;   // the CLI sets these once, before any bench runs
  return sets;
}
}  // namespace

std::string set_bench_sets(const std::vector<std::string>& sets) {
  std::vector<std::string> keyed;
  for (const std::string& set : sets) {
    const size_t eq = set.find('=');
    if (eq == std::string::npos || eq == 0) return "--set expects key=value, got \"" + set + "\"";
    if (const size_t at = set.find('@'); at != std::string::npos && at < eq) {
      std::string key_at = set.substr(0, eq);
      if (key_at.rfind("params.", 0) == 0) key_at.erase(0, 7);
      if (std::find(keyed.begin(), keyed.end(), key_at) != keyed.end())
        return "--set " + key_at + " is given twice: two values for one key at one step contradict each other";
      keyed.push_back(key_at);
    }
  }
  kept() = sets;
  return "";
}

std::string apply_bench_sets(preset& p) {
  for (const std::string& set : kept()) {
    std::vector<std::string> values;
    if (std::string e = expand_param_sweep(p, set, values); !e.empty()) return e;
    if (values.size() != 1)
      return "--set " + set + ": bench takes one value per key (a sweep is for export; run bench once per value)";
    if (std::string e = set_preset_param(p, values.front()); !e.empty()) return e;
  }
  return "";
}

std::string bench_sets_label() {
  std::string s;
  for (const std::string& set : kept()) s += (s.empty() ? "" : ", ") + set;
  return s;
}

bool load_bench_preset(const char* cmd, const std::string& path, preset& p) {
  const load_result loaded = load_preset_file(path, p);
  std::string why = loaded.ok ? "" : loaded.error;
  if (loaded.ok) {
    for (const std::string& w : loaded.warnings) warn(path, w);
    why = apply_bench_sets(p);
  }
  if (why.empty()) return true;
  if (why.find(path) == std::string::npos) why = path + ": " + why;
  std::fprintf(stderr, "sylva %s: %s\n", cmd, why.c_str());
  return false;
}

}  // namespace sylva
