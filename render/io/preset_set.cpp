// `--set KEY=VALUE` and `--set KEY=a:b:n` sweeps on a preset (render/io/preset.h): strict text ->
// value parsing, L-system #define constants and growth-phase keys.
#include "render/io/preset.h"
#include "render/io/preset_detail.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <set>

#include "generators/keyframes.h"
#include "generators/lsystem_engine.h"
#include "generators/pruning.h"

namespace sylva {
namespace {

using namespace preset_detail;

// ---------------------------------------------------------------------------------------------
// `--set`: text -> value, strict (an argument typo should stop the command, not be clamped).

bool parse_float_text(std::string_view s, float& out) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  float f = 0;
  auto r = std::from_chars(s.data(), s.data() + s.size(), f);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(f)) return false;
  out = f;
  return true;
}

std::vector<std::string_view> split(std::string_view s, char sep) {
  std::vector<std::string_view> parts;
  size_t start = 0;
  for (size_t i = 0; i <= s.size(); ++i)
    if (i == s.size() || s[i] == sep) {
      parts.push_back(s.substr(start, i - start));
      start = i + 1;
    }
  return parts;
}

bool parse_vec3_text(std::string_view s, glm::vec3& out) {
  auto parts = split(s, ',');
  if (parts.size() != 3) return false;
  glm::vec3 v;
  for (int i = 0; i < 3; ++i)
    if (!parse_float_text(parts[size_t(i)], v[i])) return false;
  out = v;
  return true;
}

template <class T>
std::string text_to_value(std::string_view s, T& out, const param_info& info) {
  if constexpr (std::is_same_v<T, float>) {
    if (!parse_float_text(s, out)) return quote_text(s) + " is not a finite number";
  } else if constexpr (std::is_same_v<T, int>) {
    float f;
    if (!parse_float_text(s, f) || f != std::floor(f) || std::fabs(f) > 2e9f)
      return quote_text(s) + " is not an integer";
    out = int(f);
  } else if constexpr (std::is_same_v<T, bool>) {
    if (s == "true" || s == "1" || s == "on" || s == "yes") out = true;
    else if (s == "false" || s == "0" || s == "off" || s == "no") out = false;
    else return quote_text(s) + " is not true or false";
  } else if constexpr (std::is_enum_v<T>) {
    const int n = option_count(info);
    std::string names;
    for (int i = 0; i < n; ++i) {
      if (s == info.options[i]) { out = T(i); return ""; }
      names += std::string(i ? ", " : "") + info.options[i];
    }
    return quote_text(s) + " is not one of " + names;
  } else if constexpr (std::is_same_v<T, glm::vec3>) {
    if (!parse_vec3_text(s, out)) return quote_text(s) + " is not x,y,z";
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (std::string e = check_text(s); !e.empty()) return e;
    out = std::string(s);
  } else if constexpr (std::is_same_v<T, std::vector<float>>) {
    std::vector<float> v;
    if (!s.empty())
      for (std::string_view part : split(s, ',')) {
        v.push_back(0);
        if (!parse_float_text(part, v.back())) return quote_text(part) + " is not a finite number";
      }
    out = std::move(v);
  } else if constexpr (std::is_same_v<T, std::vector<glm::vec3>>) {
    std::vector<glm::vec3> v;
    if (!s.empty())
      for (std::string_view part : split(s, ';')) {
        v.emplace_back(0);
        if (!parse_vec3_text(part, v.back())) return quote_text(part) + " is not x,y,z";
      }
    out = std::move(v);
  } else {
    static_assert(sizeof(T) == 0, "value type not supported by --set (see params.h)");
  }
  return check_value_limits(out);
}

