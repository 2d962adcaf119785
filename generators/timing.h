// Wall-clock helpers for every layer: elapsed milliseconds and medians.
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

namespace sylva {

using clock_type = std::chrono::steady_clock;

inline double ms_between(clock_type::time_point a, clock_type::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}
inline double ms_since(clock_type::time_point t) { return ms_between(t, clock_type::now()); }

// The median of `v` (0 when empty): benchmarks report medians, not means.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace sylva
