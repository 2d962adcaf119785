// The tree spec: which generator, its params and the seed; grow() dispatches on it.
#pragma once

#include <array>
#include <iterator>
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

// Order matters: the index is the generator combo's index, and generator_table's row.
using generator_params =
    std::variant<self_organizing_params, space_colonization_params, guiding_vectors_params, lsystem_params>;

// One row per generator, in generator_params order: its name (`sylva params`, presets), its label
// (the editor), what one growth step is for a keyframe, what a cut does to the growth after it,
// and why nothing grew when only the seedling stands. (A text L-system has its own step and cut
// texts: keyframes.cpp, pruning.cpp.)
struct generator_row {
  const char* name;
  const char* label;
  const char* step_meaning;
  const char* cut_response;
  const char* nothing_grew;
};
inline constexpr generator_row generator_table[] = {
    {"self_organizing", "Self-organizing (Palubicki 2009)",
     "a step is one year of growth: a keyframe at step k changes the buds' light, resource and shoots from year k on",
     "the cut branch's shadow is removed and its resource flows to the rest, so buds near the cut break "
     "(Palubicki et al. 2009, pruning)",
     "no bud received enough resource to grow (check alpha, the upkeep bm and be, and the shadow settings)"},
    {"space_colonization", "Space colonization (Runions 2007)",
     "a step is one iteration of the algorithm (trunk internodes first): a keyframe at step k changes the nodes grown "
     "from iteration k on",
     "the attraction points the cut branch had removed come back and other branches grow to them: many "
     "short new shoots, each tipped with leaves, so even a small cut can raise the leaf count well above "
     "the uncut tree's (the oak: +84% leaves, +15% nodes for one order-3 branch at step 45)",
     "no attraction point came within reach of the trunk (check the envelope, its offset and d_i)"},
    {"guiding_vectors", "Guiding vectors (Xu & Mould 2015)",
     "a step is one generation of endpoints and shortest paths: a keyframe at step k changes the paths added from "
     "generation k on",
     "the cut branch's graph vertices are free again, so later paths and endpoints can take them",
     "no step found an endpoint to grow to (check the endpoints per step and the endpoint volume)"},
    {"lsystem", "L-system (Honda / ABOP)",
     "a step is one derivation: a keyframe at step k changes the productions applied in derivation k (minimum "
     "length now; angles, length and width ratios of the daughters, which appear in step k+1)",
     "the cut branch's apices stop: nothing regrows from a cut in Honda's model",
     "the axiom and productions drew no internode"},
};
static_assert(std::size(generator_table) == std::variant_size_v<generator_params>, "one generator_table row per generator");
inline constexpr int generator_count = int(std::size(generator_table));

namespace detail {
template <const char* generator_row::*column>
constexpr std::array<const char*, generator_count + 1> generator_column() {
  std::array<const char*, generator_count + 1> out{};   // null-terminated
  for (int i = 0; i < generator_count; ++i) out[i] = generator_table[i].*column;
  return out;
}
inline constexpr auto generator_name_column = generator_column<&generator_row::name>();
inline constexpr auto generator_label_column = generator_column<&generator_row::label>();
}  // namespace detail

// The names and the labels as null-terminated lists (the CLI's loops, the editor's combo).
inline constexpr const char* const* generator_names = detail::generator_name_column.data();
inline constexpr const char* const* generator_labels = detail::generator_label_column.data();

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
