// Generator dispatch over the tree spec.
#include "generators/tree_spec.h"

#include <algorithm>
#include <cstring>
#include <string>

namespace sylva {

int generator_index(const std::string& name) {
  for (int i = 0; generator_names[i]; ++i)
    if (name == generator_names[i]) return i;
  return -1;
}

const char* generator_name(const tree_spec& s) { return generator_names[s.params.index()]; }

namespace {

// Generator `generator`'s default params (the last generator's for any other number).
template <size_t... I>
generator_params default_params_of(int generator, std::index_sequence<I...>) {
  generator_params out = std::variant_alternative_t<sizeof...(I) - 1, generator_params>{};
  ((generator == int(I) ? (out = std::variant_alternative_t<I, generator_params>{}, 0) : 0), ...);
  return out;
}

}  // namespace

generator_params default_params(int generator) {
  return default_params_of(generator, std::make_index_sequence<std::variant_size_v<generator_params>>{});
}

int default_steps(const generator_params& p) {
  return std::visit(
      [](const auto& q) -> int {
        if constexpr (std::is_same_v<std::decay_t<decltype(q)>, lsystem_params>) return q.derivations;
        else return q.steps;
      },
      p);
}

tree_skeleton grow(const tree_spec& spec, const grow_options& o, grow_report* report, growth_debug* debug) {
  grow_options opt = o;
  opt.seed = spec.seed;
  // Keyframes that fail their checks never reach a generator: the editor and the loaders refuse
  // them, so this only catches a spec built by hand.
  std::string bad_keys;
  if (!spec.keyframes.empty()) {
    bad_keys = check_keyframes(spec);
    opt.keyframes = bad_keys.empty() ? &spec.keyframes : nullptr;
  }
  std::string bad_cuts;
  if (!spec.cuts.empty()) {
    bad_cuts = check_cuts(spec);
    opt.cuts = bad_cuts.empty() ? &spec.cuts : nullptr;
  }
  tree_skeleton t = std::visit(
      [&](const auto& p) -> tree_skeleton {
        using P = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<P, self_organizing_params>) return grow_self_organizing(p, opt, report, debug);
        else if constexpr (std::is_same_v<P, space_colonization_params>) return grow_space_colonization(p, opt, report, debug);
        else if constexpr (std::is_same_v<P, guiding_vectors_params>) return grow_guiding_vectors(p, opt, report, debug);
        else return grow_lsystem(p, opt, report, debug);
      },
      spec.params);
  if (report && !bad_keys.empty() && report->message.empty())
    report->message = "keyframes ignored: " + bad_keys;
  if (report && !bad_cuts.empty() && report->message.empty())
    report->message = "cuts ignored: " + bad_cuts;
  // Some values inside the published ranges leave nothing to grow (no endpoints, no resource for
  // any bud): say so rather than show a bare root without a word.
  const int wanted = o.steps >= 0 ? o.steps : default_steps(spec.params);
  if (report && !report->error && !report->cancelled && report->message.empty() && wanted > 0 &&
      t.size() <= size_t(std::max(1, t.tree_count))) {
    report->message = std::string("nothing grew beyond the seedling: ") + generator_table[spec.params.index()].nothing_grew;
  }
  // Keyframes and cuts past the last step are legal (generators/keyframes.h) but do nothing: say so.
  if (report && !report->error && !report->cancelled && report->message.empty())
    if (const int n = inactive_edits(spec); n > 0)
      report->message = std::to_string(n) + (n == 1 ? " keyframe or cut lies" : " keyframes or cuts lie") +
                        " past the last step (" + std::to_string(last_keyframe_step(spec)) +
                        "): kept, inactive until Growth steps reaches them";
  // The shared passes (DESIGN §3): the generator's radii are final, the foliage is placed later by
  // the mesher on the bent skeleton. A cancelled growth is not bent: it is thrown away.
  if (!(report && (report->cancelled || report->error)) && !opt.cancelled()) apply_wood(t, spec.wood, report);
  return t;
}

}  // namespace sylva
