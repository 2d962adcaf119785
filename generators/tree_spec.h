// The tree spec: which generator, its params and the seed; grow() dispatches on it.
#pragma once

#include <string>
#include <variant>

#include "generators/guiding_vectors.h"
#include "generators/keyframes.h"
#include "generators/lsystem.h"
#include "generators/pruning.h"
#include "generators/self_organizing.h"
#include "generators/space_colonization.h"
#include "generators/wood.h"

namespace sylva {

// Order matters: the index is the generator combo's index.
using generator_params =
    std::variant<self_organizing_params, space_colonization_params, guiding_vectors_params, lsystem_params>;

inline constexpr const char* generator_names[] = {"self_organizing", "space_colonization", "guiding_vectors",
                                                  "lsystem", nullptr};
inline constexpr const char* generator_labels[] = {"Self-organizing (Palubicki 2009)",
                                                   "Space colonization (Runions 2007)",
                                                   "Guiding vectors (Xu & Mould 2015)", "L-system (Honda / ABOP)",
                                                   nullptr};
inline constexpr int generator_count = 4;

struct tree_spec {
  generator_params params = lsystem_params{};
  uint64_t seed = 1;
  wood_params wood;   // the wood pass every generator's skeleton goes through (generators/wood.h)
  std::vector<keyframe> keyframes;   // growth phases (generators/keyframes.h), sorted by step
  std::vector<prune_cut> cuts;       // pruning (generators/pruning.h), in the order they were made
  bool operator==(const tree_spec&) const = default;
};

// Index in generator_names for a name, or -1.
int generator_index(const std::string& name);
const char* generator_name(const tree_spec& s);
// A spec with the given generator's default params (same seed).
generator_params default_params(int generator);
// The step count a spec grows to when no override is given.
int default_steps(const generator_params& p);

tree_skeleton grow(const tree_spec& spec, const grow_options& o, grow_report* report = nullptr,
                   growth_debug* debug = nullptr);

}  // namespace sylva
