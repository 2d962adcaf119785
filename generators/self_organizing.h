// Self-organizing trees (Palubicki et al. 2009) with the extensions of seed 001.
#pragma once

#include <vector>

#include "generators/params.h"
#include "generators/skeleton.h"

namespace sylva {

enum class so_environment : int { shadow = 0, markers = 1 };
inline constexpr const char* so_environment_names[] = {"shadow_propagation", "space_colonization", nullptr};
enum class so_allocation : int { borchert_honda = 0, priority = 1 };
inline constexpr const char* so_allocation_names[] = {"borchert_honda", "priority", nullptr};
// spiral: one lateral bud per node, each turned by φ from the last; planar: seed 000's ±β in one
// plane; opposite: two lateral buds per node on opposite sides, each pair turned by φ from the last
// (φ = 90°: decussate, as in maples, ashes and horse chestnuts).
enum class so_phyllotaxis : int { spiral = 0, planar = 1, opposite = 2 };
inline constexpr const char* so_phyllotaxis_names[] = {"spiral", "planar", "opposite", nullptr};
enum class so_placement : int { grid = 0, random = 1, explicit_positions = 2 };
inline constexpr const char* so_placement_names[] = {"grid", "random", "explicit", nullptr};
// Priority model: how an axis ranks its buds and lateral branches (seed 000 sorts by the average).
enum class so_priority_rank : int { average = 0, summed = 1 };
inline constexpr const char* so_priority_rank_names[] = {"average", "summed", nullptr};
// How a node's light enters the flow: each live bud counts it, or the node counts it once (seed 001).
enum class so_light_count : int { per_bud = 0, per_node = 1 };
inline constexpr const char* so_light_count_names[] = {"per_bud", "per_node", nullptr};
// Upkeep normalisation: BM·(r/r₀)^BE, or seed 001's printed BM·r^BE/r₀ (r in metres).
enum class so_upkeep_form : int { relative = 0, seed001 = 1 };
inline constexpr const char* so_upkeep_form_names[] = {"relative", "seed001", nullptr};

// Memory cap: markers of the space-colonization environment, all trees together.
inline constexpr int64_t so_marker_cap = 8000000;

struct self_organizing_params {
  int steps = 27;                     // about 20,000 internodes with the defaults
  float internode_length = 0.1f;      // metres
  so_environment environment = so_environment::shadow;
  // Shadow propagation (Palubicki 2009 §4.2); seed 000's values.
  float shadow_a = 0.2f, shadow_b = 2.0f;
  int q_max = 4;
  float full_exposure = 1.0f;         // C
  float voxel_size = 1.0f;            // internode lengths
  // Perception (both environments).
  float perception_angle = 45;        // degrees, half-angle of the cone
  float perception_distance = 1.5f;     // internode lengths
  // Space-colonization environment (Palubicki 2009 §4.1).
  int marker_count = 20000;           // per tree
  float occupancy_radius = 1;         // internode lengths
  float envelope_radius = 3;          // metres
  float envelope_bottom = 0;          // metres above the root (buds outside see no markers)
  float envelope_top = 8;
  // Light to resource (seed 001 eqs. 1–2).
  float sigma = 0.5f;
  float bm = 0.02f, be = 1.3f;
  int shed_min_buds = 20;             // N_min; 0 disables shedding
  so_light_count light_count = so_light_count::per_bud;
  so_upkeep_form upkeep_form = so_upkeep_form::relative;
  // Allocation.
  so_allocation allocation = so_allocation::borchert_honda;
  float alpha = 2, lambda = 0.55f;
  float season_variation = 0;         // years differ: step k's α is α·exp(a·z_k) (generators/history.h)
  float live_crown = 1;               // limbs below (1 − this)·height die and leave stubs (1: none do)
  float stub_length = 0.3f;           // metres of a dead limb that stay as a stub
  float sky_lean = 0;                 // ψ: phototropism towards the open side (0: none)
  float open_side = 0;                // degrees from +x towards +z: the azimuth of the open sky
  float w_max = 1.0f, w_min = 0.006f, kappa = 0.5f;
  int terminal_priority_steps = 8;
  so_priority_rank priority_rank = so_priority_rank::average;
  // Shoots.
  float w_default = 1.0f, w_optimal = 0.5f, w_tropism = 0.3f;  // seed 000 fig. 6
  glm::vec3 tropism{0, 1, 0};
  float branch_angle = 45;            // degrees
  float divergence = 137.5f;          // degrees
  so_phyllotaxis phyllotaxis = so_phyllotaxis::spiral;
  // Radii.
  float pipe_exponent = 2, tip_radius = 0.003f;
  float pipe_taper = 0;   // disused pipes per metre (skeleton.h), applied to the final radii
  // Forest.
  int tree_count = 1;
  so_placement placement = so_placement::grid;
  float spacing = 4;                  // metres
  std::vector<glm::vec3> positions;
  int node_cap = 2000000;
  bool operator==(const self_organizing_params&) const = default;
};

template <params_of<self_organizing_params> P, class V>
void visit_params(P& p, V&& visitor) {
  auto v = declare_class(visitor, param_regrow);   // the generator reads them: a change regrows
  v(p.steps, param_info{"steps", "Growth steps", "N", 0, 200, "Number of growth steps (iterations)", param_on_release, "Growth"});
  v(p.internode_length, param_info{"internode_length", "Internode length", "l", 0.005f, 2, "Length of one metamer's internode in metres; a shoot of resource v has ⌊v⌋ internodes of length l·v/⌊v⌋", param_log});
  v(p.environment, param_info{"environment", "Bud environment", "", 0, 1, "shadow_propagation: light from a sparse shadow grid; space_colonization: markers in an envelope (Palubicki 2009 §4)", 0, nullptr, so_environment_names});
  v(p.shadow_a, param_info{"shadow_a", "Shadow a", "a", 0, 2, "Shadow a bud adds to its own voxel; one layer lower it adds a·b^-1, and so on (Δs = a·b^-q)", 0, "Shadow propagation"});
  v(p.shadow_b, param_info{"shadow_b", "Shadow falloff b", "b", 1.01f, 8, "Base of the shadow falloff with depth q (b > 1)"});
  v(p.q_max, param_info{"q_max", "Shadow depth", "q_max", 0, 16, "Layers of the shadow pyramid below a bud"});
  v(p.full_exposure, param_info{"full_exposure", "Full exposure", "C", 0.01f, 10, "Light of an unshaded bud: Q = max(C − s + a, 0)"});
  v(p.voxel_size, param_info{"voxel_size", "Voxel size", "", 0.25f, 8, "Shadow voxel edge in internode lengths", param_on_release});
  v(p.perception_angle, param_info{"perception_angle", "Perception angle", "θ", 1, 180, "Half-angle of the cone around a bud's default direction in which it looks for light or markers", param_degrees, "Perception"});
  v(p.perception_distance, param_info{"perception_distance", "Perception distance", "r", 0.5f, 10, "Radius of the perception cone in internode lengths"});
  v(p.marker_count, param_info{"marker_count", "Markers", "", 0, 1000000, "Marker points per tree in the crown envelope", param_log | param_on_release, "Space colonization"});
  v(p.occupancy_radius, param_info{"occupancy_radius", "Occupancy radius", "ρ", 0.1f, 10, "Markers this close to a node (internode lengths) are removed"});
  v(p.envelope_radius, param_info{"envelope_radius", "Crown radius", "", 0.1f, 100, "Horizontal radius of the ellipsoidal crown envelope (metres)"});
  v(p.envelope_bottom, param_info{"envelope_bottom", "Crown bottom", "", 0, 100, "Height of the envelope's bottom above the root (metres)"});
  v(p.envelope_top, param_info{"envelope_top", "Crown top", "", 0.1f, 200, "Height of the envelope's top above the root (metres)"});
  v(p.sigma, param_info{"sigma", "Light conversion", "σ", 0, 2, "Light to resource (Yi et al. 2018): Q = l^((T−T₀)^σ) for a bud of age T−T₀ ≥ 1", 0, "Light and upkeep"});
  v(p.bm, param_info{"bm", "Maintenance", "BM", 0, 2, "Maintenance (Měch & Prusinkiewicz 1996): BM·(r/r₀)^BE is subtracted as Q flows down"});
  v(p.be, param_info{"be", "Maintenance exponent", "BE", 0.1f, 4, "Exponent of the branch maintenance cost"});
  v(p.shed_min_buds, param_info{"shed_min_buds", "Shedding threshold", "N_min", 0, 1000, "A branch with negative flow supporting fewer buds than this is shed (0: never)"});
  v(p.light_count, param_info{"light_count", "Light counted", "", 0, 1, "per_bud: each live bud of a node counts the node's light; per_node: it counts once for a node with either bud (split between its buds)", 0, nullptr, so_light_count_names});
  v(p.upkeep_form, param_info{"upkeep_form", "Upkeep form", "", 0, 1, "relative: BM·(r/r₀)^BE; seed001: the seed's printed BM·r^BE/r₀ with r in metres (= r₀^(BE−1)·relative)", 0, nullptr, so_upkeep_form_names});
  v(p.allocation, param_info{"allocation", "Allocation model", "", 0, 1, "borchert_honda: split at each branch point; priority: sort the buds of each axis (Palubicki 2009 §5)", 0, "Allocation", so_allocation_names});
  v(p.alpha, param_info{"alpha", "Resource factor", "α", 0, 20, "v_base = α·Q_base"});
  v(p.season_variation, param_info{"season_variation", "Season variation", "a", 0, 1, "Years differ: year k's resource is v_base = α·exp(a·z_k)·Q_base, z_k a seeded run of good and poor seasons (AR(1), ρ = 0.5, as tree rings show: Fritts 1976), so a good year's shoots are long and many, a poor year's short and few (0: every year alike, as Palubicki 2009)"});
  v(p.lambda, param_info{"lambda", "Apical bias", "λ", 0, 1, "Borchert–Honda: share of resource sent to the main axis"});
  v(p.w_max, param_info{"w_max", "Top priority weight", "w_max", 0, 2, "Priority model: weight of the best-lit bud of an axis"});
  v(p.w_min, param_info{"w_min", "Low priority weight", "w_min", 0, 2, "Priority model: weight of the buds ranked at or after κN"});
  v(p.kappa, param_info{"kappa", "Priority span", "κ", 0.01f, 1, "Priority model: share of an axis' buds with linearly falling weights"});
  v(p.terminal_priority_steps, param_info{"terminal_priority_steps", "Terminal priority until", "", 0, 200, "Priority model: up to this step the terminal bud ranks first regardless of its light"});
  v(p.priority_rank, param_info{"priority_rank", "Rank buds by", "", 0, 1, "Priority model: average: rank by the average light of the buds each candidate supports; summed: by its total flow, which favours big lateral branches", 0, nullptr, so_priority_rank_names});
  v(p.w_default, param_info{"w_default", "Default weight", "ξ", 0, 4, "Weight of the default direction (previous internode or lateral bud)", 0, "Shoots"});
  v(p.w_optimal, param_info{"w_optimal", "Optimal weight", "ζ", 0, 4, "Weight of the optimal direction (least shadow / towards markers)"});
  v(p.w_tropism, param_info{"w_tropism", "Tropism weight", "τ", 0, 4, "Weight of the tropism vector (η in Palubicki et al. 2009)"});
  v(p.tropism, param_info{"tropism", "Tropism", "g", -1, 1, "Tropism vector: (0,-1,0) bends towards gravity, (0,1,0) towards the light above"});
  v(p.branch_angle, param_info{"branch_angle", "Branching angle", "β", 0, 120, "Angle between an axis and its lateral buds", param_degrees});
  v(p.divergence, param_info{"divergence", "Divergence", "φ", 0, 360, "Phyllotactic angle between successive lateral buds (opposite phyllotaxis: between successive pairs)", param_degrees});
  v(p.phyllotaxis, param_info{"phyllotaxis", "Phyllotaxis", "", 0, 2, "spiral: one lateral bud per node, turned by φ from the last; planar: ±β in one plane (flat trees); opposite: a pair of lateral buds on opposite sides of each node, each pair turned by φ from the last (φ = 90°: decussate, as in maples and ashes)", 0, nullptr, so_phyllotaxis_names});
  v(p.live_crown, param_info{"live_crown", "Live crown", "c", 0.05f, 1, "Natural pruning: a limb leaving a stem below (1 − c) of the tree's height at a step dies in that step, and only a short dead stub stays (Wilson 1984; the foresters' live crown ratio) (1: no limb dies)", 0, "Growth history"});
  v(p.stub_length, param_info{"stub_length", "Stub length", "", 0, 3, "Metres of a self-pruned limb that stay on the stem as a dead, leafless stub, as thick as the limb was when it died (0: it falls whole)"});
  v(p.sky_lean, param_info{"sky_lean", "Lean to open sky", "ψ", 0, 1, "Phototropism of the whole tree (Loehle 1986): one side is open (a forest edge, a gap), so a shoot's direction gains a fourth term, ξ·default + ζ·optimal + τ·g + ψ·ô (Palubicki 2009 §5 with the open side ô), and the crown leans and grows out towards the light (0: open all round, as Palubicki 2009)"});
  v(p.open_side, param_info{"open_side", "Open side", "", 0, 360, "Azimuth ô of the open sky the tree leans towards, from +x towards +z", param_degrees});
  v(p.pipe_exponent, param_info{"pipe_exponent", "Pipe exponent", "n", 1.5f, 4, "Pipe model r^n = Σ r_i^n", 0, "Radii"});
  v(p.tip_radius, param_info{"tip_radius", "Tip radius", "r₀", 0.0002f, 0.1f, "Radius of a branch tip in metres", param_log});
  v(p.pipe_taper, param_info{"pipe_taper", "Pipe taper", "τₚ", 0, 1, "Disused pipes (Shinozaki 1964): each metre of internode makes its base this fraction wider than its tip, so every axis tapers from base to tip even where nothing branches off (0: the plain pipe model) (per metre)"});
  v(p.tree_count, param_info{"tree_count", "Trees", "", 1, 400, "Trees growing together in one environment", param_on_release, "Forest"});
  v(p.placement, param_info{"placement", "Placement", "", 0, 2, "grid, random in a square, or the explicit positions", 0, nullptr, so_placement_names});
  v(p.spacing, param_info{"spacing", "Spacing", "", 0.1f, 100, "Distance between grid neighbours; random placement uses a square of side spacing·√count"});
  v(p.positions, param_info{"positions", "Positions", "", -1000, 1000, "Explicit tree positions (metres)", param_advanced});
  v(p.node_cap, param_info{"node_cap", "Node cap", "", 1000, 20000000, "Growth stops at this many nodes and says so", param_log | param_advanced});
}

// The editor shows the open side's azimuth only once the tree leans towards it.
inline bool param_relevant(const self_organizing_params& p, const void* field, const param_info&) {
  if (field == &p.open_side) return p.sky_lean > 0;
  return true;
}

tree_skeleton grow_self_organizing(const self_organizing_params& p, const grow_options& o, grow_report* report = nullptr,
                                   growth_debug* debug = nullptr);

// The model's pieces, exposed for the tests.

// Extended Borchert–Honda (Palubicki 2009 eq. 4–5): splits v between the main axis and the lateral.
// When both Q are 0 the resource stays on the main axis.
void split_borchert_honda(float v, float q_main, float q_lateral, float lambda, float& v_main, float& v_lateral);
// Priority weight of rank i (0 = best) among n buds (seed 000 eq. 2).
float priority_weight(int i, int n, float w_max, float w_min, float kappa);
// Priority allocation (seed 000 eq. 1): q sorted best first; v_i = v·Q_i·w_i / Σ Q_j·w_j.
void allocate_priority(float v, const std::vector<float>& q, float w_max, float w_min, float kappa,
                       std::vector<float>& out);
// Bud fate: a bud with resource v < 1 makes no shoot; otherwise ⌊v⌋ metamers of length l·v/⌊v⌋.
struct shoot_plan {
  int metamers = 0;
  float length = 0;
};
shoot_plan plan_shoot(float v, float internode_length);
// Shedding (seed 001, Měch & Prusinkiewicz 1996): the nodes to shed, given each node's basipetal
// flow and the number of buds it supports. A non-root node goes when its flow is negative and it
// supports fewer than n_min buds; its whole subtree goes with it. Returns per node 1 = shed.
std::vector<uint8_t> select_shed(const std::vector<int32_t>& parent, const std::vector<float>& flow,
                                 const std::vector<int32_t>& buds, int n_min);

}  // namespace sylva
