// Growth phases in the editor, the display-free part: "from this step on" edits, moving markers,
// the keyed steps and their text (app/editor/editor_keyframes.h). Shared by the editor and the edit fuzzer.
#include "app/editor/editor_keyframes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sylva {

bool follow_step(keyframe_panel_state& s, int step) {
  if (!s.from_step) {
    s.from_step_at = -1;
    return false;
  }
  if (s.from_step_at < 0) s.from_step_at = step;
  if (step == s.from_step_at && step >= 1) return false;
  s.from_step = false;
  s.from_step_at = -1;
  return true;
}

generator_params params_at_step(const tree_spec& spec, int step) {
  return std::visit([&](const auto& p) -> generator_params { return params_at_step(p, spec.keyframes, step); },
                    spec.params);
}

std::string key_edits(tree_spec& spec, const generator_params& before, const generator_params& after, int step) {
  if (before.index() != after.index() || before.index() != spec.params.index()) return "the generator changed";
  tree_spec out = spec;
  std::string error;
  std::visit(
      [&](const auto& b) {
        using P = std::decay_t<decltype(b)>;
        const P& a = std::get<P>(after);
        std::vector<const void*> old;
        visit_params(b, [&](const auto& value, const param_info&) { old.push_back(&value); });
        size_t i = 0;
        visit_params(a, [&](const auto& value, const param_info& info) {
          using T = std::remove_cvref_t<decltype(value)>;
          const T& was = *static_cast<const T*>(old[i++]);
          if (!error.empty() || value == was) return;
          if constexpr (!keyable_type<T>) {
            error = std::string("\"") + info.key + "\" is a text or a list, which cannot be keyed; switch off \"from this step on\" to edit it";
          } else {
            if (std::string why = keyframe_refusal(out, info.key); !why.empty()) {
              error = why + "; switch off \"from this step on\" to change it for the whole growth";
              return;
            }
            // What would be in effect at `step` without a keyframe of this key there.
            tree_spec without = out;
            std::erase_if(without.keyframes, [&](const keyframe& k) { return k.step == step && k.key == info.key; });
            const glm::vec3 v = to_key_value(value);
            bool same = false;
            const generator_params in_effect = params_at_step(without, step);
            visit_params(std::get<P>(in_effect), [&](const auto& w, const param_info& wi) {
              using W = std::remove_cvref_t<decltype(w)>;
              if constexpr (keyable_type<W>)
                if (wi.key == info.key) same = to_key_value(w) == v;
            });
            if (same) out.keyframes = std::move(without.keyframes);
            else error = set_keyframe(out, {step, info.key, v});
          }
        });
      },
      before);
  if (error.empty()) spec = std::move(out);
  return error;
}

std::string move_keyframes(tree_spec& spec, int from, int to) {
  if (from == to) return "";
  tree_spec out = spec;
  std::vector<keyframe> moving;
  std::erase_if(out.keyframes, [&](const keyframe& k) {
    if (k.step != from) return false;
    moving.push_back(k);
    return true;
  });
  for (keyframe k : moving) {
    k.step = to;
    if (std::string e = check_keyframe(out, k); !e.empty()) return e;
    out.keyframes.push_back(k);
  }
  std::stable_sort(out.keyframes.begin(), out.keyframes.end(), [](const keyframe& a, const keyframe& b) {
    return a.step != b.step ? a.step < b.step : a.key < b.key;
  });
  spec = std::move(out);
  return "";
}

std::vector<int> keyed_steps(const tree_spec& spec) {
  std::vector<int> s;
  for (const keyframe& k : spec.keyframes)
    if (s.empty() || s.back() != k.step) s.push_back(k.step);
  std::sort(s.begin(), s.end());
  s.erase(std::unique(s.begin(), s.end()), s.end());
  return s;
}

std::string keyframe_text(const tree_spec& spec, const keyframe& k) {
  std::string text = k.key + " = ?";
  visit_keyed_value(spec, k, [&](const auto& value, const param_info& info) {
    using T = std::remove_cvref_t<decltype(value)>;
    char b[96];
    if constexpr (std::is_same_v<T, float>) std::snprintf(b, sizeof b, "%.4g", double(value));
    else if constexpr (std::is_same_v<T, bool>) std::snprintf(b, sizeof b, "%s", value ? "on" : "off");
    else if constexpr (std::is_enum_v<T>) std::snprintf(b, sizeof b, "%s", int(value) < option_count(info) ? info.options[int(value)] : "?");
    else if constexpr (std::is_same_v<T, int>) std::snprintf(b, sizeof b, "%d", value);
    else std::snprintf(b, sizeof b, "(%.3g, %.3g, %.3g)", double(value.x), double(value.y), double(value.z));
    text = k.key + " = " + b;
  });
  return text;
}

bool keyed_at(const tree_spec& spec, const char* key, int step) {
  for (const keyframe& k : spec.keyframes)
    if (k.step == step && k.key == key) return true;
  return false;
}

}  // namespace sylva
