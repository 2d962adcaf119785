// What the preset loader (preset.cpp) and `--set` (preset_set.cpp) share: value texts for
// messages, the limits a value must keep, and the keyable-parameter lookup. Internal to render/.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "render/io/preset.h"

namespace sylva::preset_detail {

inline std::string format_number(double d) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", d);
  return buf;
}

// Built with += because GCC 12 warns falsely (-Wrestrict) on "literal" + std::string temporaries.
inline std::string range_text(const param_info& info) {
  std::string r = "[";
  r += format_number(info.min);
  r += ", ";
  r += format_number(info.max);
  r += ']';
  return r;
}

inline std::string quote_text(std::string_view s) {
  std::string r = "\"";
  r += s;
  r += '"';
  return r;
}

inline std::string mb_text(size_t bytes) {
  return bytes >= (1u << 20) ? std::to_string(bytes >> 20) + " MB" : std::to_string(bytes >> 10) + " KB";
}

inline std::string check_text(std::string_view s) {
  if (s.size() > max_preset_text_bytes) return "text longer than the " + mb_text(max_preset_text_bytes) + " limit";
  if (!valid_utf8(s)) return "text is not valid UTF-8";
  return "";
}

template <class T>
inline std::string check_value_limits(const T& v) {
  if constexpr (std::is_same_v<T, std::string>) {
    return check_text(v);
  } else if constexpr (std::is_same_v<T, std::vector<float>> || std::is_same_v<T, std::vector<glm::vec3>>) {
    if (v.size() > max_preset_list)
      return std::to_string(v.size()) + " entries, more than the limit of " + std::to_string(max_preset_list);
  }
  return "";
}

// Calls f(value, info) on the keyable generator parameter `key` of a copy of the spec's params;
// false when there is none (check_keyframe then names the problem).
template <class F>
bool with_keyable(const tree_spec& spec, std::string_view key, F&& f) {
  bool found = false;
  std::visit(
      [&](const auto& gp) {
        auto copy = gp;
        visit_params(copy, [&](auto& value, const param_info& info) {
          using T = std::remove_cvref_t<decltype(value)>;
          if constexpr (keyable_type<T>)
            if (key == info.key) {
              found = true;
              f(value, info);
            }
        });
      },
      spec.params);
  return found;
}

}  // namespace sylva::preset_detail
