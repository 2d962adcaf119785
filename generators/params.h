// The parameter schema: each parameter is declared once, in a visit_params overload (DESIGN §4).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <glm/vec3.hpp>

namespace sylva {

enum param_flags : unsigned {
  param_log = 1u << 0,           // slider on a logarithmic scale
  param_degrees = 1u << 1,       // value is in degrees (shown with a ° suffix)
  param_on_release = 1u << 2,    // expensive: apply when the slider is released, not while dragging
  param_advanced = 1u << 3,      // shown in a collapsed "advanced" part of its group
  param_multiline = 1u << 4,     // strings: a multi-line text box (L-system source)
  param_path = 1u << 5,          // strings: a file path
  param_direction = 1u << 6,     // vec3: a direction (normalised where used)
  // The parameter's class: how much of the pipeline a change of it redoes. Exactly one is set on
  // every parameter (a struct whose parameters share one declares it once, with declare_class).
  param_regrow = 1u << 7,        // the generator grows the tree again, then it is meshed and drawn
  param_remesh = 1u << 8,        // the kept skeleton is meshed again; nothing regrows
  param_render = 1u << 9,        // only drawing changes (uniforms, textures, LODs): no regrow, no re-mesh
  // The generator's own leaf rule (space colonization's spiral, the L-system's L): used only when
  // the mesh's leaf mode is "generator", so the editor hides it otherwise.
  param_own_leaves = 1u << 10,
};

// The classes in the order of their cost: an edit of several parameters needs the largest.
enum class param_class : uint8_t { render = 0, remesh = 1, regrow = 2 };
inline constexpr const char* param_class_names[] = {"render", "re-mesh", "regrow", nullptr};

// Everything but the value: consumers (editor, preset JSON, CLI --set, `sylva params`, tests)
// derive their behaviour from this record.
struct param_info {
  const char* key;         // stable JSON / CLI key, unique within one params struct
  const char* label;       // human label
  const char* symbol;      // the paper's symbol: "λ", "σ" ... ("" when none)
  float min, max;          // inclusive range (ints and vector elements too)
  const char* help;        // tooltip: meaning and source
  unsigned flags = 0;
  const char* group = nullptr;               // starts a new collapsible group in the editor
  const char* const* options = nullptr;      // enums: nullptr-terminated option names, index = value
};

// The declared class of a parameter (param_regrow when it declares none, which the parameter walk
// in tests/app/param_class_test.cpp refuses).
inline param_class class_of(const param_info& info) {
  if (info.flags & param_render) return param_class::render;
  if (info.flags & param_remesh) return param_class::remesh;
  return param_class::regrow;
}

// A visitor passing every parameter on to `v` with `class_flag` (param_regrow, param_remesh or
// param_render) added to its flags: the first line of a visit_params whose parameters share a class.
template <class V>
auto declare_class(V& v, unsigned class_flag) {
  return [&v, class_flag](auto& value, const param_info& info) {
    param_info declared = info;
    declared.flags |= class_flag;
    v(value, declared);
  };
}

// Supported value types: float, int, bool, enum (with options), glm::vec3, std::string,
// std::vector<float>, std::vector<glm::vec3>. A visitor is called as v(value&, const param_info&).

// `template <params_of<foo_params> P, class V> void visit_params(P& p, V&& v)` declares one visitor
// for both the mutable and the const struct.
template <class P, class T>
concept params_of = std::is_same_v<std::remove_const_t<P>, T>;

inline int option_count(const param_info& info) {
  int n = 0;
  while (info.options && info.options[n]) ++n;
  return n;
}

// Whether the editor shows a parameter for the current values of its struct (e.g. the L-system's
// Honda sliders are hidden in text mode). Consulted by the editor only: presets, the CLI and
// `sylva params` still see every key. A struct with mode-dependent fields declares a non-template
// overload next to its visit_params; `field` is the address of the visited member, so no key is
// typed twice.
template <class P>
bool param_relevant(const P&, const void* /*field*/, const param_info&) {
  return true;
}

// Clamps a value into its declared range; returns false when it had to change it (NaN included).
template <class T>
bool clamp_param(T& value, const param_info& info) {
  if constexpr (std::is_same_v<T, float>) {
    if (std::isnan(value)) { value = info.min; return false; }
    if (value < info.min) { value = info.min; return false; }
    if (value > info.max) { value = info.max; return false; }
    return true;
  } else if constexpr (std::is_same_v<T, int>) {
    if (value < (int)info.min) { value = (int)info.min; return false; }
    if (value > (int)info.max) { value = (int)info.max; return false; }
    return true;
  } else if constexpr (std::is_enum_v<T>) {
    const int n = option_count(info);
    if ((int)value < 0 || (int)value >= n) { value = T(0); return false; }
    return true;
  } else if constexpr (std::is_same_v<T, glm::vec3>) {
    bool ok = true;
    for (int i = 0; i < 3; ++i) {
      float c = value[i];
      ok &= clamp_param(c, info);
      value[i] = c;
    }
    return ok;
  } else if constexpr (std::is_same_v<T, std::vector<float>>) {
    bool ok = true;
    for (float& c : value) ok &= clamp_param(c, info);
    return ok;
  } else if constexpr (std::is_same_v<T, std::vector<glm::vec3>>) {
    bool ok = true;
    for (glm::vec3& c : value) ok &= clamp_param(c, info);
    return ok;
  } else {
    return true;  // bool, string
  }
}

// The one check of a number that comes from outside: the CLI's options (app/cli/cli_numbers.h),
// `--set`, the editor's fields and documents (non_finite_refusal, render/io/preset.h) and the
// export options. NaN passes every range check, since each comparison with it is false, so
// finiteness is checked first and on its own. "" when v is finite, else
// "NAME: VALUE is not a finite number" (VALUE as printf's %g writes it: nan, inf, -inf).
inline std::string finite_refusal(std::string_view name, double v) {
  if (std::isfinite(v)) return "";
  char text[16];
  std::snprintf(text, sizeof text, "%g", v);
  return std::string(name) + (name.empty() ? "" : ": ") + text + " is not a finite number";
}

// The first number of p that is NaN or infinite (a float, a vec3's component, a list's entry), as
// finite_refusal names it with the parameter's label; "" when every number is finite.
template <class P>
std::string non_finite_param(const P& p) {
  std::string why;
  visit_params(p, [&](const auto& value, const param_info& info) {
    using T = std::remove_cvref_t<decltype(value)>;
    auto check = [&](float f) {
      if (why.empty()) why = finite_refusal(info.label, f);
    };
    if constexpr (std::is_same_v<T, float>) {
      check(value);
    } else if constexpr (std::is_same_v<T, glm::vec3>) {
      for (int i = 0; i < 3; ++i) check(value[i]);
    } else if constexpr (std::is_same_v<T, std::vector<float>>) {
      for (float f : value) check(f);
    } else if constexpr (std::is_same_v<T, std::vector<glm::vec3>>) {
      for (const glm::vec3& c : value)
        for (int i = 0; i < 3; ++i) check(c[i]);
    }
  });
  return why;
}

// Clamps every parameter of a params struct; returns the keys that were changed.
template <class P>
std::vector<std::string> clamp_all_params(P& p) {
  std::vector<std::string> changed;
  visit_params(p, [&](auto& value, const param_info& info) {
    if (!clamp_param(value, info)) changed.emplace_back(info.key);
  });
  return changed;
}

}  // namespace sylva
