// Edit sequences as the editor makes them, decoded from bytes: slider moves of any parameter (the
// editor script's `set`, the CLI's --set), "from this step on" edits (key_edits), keys at a step,
// marker drags (move_keyframes), cuts, and deleting a keyframe or a cut. Shared by the edit fuzzer
// (tests/fuzz/fuzz_edits.cpp) and the round-trip property test (tests/app/edit_sequence_test.cpp).
//
// After every edit the document must save and load back equal, whatever the edit order: the loader
// and the editor apply one rule (generators/keyframes.h: keyframes and cuts past the last step are
// kept, inactive). A refused edit must leave the document as it was.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "app/editor/editor_keyframes.h"
#include "generators/keyframes.h"
#include "generators/pruning.h"
#include "render/io/preset.h"

namespace sylva_test {

using namespace sylva;

// Reads bytes one at a time; past the end it gives zeros.
struct byte_reader {
  const uint8_t* data;
  size_t size, at = 0;
  bool done() const { return at >= size; }
  unsigned byte() { return at < size ? data[at++] : 0u; }
  float unit() { return float(byte() | (byte() << 8)) / 65535.0f; }   // [0, 1]
};

// A value inside the parameter's range written as set_preset_param reads it; "" for texts and
// lists, which the sequences leave alone (tests/fuzz/fuzz_lsystem.cpp covers the L-system texts).
template <class T>
std::string value_text(const param_info& info, byte_reader& in) {
  char b[96];
  auto in_range = [&] { return info.min + (info.max - info.min) * in.unit(); };
  if constexpr (std::is_same_v<T, float>) {
    std::snprintf(b, sizeof b, "%.9g", double(in_range()));
  } else if constexpr (std::is_same_v<T, int>) {
    std::snprintf(b, sizeof b, "%d", int(std::lround(in_range())));
  } else if constexpr (std::is_same_v<T, bool>) {
    return in.byte() & 1 ? "on" : "off";
  } else if constexpr (std::is_enum_v<T>) {
    return info.options[in.byte() % unsigned(option_count(info))];
  } else if constexpr (std::is_same_v<T, glm::vec3>) {
    const float x = in_range(), y = in_range(), z = in_range();
    std::snprintf(b, sizeof b, "%.9g,%.9g,%.9g", double(x), double(y), double(z));
  } else {
    return "";
  }
  return b;
}

// One settable parameter: its qualified key and a writer of an in-range value.
struct settable {
  std::string key;
  bool keyable = false;
  std::function<std::string(byte_reader&)> value;
};

inline std::vector<settable> settables(const preset& p) {
  std::vector<settable> out;
  auto look = [&](const char* section, const auto& params) {
    visit_params(params, [&](const auto& value, const param_info& info) {
      using T = std::remove_cvref_t<decltype(value)>;
      if constexpr (std::is_same_v<T, float> || std::is_same_v<T, int> || std::is_same_v<T, bool> ||
                    std::is_enum_v<T> || std::is_same_v<T, glm::vec3>)
        out.push_back({std::string(section) + "." + info.key, std::string(section) == "params",
                       [info](byte_reader& in) { return value_text<T>(info, in); }});
    });
  };
  std::visit([&](const auto& gp) { look("params", gp); }, p.spec.params);
  look("mesh", p.mesh);
  look("render", p.render);
  look("wood", p.spec.wood);
  return out;
}

// One edit, chosen and filled in from the bytes; `what` says what it was (for a failure message).
// Returns false when the edit was refused (the document must then be unchanged).
inline bool apply_one_edit(preset& p, byte_reader& in, std::string& what) {
  const std::vector<settable> all = settables(p);
  const int top = max_keyframe_step(p.spec);
  // Steps reach past the range's top now and then, to try the refusal too.
  auto any_step = [&] { return int(in.byte() % unsigned(top + 3)); };
  auto step_param = [&]() -> std::string {
    return p.spec.params.index() == 3 ? "params.derivations" : "params.steps";
  };
  std::string error;
  switch (in.byte() % 8) {
    case 0:
    case 1: {   // a slider: any parameter, any in-range value
      const settable& s = all[in.byte() % all.size()];
      what = s.key + "=" + s.value(in);
      error = set_preset_param(p, what);
      break;
    }
    case 2: {   // Growth steps, low or high: strands keyframes past the last step, or revives them
      const int n = in.byte() & 1 ? int(in.byte() % 8) : int(in.unit() * float(top));
      what = step_param() + "=" + std::to_string(n);
      error = set_preset_param(p, what);
      break;
    }
    case 3: {   // a key at a step, as --set key@k=value and the script's `set` write it
      std::vector<const settable*> keyable;
      for (const settable& s : all)
        if (s.keyable) keyable.push_back(&s);
      const settable& s = *keyable[in.byte() % keyable.size()];
      what = s.key.substr(7) + "@" + std::to_string(any_step()) + "=" + s.value(in);
      error = set_preset_param(p, what);
      break;
    }
    case 4: {   // "from this step on": a slider moved in the panel at a step (key_edits)
      const int step = 1 + int(in.byte() % unsigned(top));
      const generator_params before = params_at_step(p.spec, step);
      preset moved = p;
      moved.spec.params = before;
      const settable& s = all[in.byte() % all.size()];
      if (s.key.rfind("params.", 0) != 0) return true;
      what = "from step " + std::to_string(step) + " on: " + s.key + "=" + s.value(in);
      if (!set_preset_param(moved, what.substr(what.find(": ") + 2)).empty()) return true;
      error = key_edits(p.spec, before, moved.spec.params, step);
      break;
    }
    case 5: {   // a marker dragged from one keyed step to another
      const std::vector<int> keyed = keyed_steps(p.spec);
      const int from = keyed.empty() ? 1 : keyed[in.byte() % keyed.size()];
      const int to = any_step();
      what = "move keyframes " + std::to_string(from) + " -> " + std::to_string(to);
      error = move_keyframes(p.spec, from, to);
      break;
    }
    case 6: {   // a cut: a picked branch or a brush, at any step
      prune_cut c;
      c.step = any_step();
      c.shape = prune_shape(in.byte() % 3);
      c.point = glm::vec3(in.unit() * 4 - 2, in.unit() * 6, in.unit() * 4 - 2);
      c.size = glm::vec3(0.1f + in.unit() * 2);
      c.reach = 0.05f + in.unit();
      what = "cut at step " + std::to_string(c.step);
      error = add_cut(p.spec, c);
      break;
    }
    default: {   // delete a keyframe or a cut
      what = "delete";
      if (in.byte() & 1) {
        if (!p.spec.keyframes.empty()) p.spec.keyframes.erase(p.spec.keyframes.begin() + long(in.byte() % p.spec.keyframes.size()));
      } else if (!p.spec.cuts.empty()) {
        p.spec.cuts.erase(p.spec.cuts.begin() + long(in.byte() % p.spec.cuts.size()));
      }
    }
  }
  return error.empty();
}

// Runs the whole sequence on `p`; returns "" or the first broken rule, with the edits that led
// there.
inline std::string run_edit_sequence(preset& p, const uint8_t* data, size_t size) {
  byte_reader in{data, size};
  std::string log;
  while (!in.done()) {
    const preset before = p;
    std::string what;
    const bool applied = apply_one_edit(p, in, what);
    log += "  " + what + (applied ? "\n" : " (refused)\n");
    if (!applied && !(p == before)) return "a refused edit changed the document:\n" + log;
    const std::string saved = save_preset_json(p);
    preset back;
    const load_result r = load_preset_json(saved, back);
    if (!r.ok) return "the saved document does not load (" + r.error + ") after:\n" + log;
    if (!(back == p)) return "the saved document loads back different after:\n" + log;
  }
  return "";
}

}  // namespace sylva_test
