// Growth phases: which parameters can change from a step on, and the checks on a keyframe list.
#include "generators/keyframes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "generators/tree_spec.h"

namespace sylva {
namespace {

struct refusal {
  const char* key;
  const char* why;
};

// Parameters that cannot change during growth, with the reason. Each key is checked against the
// generator's visit_params by the tests (keyframes_test.cpp), so a renamed key cannot go stale.
constexpr const char* once = "it is used once, before the first step";
constexpr const char* whole = "it acts on the finished tree, not on one step";
constexpr const char* cap = "it is a limit on the whole growth";

constexpr refusal so_refusals[] = {
    {"steps", "the step count itself cannot change during growth"},
    {"internode_length", "the shadow grid and the perception cone are sized in internode lengths once, before the first step"},
    {"environment", once},
    {"shadow_a", "a bud's shadow is removed again with the values it was cast with when the bud is shed"},
    {"shadow_b", "a bud's shadow is removed again with the values it was cast with when the bud is shed"},
    {"q_max", "a bud's shadow is removed again with the values it was cast with when the bud is shed"},
    {"voxel_size", "the shadow grid is built once, before the first step"},
    {"perception_distance", "the perception cone's voxel offsets are built once, before the first step"},
    {"marker_count", "the markers are scattered once, before the first step"},
    {"envelope_radius", "the markers are scattered once, before the first step"},
    {"envelope_bottom", "the markers are scattered once, before the first step"},
    {"envelope_top", "the markers are scattered once, before the first step"},
    {"pipe_exponent", whole},
    {"pipe_taper", whole},
    {"tip_radius", whole},
    {"live_crown", whole},
    {"stub_length", whole},
    {"tree_count", once},
    {"placement", once},
    {"spacing", once},
    {"node_cap", cap},
};

constexpr refusal sc_refusals[] = {
    {"envelope", "the attraction points are sampled once, before the first step"},
    {"points", "the attraction points are sampled once, before the first step"},
    {"size", "the attraction points are sampled once, before the first step"},
    {"offset", "the attraction points are sampled once, before the first step"},
    {"slab_thickness", "the attraction points are sampled once, before the first step"},
    {"envelope_dents", "the attraction points are sampled once, before the first step"},
    {"sky_lean", "the attraction points are thinned towards the open side once, before the first step"},
    {"open_side", "the attraction points are thinned towards the open side once, before the first step"},
    {"envelope_dent_depth", "the attraction points are sampled once, before the first step"},
    {"influence_radius", "the point search grid is built for dᵢ once, before the first step"},
    {"kill_distance", "the point search grid is built for dₖ once, before the first step"},
    {"trunk_length", "the trunk's length is decided once, before the first step"},
    {"max_branches", cap},
    {"steps", "the step count itself cannot change during growth"},
    {"node_cap", cap},
    {"pipe_exponent", whole},
    {"pipe_taper", whole},
    {"min_width", whole},
    {"max_width", whole},
    {"leaves_min", whole},
    {"leaves_max", whole},
    {"leaf_size_min", whole},
    {"leaf_size_max", whole},
    {"spiral_a", whole},
    {"spiral_k", whole},
    {"spiral_e", whole},
    {"spiral_rounds", whole},
    {"live_crown", whole},
    {"stub_length", whole},
};

constexpr refusal gv_refusals[] = {
    {"steps", "the step count itself cannot change during growth"},
    {"spacing", "the Poisson-disc graph is built once, before the first step"},
    {"candidates", "the Poisson-disc graph is built once, before the first step"},
    {"domain_size", "the Poisson-disc graph is built once, before the first step"},
    {"ground_rise", "the Poisson-disc graph is built once, before the first step"},
    {"ground_base", "the Poisson-disc graph is built once, before the first step"},
    {"volume", "only step 1 samples the endpoint volume; later steps use the border set"},
    {"volume_offset", "only step 1 samples the endpoint volume; later steps use the border set"},
    {"volume_scale", "only step 1 samples the endpoint volume; later steps use the border set"},
    {"volume_outer", "only step 1 samples the endpoint volume; later steps use the border set"},
    {"volume_inner", "only step 1 samples the endpoint volume; later steps use the border set"},
    {"pipe_exponent", whole},
    {"pipe_taper", whole},
    {"tip_radius", whole},
    {"node_cap", cap},
};

constexpr refusal honda_refusals[] = {
    {"mode", once},
    {"derivations", "the derivation count itself cannot change during growth"},
    {"s0", "the axiom A(s₀,w₀) is written once, before derivation 1"},
    {"w0", "the axiom A(s₀,w₀) is written once, before derivation 1"},
    {"scale", whole},
    {"width_scale", whole},
    {"node_cap", cap},
    {"turtle_leaf_size", whole},
    {"widths", whole},
    {"pipe_exponent", whole},
    {"pipe_taper", whole},
    {"tip_radius", whole},
    {"module_cap", cap},
    {"season_variation", "it acts in text mode only, which takes no keyframes"},
    {"live_crown", whole},
    {"stub_length", whole},
};

template <size_t N>
const char* find_refusal(const refusal (&table)[N], std::string_view key) {
  for (const refusal& r : table)
    if (key == r.key) return r.why;
  return nullptr;
}

std::string step_text(int step) { return "step " + std::to_string(step); }

}  // namespace

std::vector<std::string> keyframe_refused_keys(int generator) {
  std::vector<std::string> out;
  auto add = [&](const auto& table) {
    for (const refusal& r : table) out.emplace_back(r.key);
  };
  switch (generator) {
    case 0: add(so_refusals); break;
    case 1: add(sc_refusals); break;
    case 2: add(gv_refusals); break;
    default: add(honda_refusals);
  }
  return out;
}

int last_keyframe_step(const tree_spec& spec) { return default_steps(spec.params); }

int max_keyframe_step(const tree_spec& spec) {
  int top = 0;
  std::visit(
      [&](const auto& p) {
        visit_params(p, [&](const auto&, const param_info& info) {
          if (std::string_view(info.key) == "steps" || std::string_view(info.key) == "derivations") top = int(info.max);
        });
      },
      spec.params);
  return top;
}

bool step_active(const tree_spec& spec, int step) { return step <= last_keyframe_step(spec); }

int inactive_edits(const tree_spec& spec) {
  int n = 0;
  for (const keyframe& k : spec.keyframes) n += !step_active(spec, k.step);
  for (const prune_cut& c : spec.cuts) n += !step_active(spec, c.step);
  return n;
}

const char* keyframe_step_meaning(const tree_spec& spec) {
  if (const auto* l = std::get_if<lsystem_params>(&spec.params); l && l->mode == lsystem_mode::text)
    return "not available for text L-systems: the turtle reads the string after the last derivation";
  return generator_table[spec.params.index()].step_meaning;
}

std::string keyframe_refusal(const tree_spec& spec, std::string_view key) {
  // Is it a parameter of this generator, and of a type that can be keyed?
  int kind = 0;  // 0 unknown, 1 keyable type, 2 text or list
  std::visit(
      [&](const auto& p) {
        visit_params(p, [&](const auto& value, const param_info& info) {
          if (key != info.key) return;
          kind = keyable_type<std::remove_cvref_t<decltype(value)>> ? 1 : 2;
        });
      },
      spec.params);
  const std::string name = "\"" + std::string(key) + "\"";
  if (kind == 0)
    return name + " is not a parameter of " + generator_name(spec) + " (see `sylva params`)";
  if (kind == 2) {
    if (std::holds_alternative<guiding_vectors_params>(spec.params))
      return name + " is already a per-step schedule; edit its entry for the step instead";
    return name + " is a text or a list, which cannot be keyed";
  }
  const char* why = nullptr;
  switch (spec.params.index()) {
    case 0: why = find_refusal(so_refusals, key); break;
    case 1: why = find_refusal(sc_refusals, key); break;
    case 2: why = find_refusal(gv_refusals, key); break;
    default:
      if (std::get<lsystem_params>(spec.params).mode == lsystem_mode::text)
        return name + " cannot be keyed: keyframes are not available for text L-systems, since the turtle reads the "
                      "string only after the last derivation (write the change into the productions instead)";
      why = find_refusal(honda_refusals, key);
  }
  if (why) return name + " cannot change from a step on: " + why;
  return "";
}

std::string check_keyframe(const tree_spec& spec, const keyframe& k, int ignore) {
  const std::string at = "keyframe " + k.key + "@" + std::to_string(k.step);
  if (std::string why = keyframe_refusal(spec, k.key); !why.empty()) return at + ": " + why;
  const int top = max_keyframe_step(spec);
  if (k.step < 1) return at + ": steps start at 1 (the value before step 1 is the parameter's own value)";
  if (k.step > top)
    return at + ": " + step_text(k.step) + " is beyond the most steps a growth can have (" + std::to_string(top) + ")";
  std::string range;
  std::visit(
      [&](const auto& p) {
        visit_params(p, [&](const auto& value, const param_info& info) {
          using T = std::remove_cvref_t<decltype(value)>;
          if constexpr (keyable_type<T>) {
            if (k.key != info.key) return;
            for (int c = 0; c < (std::is_same_v<T, glm::vec3> ? 3 : 1); ++c) {
              const float x = k.value[c];
              bool ok = std::isfinite(x) && x >= info.min && x <= info.max;
              if constexpr (std::is_same_v<T, bool>) ok = x == 0 || x == 1;
              else if constexpr (std::is_enum_v<T>) ok = x == std::floor(x) && x >= 0 && x < float(option_count(info));
              else if constexpr (std::is_same_v<T, int>) ok = ok && x == std::floor(x);
              if (!ok && range.empty()) {
                char b[160];
                std::snprintf(b, sizeof b, "value %g is outside the parameter's range [%g, %g]", double(x),
                              double(info.min), double(info.max));
                range = b;
                if constexpr (std::is_enum_v<T>) range = "value " + std::to_string(x) + " is not an option index";
              }
            }
          }
        });
      },
      spec.params);
  if (!range.empty()) return at + ": " + range;
  for (size_t i = 0; i < spec.keyframes.size(); ++i)
    if (int(i) != ignore && spec.keyframes[i].step == k.step && spec.keyframes[i].key == k.key)
      return at + ": the same key is already keyed at that step (two values for one step contradict each other)";
  return "";
}

std::string check_keyframes(const tree_spec& spec) {
  for (size_t i = 0; i < spec.keyframes.size(); ++i)
    if (std::string e = check_keyframe(spec, spec.keyframes[i], int(i)); !e.empty()) return e;
  return "";
}

std::string set_keyframe(tree_spec& spec, const keyframe& k) {
  int same = -1;
  for (size_t i = 0; i < spec.keyframes.size(); ++i)
    if (spec.keyframes[i].step == k.step && spec.keyframes[i].key == k.key) same = int(i);
  if (std::string e = check_keyframe(spec, k, same); !e.empty()) return e;
  if (same >= 0) {
    spec.keyframes[size_t(same)].value = k.value;
    return "";
  }
  auto before = [](const keyframe& a, const keyframe& b) { return a.step != b.step ? a.step < b.step : a.key < b.key; };
  spec.keyframes.insert(std::upper_bound(spec.keyframes.begin(), spec.keyframes.end(), k, before), k);
  return "";
}

}  // namespace sylva