// Calls f(value, info) on the parameter `key` (optionally "params.", "mesh.", "render." or "wood."
// qualified). Returns "" or why no single parameter matched.
template <class F>
std::string with_param(preset& p, std::string_view key, F&& f) {
  std::string_view only;
  for (std::string_view s : {"params", "mesh", "render", "wood"})
    if (key.size() > s.size() && key.substr(0, s.size()) == s && key[s.size()] == '.') {
      only = s;
      key.remove_prefix(s.size() + 1);
    }
  std::vector<std::string> hits;
  std::function<void()> apply;
  auto look = [&](std::string_view section, auto& params) {
    if (!only.empty() && only != section) return;
    visit_params(params, [&](auto& value, const param_info& info) {
      if (key != info.key) return;
      hits.push_back(std::string(section) + "." + info.key);
      apply = [&value, info, &f] { f(value, info); };
    });
  };
  std::visit([&](auto& gp) { look("params", gp); }, p.spec.params);
  look("mesh", p.mesh);
  look("render", p.render);
  look("wood", p.spec.wood);
  if (hits.empty())
    return "unknown parameter \"" + std::string(key) + "\" for generator " + generator_name(p.spec) +
           " (see `sylva params`)";
  if (hits.size() > 1) {
    std::string names;
    for (const std::string& h : hits) names += (names.empty() ? "" : " or ") + h;
    return quote_text(key) + " is ambiguous: write " + names;
  }
  apply();
  return "";
}

}  // namespace

namespace {
constexpr std::string_view define_prefix = "define.";
bool is_define_key(std::string_view key) {
  return key.size() > define_prefix.size() && key.substr(0, define_prefix.size()) == define_prefix;
}

// --set define.NAME=value: rewrites `#define NAME ...` in a text-mode L-system's source. The value
// must lie in the constant's [min,max] (its comment, or the editor's default range around it).
std::string set_preset_define(preset& p, std::string_view key, std::string_view text) {
  auto* lp = std::get_if<lsystem_params>(&p.spec.params);
  if (!lp || lp->mode != lsystem_mode::text)
    return std::string(key) + ": define.NAME reaches the #define constants of a text-mode L-system; this preset has none";
  const std::string name(key.substr(define_prefix.size()));
  const std::vector<lsystem_constant> ks = lsystem_constants(lp->source);
  const lsystem_constant* k = nullptr;
  std::string names;
  for (const lsystem_constant& c : ks) {
    if (c.name == name) k = &c;
    names += (names.empty() ? "" : ", ") + c.name;
  }
  if (!k) return std::string(key) + ": the L-system has no #define " + quote_text(name) +
                (names.empty() ? " (it defines no constants)" : " (it defines " + names + ")");
  float v;
  if (!parse_float_text(text, v) || !std::isfinite(v)) return std::string(key) + ": " + quote_text(text) + " is not a number";
  if (v < k->min || v > k->max) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " is outside [%g, %g]", double(k->min), double(k->max));
    return std::string(key) + ": " + quote_text(text) + buf;
  }
  if (!set_lsystem_constant(lp->source, name, v)) return std::string(key) + ": could not rewrite #define " + name;
  return "";
}
}  // namespace

// `--set key@step=value`: a keyframe of the generator's parameter `key`.
static std::string set_preset_keyframe(preset& p, std::string_view key_at, std::string_view text) {
  const size_t at = key_at.find('@');
  std::string_view key = key_at.substr(0, at);
  if (key.substr(0, 7) == "params.") key.remove_prefix(7);
  float step_f = 0;
  if (!parse_float_text(key_at.substr(at + 1), step_f) || step_f != std::floor(step_f) || std::fabs(step_f) > 1e6f)
    return std::string(key_at) + ": the step after @ must be a whole number";
  keyframe k;
  k.step = int(step_f);
  k.key = std::string(key);
  std::string error;
  with_keyable(p.spec, k.key, [&](auto& value, const param_info& info) {
    error = text_to_value(text, value, info);
    k.value = to_key_value(value);
  });
  if (!error.empty()) return std::string(key_at) + ": " + error;
  return set_keyframe(p.spec, k);
}

