// The wood pass: every generator's skeleton bends under its own load, step by step, and
// young shoots curve back toward their set direction (reaction wood). DESIGN §3 "shared passes".
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "generators/params.h"
#include "generators/skeleton.h"

namespace sylva {

struct wood_params {
  // 0: the pass is off and the skeleton is exactly the generator's; 1: real weight. It multiplies g,
  // so 2 is a tree twice as heavy for its wood.
  float gravity = 0;
  // Green wood with its water: specific gravity about 0.56-0.60 for the oaks, maples and beech
  // (USDA FPL Wood Handbook, FPL-GTR-190, 2010, Table 5-3a) times 1 + a green moisture content of
  // 64-80 % (same handbook, Table 4-1) gives about 950-1,050 kg/m³.
  float density = 1000;       // kg/m³
  // Modulus of elasticity of green hardwood: white oak 8.6 GPa, northern red oak 9.3 GPa, American
  // beech 9.5 GPa, sugar maple 10.7 GPa (Wood Handbook 2010, Table 5-3a, green condition).
  float modulus = 9;          // GPa
  // Fresh mass of one broadleaf blade with its petiole: an estimate, about 0.5-1 g for a 40-60 cm²
  // blade at a leaf mass per area near 80 g/m² dry (Wright et al. 2004, the leaf economics
  // spectrum) and about 60 % water.
  float leaf_mass = 0.8f;     // grams
  float leaves_per_metre = 16;  // leaves per metre of young shoot (the foliage model's 6 cm spacing)
  int leaf_age = 1;           // a shoot carries leaves while its age in steps is at most this
  float recovery = 0.2f;      // share of a young shoot's deviation from its set direction undone per step
  int recovery_age = 2;       // shoots recover while their age in steps is at most this
  float recovery_up = 0;      // the set direction: 0 the generator's own, 1 straight up
  float max_bend = 30;        // degrees: most an internode may bend; more load is clamped and reported
  // The soil: a shoot bent below this height above its tree's base rests on the ground there,
  // laid level in the direction it was heading (its length kept), and carries its descendants
  // with it. A negative value switches the soil off.
  float ground_rest = 0.05f;  // metres
  bool operator==(const wood_params&) const = default;
};

template <params_of<wood_params> P, class V>
void visit_params(P& p, V&& visitor) {
  auto v = declare_class(visitor, param_regrow);   // the wood pass bends the grown tree: a change regrows
  v(p.gravity, param_info{"gravity", "Gravity", "", 0, 10, "Weight of wood and leaves bends every branch (0: off, the generator's own shape; 1: real weight, g = 9.81 m/s²)", param_on_release, "Wood"});
  v(p.density, param_info{"wood_density", "Wood density", "ρ", 100, 1500, "Green wood with its water, kg/m³ (about 1,000 for oak, maple, beech: USDA Wood Handbook 2010, Tables 4-1 and 5-3a)", param_on_release});
  v(p.modulus, param_info{"youngs_modulus", "Young's modulus", "E", 0.5f, 30, "Stiffness of green wood, GPa (8.6 white oak, 9.3 red oak, 10.7 sugar maple: Wood Handbook 2010, Table 5-3a); a branch's stiffness is E·πr⁴/4", param_log | param_on_release});
  v(p.leaf_mass, param_info{"leaf_mass", "Leaf mass", "", 0, 50, "Fresh mass of one leaf in grams (0.5-1 g for a broadleaf)", param_on_release});
  v(p.leaves_per_metre, param_info{"leaves_per_metre", "Leaves per metre", "", 0, 500, "Leaves carried per metre of young shoot, for the load (the foliage pass places the visible ones)", param_on_release | param_advanced});
  v(p.leaf_age, param_info{"foliage_age", "Foliage age", "", 0, 64, "A shoot carries leaves while it is at most this many steps old (1: deciduous, 3-7: conifers)", param_on_release | param_advanced});
  v(p.recovery, param_info{"recovery", "Gravitropic recovery", "", 0, 1, "Reaction wood: share of a young shoot's sag undone per step, so a bent branch turns up at its tip", param_on_release});
  v(p.recovery_age, param_info{"recovery_age", "Recovery age", "", 0, 64, "Shoots form reaction wood while they are at most this many steps old", param_on_release | param_advanced});
  v(p.recovery_up, param_info{"recovery_up", "Recover toward up", "", 0, 1, "Direction shoots recover toward: 0 the generator's own (its set angle), 1 straight up", param_on_release | param_advanced});
  v(p.ground_rest, param_info{"ground_rest", "Rest on the ground", "", -1, 2, "A shoot that bends down to this height above the tree's base rests on the soil there instead of passing through it (metres; below 0: no soil)", param_on_release | param_advanced});
  v(p.max_bend, param_info{"max_bend", "Maximum bend", "", 1, 90, "Most an internode may bend; a heavier load is clamped here and the status bar says so", param_degrees | param_on_release | param_advanced});
}

// What scrubbing needs to show the bend of an earlier step without regrowing: the generator's
// unbent positions, the parameters and the steps at which the pass bent the tree.
struct wood_history {
  std::vector<glm::vec3> rest;        // the generator's positions, before the pass
  wood_params params;
  std::vector<uint16_t> bend_steps;   // ascending; every step unless the tree is large (wood.cpp)
};

// Runs the pass on a generator's skeleton: positions are bent, generator-placed leaves follow their
// node, and t.wood records the history. Does nothing when p.gravity is 0. Clamped bends and clamped
// parameters are reported in report->message. Radii are not changed, so the pipe model still holds.
void apply_wood(tree_skeleton& t, const wood_params& p, grow_report* report = nullptr);

// Node positions of the tree as it stood at `step` (same indices as t.position; nodes not alive
// then get the position the pass would give them). Replays the pass from the recorded history,
// O(nodes × bend steps up to `step`); without a history it is t.position.
std::vector<glm::vec3> positions_at_step(const tree_skeleton& t, int step);

// One bend of the whole skeleton under its load, with no history and no recovery: the static
// small-deflection answer (for tests and checks). point_mass: optional extra kg at each node.
std::vector<glm::vec3> bend_static(const tree_skeleton& t, const wood_params& p,
                                   const std::vector<float>* point_mass = nullptr);

}  // namespace sylva
