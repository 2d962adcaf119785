// Slider behaviour for the parameter panel (see editor_sliders.h).
#include "app/editor/editor_sliders.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace sylva {

bool slider_is_log(const param_info& info) {
  if (info.flags & param_log) return true;
  return info.min > 0 && info.max / info.min >= 1000;
}

float drag_speed(const param_info& info, bool fine) {
  // In value units; a log drag divides it by the range to move along its log scale, so either way
  // the whole scale takes about 600 pixels.
  const float per_pixel = std::max(info.max - info.min, 1e-6f) / 600.0f;
  return fine ? per_pixel * 0.1f : per_pixel;
}

std::string param_unit(const param_info& info) {
  if (info.flags & param_degrees) return "°";
  const char* h = info.help ? info.help : "";
  // The help names the unit in words: "(metres)", "in metres", "per metre" (a rate: no unit here).
  if (std::strstr(h, "per metre") || std::strstr(h, "per second")) return "";
  if (std::strstr(h, "(metres)") || std::strstr(h, "in metres") || std::strstr(h, "(m)") || std::strstr(h, "metres of"))
    return " m";
  if (std::strstr(h, "percent")) return "%";
  if (std::strstr(h, "(seconds)") || std::strstr(h, "in seconds")) return " s";
  return "";
}

std::string slider_format(const param_info& info) {
  std::string unit = param_unit(info);
  if (unit == "%") unit = "%%";
  if (info.flags & param_degrees) return "%.1f" + unit;
  if (slider_is_log(info)) return "%.3g" + unit;
  // Three significant digits of the range's size: 0..50 shows 0.1 steps, 0..1 shows 0.001.
  const float range = std::max(info.max - info.min, 1e-6f);
  const int digits = std::clamp(3 - int(std::ceil(std::log10(range))), 0, 4);
  char f[16];
  std::snprintf(f, sizeof f, "%%.%df", digits);
  return f + unit;
}

}  // namespace sylva