std::string set_preset_param(preset& p, std::string_view assignment) {
  const size_t eq = assignment.find('=');
  if (eq == std::string_view::npos || eq == 0)
    return "--set expects key=value, got \"" + std::string(assignment) + "\"";
  const std::string_view key = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  if (is_define_key(key)) return set_preset_define(p, key, text);
  if (key.find('@') != std::string_view::npos) return set_preset_keyframe(p, key, text);
  std::string error;
  preset before = p;
  std::string found = with_param(p, key, [&](auto& value, const param_info& info) {
    auto v = value;
    error = text_to_value(text, v, info);
    if (error.empty() && !clamp_param(v, info)) error = quote_text(text) + " is outside " + range_text(info);
    if (error.empty()) value = std::move(v);
  });
  if (!found.empty()) return found;
  if (!error.empty()) return std::string(key) + ": " + error;
  if (std::string why = document_refusal(p); !why.empty()) {
    p = std::move(before);
    return std::string(key) + ": not applied, since the document would not load again: " + why;
  }
  return "";
}

std::string non_finite_refusal(const preset& p) {
  std::string why = std::visit([](const auto& gp) { return non_finite_param(gp); }, p.spec.params);
  if (why.empty()) why = non_finite_param(p.spec.wood);
  if (why.empty()) why = non_finite_param(p.mesh);
  if (why.empty()) why = non_finite_param(p.render);
  for (const keyframe& k : p.spec.keyframes)
    for (int i = 0; i < 3 && why.empty(); ++i) why = finite_refusal(k.key + " at step " + std::to_string(k.step), k.value[i]);
  return why;
}

std::string document_refusal(const preset& p) {
  if (std::string e = non_finite_refusal(p); !e.empty()) return e;
  if (std::string e = check_keyframes(p.spec); !e.empty()) return e;
  return check_cuts(p.spec);
}

std::string expand_param_sweep(const preset& p, std::string_view assignment, std::vector<std::string>& out) {
  const size_t eq = assignment.find('=');
  if (eq == std::string_view::npos || eq == 0)
    return "--set expects key=value, got \"" + std::string(assignment) + "\"";
  const std::string_view key = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  if (key.find('@') != std::string_view::npos) {
    // A keyframe: one value, checked when it is set, after the --set before it (which may raise
    // the step count it is checked against).
    out.emplace_back(assignment);
    return "";
  }
  const auto parts = split(text, ':');
  preset copy = p;
  bool numeric = is_define_key(key), integral = false;
  std::string found = numeric ? std::string() : with_param(copy, key, [&](auto& value, const param_info&) {
    using T = std::decay_t<decltype(value)>;
    numeric = std::is_same_v<T, float> || std::is_same_v<T, int>;
    integral = std::is_same_v<T, int>;
  });
  if (!found.empty()) return found;
  if (!numeric || parts.size() != 3) {  // a plain value (strings such as L-system text may hold ':')
    if (std::string e = set_preset_param(copy, assignment); !e.empty()) return e;
    out.emplace_back(assignment);
    return "";
  }
  float a, b, n;
  if (!parse_float_text(parts[0], a) || !parse_float_text(parts[1], b) || !parse_float_text(parts[2], n) ||
      n != std::floor(n) || n < 1 || n > 100000)
    return std::string(key) + ": a sweep is from:to:count with a whole count >= 1, got \"" + std::string(text) + "\"";
  const int count = int(n);
  std::vector<std::string> values;
  for (int i = 0; i < count; ++i) {
    const double t = count == 1 ? 0.0 : double(i) / double(count - 1);
    double v = double(a) + (double(b) - double(a)) * t;
    if (integral) v = std::round(v);
    char buf[32];
    if (integral) std::snprintf(buf, sizeof buf, "%lld", (long long)v);
    else {
      auto r = std::to_chars(buf, buf + sizeof buf - 1, float(v));
      *r.ptr = 0;
    }
    std::string value = std::string(key) + "=" + buf;
    // Checked now, so that a sweep whose last value is out of range is refused before the first grows.
    if (std::string e = set_preset_param(copy, value); !e.empty())
      return e + " (value " + std::to_string(i + 1) + " of the sweep " + quote_text(text) + ")";
    values.push_back(std::move(value));
  }
  out.insert(out.end(), std::make_move_iterator(values.begin()), std::make_move_iterator(values.end()));
  return "";
}

}  // namespace sylva
