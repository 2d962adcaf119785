// L-system generator: Honda's parametric tree (Prusinkiewicz, Hammel, Hanan & Měch 1996) and
// general bracketed, parametric L-systems (ABOP) interpreted by a 3D turtle.
#pragma once

#include <string>

#include <glm/mat3x3.hpp>

#include "generators/params.h"
#include "generators/skeleton.h"

namespace sylva {

enum class lsystem_mode : int { honda = 0, text = 1 };
inline constexpr const char* lsystem_mode_names[] = {"honda", "text", nullptr};
// Where text-mode branch widths come from: the turtle's !(w) / #width, or the pipe model.
enum class lsystem_widths : int { turtle = 0, pipe = 1 };
inline constexpr const char* lsystem_widths_names[] = {"turtle", "pipe", nullptr};

struct lsystem_params {
  lsystem_mode mode = lsystem_mode::honda;
  // Honda's model, axiom A(s0, w0):
  //   A(s,w) : s >= min -> !(w)F(s) [+(α1)/(φ1)A(s·r1, w·q^e)] [+(α2)/(φ2)A(s·r2, w·(1−q)^e)]
  // Defaults are tree a of the 1996 paper's Table 1.
  float s0 = 100, w0 = 30, min_length = 0;
  float alpha1 = 35, alpha2 = -35, phi1 = 0, phi2 = 0;  // degrees
  float r1 = 0.75f, r2 = 0.77f, q = 0.5f, e = 0.4f;
  int derivations = 10;
  float scale = 0.02f;     // metres per model unit
  float width_scale = 1;   // multiplies every radius (the paper's widths are diameters in model units)
  // General L-systems (text mode): the full source with #define constants, axiom and productions.
  // Default: ABOP Fig. 1.24d, so that switching to text mode shows a plant at once.
  std::string source =
      "// ABOP Fig. 1.24d\n#define delta 20 // [0,90] branching angle\n#angle delta\n#axiom X\n"
      "X -> F[+X]F[-X]+X\nF -> FF\n";
  float leaf_size = 0.08f;  // metres, for L without a parameter
  // Most textbook systems draw every F at one width; the pipe model instead thickens each segment
  // by what it carries, which is what makes them read as plants.
  lsystem_widths widths = lsystem_widths::turtle;
  float pipe_exponent = 2.0f, tip_radius = 0.004f;
  float pipe_taper = 0.0f;   // disused pipes per metre (skeleton.h), pipe widths only
  // Growth history (generators/history.h), text mode, off by default.
  float season_variation = 0.0f;  // amplitude a: an F of derivation k is exp(a·z_k) times as long
  float live_crown = 1.0f;        // limbs below (1 − this)·height die (1: none do)
  float stub_length = 0.3f;       // metres of a dead limb that stay as a stub
  int node_cap = 2000000;
  int module_cap = 4000000;
  bool operator==(const lsystem_params&) const = default;
};

template <params_of<lsystem_params> P, class V>
void visit_params(P& p, V&& visitor) {
  auto v = declare_class(visitor, param_regrow);   // the generator reads them: a change regrows
  v(p.mode, param_info{"mode", "Model", "", 0, 1, "honda: Honda's binary tree (Prusinkiewicz et al. 1996); text: a general L-system", 0, "Model", lsystem_mode_names});
  v(p.derivations, param_info{"derivations", "Derivations", "n", 0, 24, "Number of derivation steps; derivation k is growth step k", param_on_release});
  v(p.s0, param_info{"s0", "Trunk length", "s₀", 1, 1000, "Length of the first internode, in model units (axiom A(s₀,w₀))", 0, "Honda tree"});
  v(p.w0, param_info{"w0", "Trunk width", "w₀", 0.1f, 200, "Width of the first internode, in model units"});
  v(p.min_length, param_info{"min", "Minimum length", "min", 0, 100, "Apices shorter than this stop growing (condition s ≥ min)"});
  v(p.alpha1, param_info{"alpha1", "Branch angle 1", "α₁", -180, 180, "Turn (+) of the first daughter branch", param_degrees});
  v(p.alpha2, param_info{"alpha2", "Branch angle 2", "α₂", -180, 180, "Turn (+) of the second daughter branch", param_degrees});
  v(p.phi1, param_info{"phi1", "Divergence 1", "φ₁", -180, 180, "Roll (/) of the first daughter branch", param_degrees});
  v(p.phi2, param_info{"phi2", "Divergence 2", "φ₂", -180, 180, "Roll (/) of the second daughter branch", param_degrees});
  v(p.r1, param_info{"r1", "Length ratio 1", "r₁", 0.05f, 1.2f, "First daughter's length = s·r₁"});
  v(p.r2, param_info{"r2", "Length ratio 2", "r₂", 0.05f, 1.2f, "Second daughter's length = s·r₂"});
  v(p.q, param_info{"q", "Width split", "q", 0, 1, "Share of the parent's width going to the first daughter (w·q^e vs w·(1−q)^e)"});
  v(p.e, param_info{"e", "Width exponent", "e", 0, 1, "Width decrease exponent; widths then obey w^(1/e) = w₁^(1/e) + w₂^(1/e)"});
  v(p.scale, param_info{"scale", "Scale", "", 0.0005f, 1, "Metres per model unit", param_log, "Output"});
  v(p.width_scale, param_info{"width_scale", "Width scale", "", 0.05f, 5, "Multiplies every branch radius"});
  v(p.node_cap, param_info{"node_cap", "Node cap", "", 1000, 20000000, "Growth stops at this many nodes and says so", param_log | param_advanced});
  v(p.source, param_info{"source", "L-system", "", 0, 0, "The L-system text (text mode)", param_multiline, "L-system text"});
  v(p.leaf_size, param_info{"turtle_leaf_size", "Leaf size", "", 0.005f, 1, "Blade length in metres of a leaf placed by L (L(s) gives s model units instead)", param_log | param_own_leaves});
  v(p.widths, param_info{"widths", "Widths", "", 0, 1, "turtle: widths from !(w) and #width; pipe: the pipe model r^n = Σ r_i^n from thin tips (Shinozaki 1964)", 0, nullptr, lsystem_widths_names});
  v(p.pipe_exponent, param_info{"pipe_exponent", "Pipe exponent", "n", 1, 4, "Pipe model exponent (pipe widths): 2 keeps the cross-section area, larger gives thinner trunks"});
  v(p.tip_radius, param_info{"tip_radius", "Tip radius", "r₀", 0.0002f, 0.1f, "Radius of the youngest segments in metres (pipe widths)", param_log});
  v(p.pipe_taper, param_info{"pipe_taper", "Pipe taper", "τₚ", 0, 1, "Disused pipes (Shinozaki 1964): each metre of internode makes its base this fraction wider than its tip, so every axis tapers from base to tip even where nothing branches off (0: the plain pipe model) (pipe widths; per metre)"});
  v(p.season_variation, param_info{"season_variation", "Season variation", "a", 0, 1, "Years differ: every F written by derivation k is exp(a·z_k) times as long, z_k a seeded run of good and poor seasons (AR(1), ρ = 0.5, as tree rings show: Fritts 1976), so a good year's leader internode and laterals are long together and a poor year's short: uneven tiers (0: every derivation alike)", 0, "Growth history"});
  v(p.live_crown, param_info{"live_crown", "Live crown", "c", 0.05f, 1, "Natural pruning: a limb leaving the trunk below (1 − c) of the tree's height at a derivation dies in that derivation, and only a short dead stub stays (Wilson 1984; the foresters' live crown ratio) (1: no limb dies)"});
  v(p.stub_length, param_info{"stub_length", "Stub length", "", 0, 3, "Metres of a self-pruned limb that stay on the trunk as a dead, leafless stub (0: it falls whole)"});
  v(p.module_cap, param_info{"module_cap", "Module cap", "", 1000, 50000000, "Derivation stops at this many modules and says so", param_log | param_advanced});
}

// Honda's sliders only in honda mode, the text-mode settings only in text mode (editor only).
inline bool param_relevant(const lsystem_params& p, const void* field, const param_info&) {
  const bool honda_only = field == &p.s0 || field == &p.w0 || field == &p.min_length || field == &p.alpha1 ||
                          field == &p.alpha2 || field == &p.phi1 || field == &p.phi2 || field == &p.r1 ||
                          field == &p.r2 || field == &p.q || field == &p.e;
  const bool text_only = field == &p.source || field == &p.leaf_size || field == &p.module_cap ||
                         field == &p.widths || field == &p.pipe_exponent || field == &p.tip_radius ||
                         field == &p.pipe_taper || field == &p.season_variation || field == &p.live_crown ||
                         field == &p.stub_length;
  if (field == &p.stub_length && p.live_crown >= 1) return false;
  if (honda_only) return p.mode == lsystem_mode::honda;
  if (text_only) return p.mode == lsystem_mode::text;
  return true;
}

// The turtle's handedness, shared by the text turtle and Honda's tree (see lsystem_turtle.cpp):
// frame columns H, L, U; ABOP §1.5's matrices as printed; start H = +Y, L = +X, U = −Z.
glm::mat3 lsystem_start_frame();
glm::mat3 turtle_turn(const glm::mat3& frame, float degrees);   // +(δ): R_U(δ); -(δ) is turtle_turn(−δ)
glm::mat3 turtle_pitch(const glm::mat3& frame, float degrees);  // &(δ): R_L(δ); ^(δ) is turtle_pitch(−δ)
glm::mat3 turtle_roll(const glm::mat3& frame, float degrees);   // \(δ): R_H(δ); /(δ) is turtle_roll(−δ)

// Honda's tree (derivation k = growth step k). Deterministic; no randomness.
tree_skeleton grow_honda(const lsystem_params& p, const grow_options& o, grow_report* report = nullptr);

// Dispatches on p.mode.
tree_skeleton grow_lsystem(const lsystem_params& p, const grow_options& o, grow_report* report = nullptr,
                           growth_debug* debug = nullptr);

}  // namespace sylva
