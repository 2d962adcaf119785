// Growth phases: a generator parameter that takes a new value from growth step k on.
#pragma once

#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <glm/vec3.hpp>

#include "generators/params.h"

namespace sylva {

// From `step` on, the parameter `key` of the spec's generator has `value`. Keyframes are applied
// at the top of growth step `step`, before anything of that step is computed, so the tree up to
// step − 1 is the tree without the keyframe, bit for bit.
struct keyframe {
  int step = 1;
  std::string key;
  glm::vec3 value{0};   // scalars in x; ints, bools and enums as whole numbers (exact in a float)
  bool operator==(const keyframe&) const = default;
};

// Only scalars and vec3 can be keyed: texts and lists are not (the per-step lists of guiding
// vectors already are schedules).
template <class T>
inline constexpr bool keyable_type = std::is_same_v<T, float> || std::is_same_v<T, int> || std::is_same_v<T, bool> ||
                                     std::is_enum_v<T> || std::is_same_v<T, glm::vec3>;

template <class T>
glm::vec3 to_key_value(const T& v) {
  if constexpr (std::is_same_v<T, glm::vec3>) return v;
  else if constexpr (std::is_enum_v<T>) return glm::vec3(float(int(v)), 0, 0);
  else if constexpr (keyable_type<T>) return glm::vec3(float(v), 0, 0);
  else return glm::vec3(0);
}

template <class T>
void from_key_value(const glm::vec3& k, T& out) {
  if constexpr (std::is_same_v<T, glm::vec3>) out = k;
  else if constexpr (std::is_same_v<T, float>) out = k.x;
  else if constexpr (std::is_same_v<T, bool>) out = k.x != 0;
  else if constexpr (std::is_same_v<T, int>) out = int(k.x);
  else if constexpr (std::is_enum_v<T>) out = T(int(k.x));
}

// Sets every parameter keyed at exactly `step`; returns true when one was set. A generator calls it
// at the top of each growth step on its working copy of the params (then re-clamps and recomputes
// what it derives from them). Keys that do not name a parameter of P are skipped: grow() checks
// the keyframes before it calls the generator.
template <class P>
bool apply_keyframes(P& p, const std::vector<keyframe>* keys, int step) {
  if (!keys || keys->empty()) return false;
  bool any = false;
  for (const keyframe& k : *keys) {
    if (k.step != step) continue;
    visit_params(p, [&](auto& value, const param_info& info) {
      using T = std::remove_cvref_t<decltype(value)>;
      if constexpr (keyable_type<T>)
        if (k.key == info.key) {
          from_key_value(k.value, value);
          any = true;
        }
    });
  }
  return any;
}

// The params as they stand during growth step `step`: the base values with every keyframe at or
// before `step` applied in step order.
template <class P>
P params_at_step(const P& base, const std::vector<keyframe>& keys, int step) {
  P p = base;
  int prev = 0;
  for (;;) {  // keyframes are few: visit the steps in order without sorting a copy
    int next = step + 1;
    for (const keyframe& k : keys)
      if (k.step > prev && k.step < next) next = k.step;
    if (next > step) break;
    apply_keyframes(p, &keys, next);
    prev = next;
  }
  return p;
}

struct tree_spec;

// Why `key` cannot be keyed for this spec's generator (and mode), or "" when it can. Some
// parameters set up growth once (a shadow grid, a point cloud, a graph) or act on the finished
// tree (pipe radii, leaves): a change from step k on would have no defined meaning for them.
std::string keyframe_refusal(const tree_spec& spec, std::string_view key);
// Checks one keyframe against the spec: a keyable parameter of its generator, a step in
// 1..last step, a value inside the parameter's range, no other keyframe of the same key at the
// same step (`ignore`: index of a keyframe of spec.keyframes to leave out of that test, -1 none).
// Returns "" or a message that names the key and step.
std::string check_keyframe(const tree_spec& spec, const keyframe& k, int ignore = -1);
// Checks every keyframe of the spec; "" or the first problem.
std::string check_keyframes(const tree_spec& spec);
// Adds k, or replaces the value of the keyframe with the same key and step; keeps the list sorted
// by step, then key. On a bad keyframe returns the message and leaves the spec as it was.
std::string set_keyframe(tree_spec& spec, const keyframe& k);
// The spec's own step (or derivation) count: the last step whose keyframes and cuts apply.
int last_keyframe_step(const tree_spec& spec);
// The last step a keyframe or cut may name: the top of the step (or derivation) parameter's range.
// A keyframe between last_keyframe_step and this is legal but inactive: it stays in the document,
// is saved and loaded, and applies again once Growth steps reaches it. So lowering Growth steps
// never makes a document that cannot be saved and reopened.
int max_keyframe_step(const tree_spec& spec);
// Whether a keyframe or cut at `step` applies in this spec's growth (step <= last_keyframe_step).
bool step_active(const tree_spec& spec, int step);
// How many keyframes and cuts lie past the last step (kept, inactive).
int inactive_edits(const tree_spec& spec);
// The keys a generator (index in generator_names; Honda's mode for the L-system) refuses, for the
// tests that check each one names a parameter.
std::vector<std::string> keyframe_refused_keys(int generator);
// What a step means for the spec's generator, for the editor and `sylva params`.
const char* keyframe_step_meaning(const tree_spec& spec);

}  // namespace sylva
