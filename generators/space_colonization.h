// Space colonization (Runions, Lane & Prusinkiewicz 2007) with the envelopes, widths and spiral leaves of seed 003.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "generators/params.h"
#include "generators/skeleton.h"

namespace sylva {

// flame: a spindle widest a quarter of the way up, rounded below and drawn out to a point at the
// top (Lombardy poplar, Italian cypress; space_colonization_envelope.cpp, flame_radius).
enum class envelope_shape : int { box = 0, sphere, ellipsoid, hemisphere, cylinder, cone, slab, mesh, flame };
inline constexpr const char* envelope_shape_names[] = {"box",      "sphere", "ellipsoid", "hemisphere", "cylinder",
                                                       "cone",     "slab",   "mesh",      "flame",      nullptr};

struct space_colonization_params {
  // Envelope: where the attraction points lie.
  envelope_shape envelope = envelope_shape::ellipsoid;
  int points = 4000;
  glm::vec3 size{10, 8, 10};
  glm::vec3 offset{0, 7, 0};
  float slab_thickness = 0.3f;
  std::string envelope_mesh;
  // Dents (seeded bays cut into the envelope, so the crown's outline breaks into limb masses).
  int envelope_dents = 0;
  float envelope_dent_depth = 0.4f;
  // Growth (Runions 2007 §3).
  float segment_length = 0.25f;
  float influence_radius = 2.0f;
  float kill_distance = 0.5f;
  float trunk_length = 3.0f;
  glm::vec3 tropism{0, -1, 0};
  float tropism_weight = 0.0f;
  int max_branches = 100000;
  int steps = 400;
  int node_cap = 2000000;
  // Branching habit: bud life, sympodial forks and crooks; all off by default (Runions 2007).
  int bud_life = 0;            // steps a node may sprout laterals after its birth (0: always)
  float fork_length = 0.0f;    // metres an axis grows before its apex forks sympodially (0: never)
  float fork_angle = 50.0f;    // degrees between the two shoots of a fork
  float crook = 0.0f;          // degrees of seeded turn off course for each shoot of a fork
  float max_turn = 180.0f;     // degrees an axis' apex may turn off its last segment per segment (180: any)
  float leader_damage = 0.0f;   // chance a step that an apex dies and forks (leader damage and recovery)
  float fork_asymmetry = 0.0f;  // share by which a fork's leader turns less, and its other shoot more, than half the fork angle
  float twig_droop = 0.0f;      // tropism weight added per order past the limbs (pendulous twigs; 0: none)
  // Growth history (generators/history.h), off by default.
  float season_variation = 0.0f;  // amplitude a of the seasons: step k's segments are D·exp(a·z_k) long
  float live_crown = 1.0f;        // limbs below (1 − this)·height die (1: none do)
  float stub_length = 0.3f;       // metres of a dead limb that stay as a stub
  float sky_lean = 0.0f;          // ψ: phototropism towards the open side (0: none)
  float open_side = 0.0f;         // degrees from +x towards +z: the azimuth of the open sky
  // Widths: pipe model (seed 003's "Da Vinci" rule).
  float pipe_exponent = 2.0f;
  float min_width = 0.01f;
  float max_width = 50.0f;
  float pipe_taper = 0.0f;   // disused pipes per metre (skeleton.h)
  // Leaves on terminal branches along a logarithmic spiral (seed 003).
  int leaves_min = 3;
  int leaves_max = 6;
  float leaf_size_min = 0.12f;
  float leaf_size_max = 0.2f;
  float spiral_a = 0.03f;
  float spiral_k = 0.15f;
  float spiral_e = 2.7182817f;
  float spiral_rounds = 1.0f;
  bool operator==(const space_colonization_params&) const = default;
};

template <params_of<space_colonization_params> P, class V>
void visit_params(P& p, V&& visitor) {
  auto v = declare_class(visitor, param_regrow);   // the generator reads them: a change regrows
  v(p.envelope, param_info{"envelope", "Envelope", "", 0, 8, "Shape the attraction points fill uniformly; mesh: a closed OBJ file; flame: widest a quarter of the way up, tapering to a point (Lombardy poplar)", param_on_release, "Envelope", envelope_shape_names});
  v(p.points, param_info{"points", "Attraction points", "N", 0, 2000000, "Number of attraction points sampled in the envelope (seeded)", param_log | param_on_release});
  v(p.size, param_info{"size", "Size", "", 0.01f, 1000, "Bounding box of the envelope in metres (x, y up, z); a sphere uses x as its diameter, a slab x and y", param_on_release});
  v(p.offset, param_info{"offset", "Offset", "", -1000, 1000, "Centre of the envelope's bounding box in metres; the root stands at the origin", param_on_release});
  v(p.slab_thickness, param_info{"slab_thickness", "Slab thickness", "", 0.001f, 100, "Depth (z) of the slab envelope, for planar trees", param_log | param_on_release});
  v(p.envelope_mesh, param_info{"envelope_mesh", "Envelope mesh", "", 0, 0, "Path of a closed OBJ mesh; it is scaled to fill the size box", param_path | param_on_release});
  v(p.envelope_dents, param_info{"envelope_dents", "Dents", "", 0, 64, "Seeded bays cut into the envelope from outside (0: none), so the crown grows as uneven limb masses with gaps between them instead of a smooth dome", param_on_release});
  v(p.envelope_dent_depth, param_info{"envelope_dent_depth", "Dent depth", "", 0, 0.9f, "How far each dent reaches in, as a share of the envelope's radius in its direction", param_on_release});
  v(p.segment_length, param_info{"segment_length", "Segment length", "D", 0.005f, 10, "Distance between a node and the node it grows (Runions 2007 §3)", param_log | param_on_release, "Growth"});
  v(p.influence_radius, param_info{"influence_radius", "Influence radius", "dᵢ", 0.01f, 100, "A point attracts its nearest node only within this distance (Runions 2007 §3)", param_log | param_on_release});
  v(p.kill_distance, param_info{"kill_distance", "Kill distance", "dₖ", 0, 50, "Points this close to a node are removed (Runions 2007 §3)", param_on_release});
  v(p.trunk_length, param_info{"trunk_length", "Trunk length", "", 0, 100, "The root grows straight up this far, and on until the crown's points reach it", param_on_release});
  v(p.tropism, param_info{"tropism", "Tropism", "g", -1, 1, "Direction blended into every growth direction (gravity, light)", param_direction | param_on_release});
  v(p.tropism_weight, param_info{"tropism_weight", "Tropism weight", "", 0, 1, "Blend: direction = normalize((1−w)·n̂ + w·ĝ)", param_on_release});
  v(p.max_branches, param_info{"max_branches", "Max branches", "", 1, 10000000, "Growth stops cleanly at this many internodes", param_log | param_on_release});
  v(p.steps, param_info{"steps", "Growth steps", "", 0, 20000, "Iterations; each one is a scrubbable growth step (trunk internodes included)", param_on_release});
  v(p.node_cap, param_info{"node_cap", "Node cap", "", 1000, 20000000, "Growth stops at this many nodes and says so", param_log | param_advanced});
  v(p.bud_life, param_info{"bud_life", "Bud life", "", 0, 400, "Apical control: a node can sprout a lateral only this many growth steps after it appears; older wood stays bare and drops the points only it could reach, so limbs branch near their tips instead of as spokes from the trunk (0: always, as in Runions 2007)", param_on_release, "Branching habit"});
  v(p.fork_length, param_info{"fork_length", "Fork length", "", 0, 20, "Sympodial forking: once an axis has grown this far (metres) since its last fork, its apex stops and two shoots a fork angle apart take over, as in oak limbs (0: monopodial axes)", param_on_release});
  v(p.fork_angle, param_info{"fork_angle", "Fork angle", "", 0, 150, "Angle between the two shoots that take over at a sympodial fork", param_degrees | param_on_release});
  v(p.crook, param_info{"crook", "Crook", "", 0, 60, "Each shoot of a fork turns off its course by up to this seeded angle, so limbs zig-zag at their forks (crooked oak limbs)", param_degrees | param_on_release});
  v(p.max_turn, param_info{"max_turn", "Apex turn limit", "", 1, 180, "Most an axis' apex turns off its last segment in one segment; a low limit keeps a shoot that chases points round it from curling into a loop (180: no limit, as Runions 2007)", param_degrees | param_on_release});
  v(p.leader_damage, param_info{"leader_damage", "Leader damage", "", 0, 0.5f, "Chance each growth step that a shoot's apex dies (frost, browsing, insects) and two shoots below it take over as a fork, whatever the fork length: forks and reiterated limbs at seeded places, as on old trees (Hallé, Oldeman & Tomlinson 1978) (0: apices never die)", param_on_release});
  v(p.fork_asymmetry, param_info{"fork_asymmetry", "Fork asymmetry", "", 0, 0.9f, "Unequal forks: the first shoot of a sympodial fork leaves its course by (1 − this) × half the fork angle and takes over the axis, the second by (1 + this) × half, so a limb forks into a leader and a side limb instead of a symmetric Y (0: symmetric)", param_on_release});
  v(p.twig_droop, param_info{"twig_droop", "Twig droop", "", 0, 0.6f, "Pendulous twigs: a segment of order o ≥ 2 blends the tropism with weight w + this·min(o − 1, 3)/3 instead of w, so the limbs keep their course and the finer twigs hang from them, as on a silver birch (Betula pendula: Atkinson 1992, J. Ecol. 80) (0: every order alike, as Runions 2007)", param_on_release});
  v(p.season_variation, param_info{"season_variation", "Season variation", "a", 0, 1, "Years differ: each crown step's segments are D·exp(a·z_k) long, z_k a seeded run of good and poor seasons (AR(1), ρ = 0.5, as tree rings show: Fritts 1976), so shoot lengths and the spacing of forks vary from step to step (0: every step alike)", param_on_release, "Growth history"});
  v(p.live_crown, param_info{"live_crown", "Live crown", "c", 0.05f, 1, "Natural pruning: a limb leaving the trunk below (1 − c) of the tree's height at a step dies in that step, and only a short dead stub stays (Wilson 1984; the foresters' live crown ratio) (1: no limb dies)", param_on_release});
  v(p.stub_length, param_info{"stub_length", "Stub length", "", 0, 3, "Metres of a self-pruned limb that stay on the trunk as a dead, leafless stub, as thick as the limb was when it died (0: it falls whole)", param_on_release});
  v(p.sky_lean, param_info{"sky_lean", "Lean to open sky", "ψ", 0, 1, "Phototropism of the whole tree (Loehle 1986): one side is open (a forest edge, a gap), so every new segment turns towards it, n̂ + ψ·ô normalised, and the attraction points thin out on the shaded side (kept with chance 1 − ψ·(1 − u·ô)/2, u the point's offset from the crown's axis), so the crown grows out and leans towards the light (0: open all round, as Runions 2007)", param_on_release});
  v(p.open_side, param_info{"open_side", "Open side", "", 0, 360, "Azimuth ô of the open sky the tree leans towards, from +x towards +z", param_degrees | param_on_release});
  v(p.pipe_exponent, param_info{"pipe_exponent", "Pipe exponent", "n", 1, 4, "Pipe model r^n = Σ rᵢ^n (the Da Vinci rule; 2 is Leonardo's)", 0, "Widths"});
  v(p.min_width, param_info{"min_width", "Tip radius", "W", 0.0001f, 1, "Radius of a branch tip in metres, the minimum width", param_log});
  v(p.max_width, param_info{"max_width", "Max width", "", 1, 1000, "Largest radius as a multiple of W (50 is a usual cap)", param_log});
  v(p.pipe_taper, param_info{"pipe_taper", "Pipe taper", "τₚ", 0, 1, "Disused pipes (Shinozaki 1964): each metre of internode makes its base this fraction wider than its tip, so every axis tapers from base to tip even where nothing branches off (0: the plain pipe model) (per metre)"});
  v(p.leaves_min, param_info{"leaves_min", "Leaves per segment (min)", "", 0, 64, "Fewest leaves on a terminal segment (used when the leaf mode is generator)", param_own_leaves, "Own leaves (leaf mode: generator)"});
  v(p.leaves_max, param_info{"leaves_max", "Leaves per segment (max)", "", 0, 64, "Most leaves on a terminal segment; 0 for a bare tree", param_own_leaves});
  v(p.leaf_size_min, param_info{"leaf_size_min", "Leaf size (min)", "", 0.001f, 2, "Smallest leaf blade length in metres", param_log | param_own_leaves});
  v(p.leaf_size_max, param_info{"leaf_size_max", "Leaf size (max)", "", 0.001f, 2, "Largest leaf blade length in metres", param_log | param_own_leaves});
  v(p.spiral_a, param_info{"spiral_a", "Spiral a", "a", 0, 1, "Logarithmic spiral r = a·e^(kθ): distance of the first leaf from the axis, metres", param_own_leaves});
  v(p.spiral_k, param_info{"spiral_k", "Spiral k", "k", -1, 1, "Logarithmic spiral r = a·e^(kθ): growth rate per radian", param_own_leaves});
  v(p.spiral_e, param_info{"spiral_e", "Spiral base", "e", 1, 10, "Base of the spiral's exponential (Euler's number by default)", param_own_leaves});
  v(p.spiral_rounds, param_info{"spiral_rounds", "Spiral rounds", "", 0, 8, "Turns of the spiral along one terminal segment", param_own_leaves});
}

// The editor shows the slab's thickness only for the slab envelope, the mesh's path only for the
// mesh envelope, and the dents' depth only once there are dents: the other envelopes ignore them.
inline bool param_relevant(const space_colonization_params& p, const void* field, const param_info&) {
  if (field == &p.slab_thickness) return p.envelope == envelope_shape::slab;
  if (field == &p.envelope_mesh) return p.envelope == envelope_shape::mesh;
  if (field == &p.envelope_dent_depth) return p.envelope_dents > 0;
  if (field == &p.stub_length) return p.live_crown < 1;
  if (field == &p.open_side) return p.sky_lean > 0;
  if (field == &p.fork_asymmetry) return p.fork_length > 0 || p.leader_damage > 0;
  return true;
}

// Attraction points sampled uniformly inside the envelope, and its outline as line pairs.
struct envelope_sample {
  std::vector<glm::vec3> points;
  std::vector<glm::vec3> outline;  // pairs of endpoints
  std::string error;               // "" unless the envelope is unusable (missing or open OBJ mesh)
};
envelope_sample sample_envelope(const space_colonization_params& p, uint64_t seed, bool want_outline = false);

// The largest envelope OBJ file read (docs/DESIGN-NOTES.md, "Input limits"; the same as textures).
inline constexpr uint64_t max_envelope_mesh_bytes = 256ull << 20;
// The OBJ reader behind envelope_mesh, on text (for tests and the fuzz harness). Returns "" or the
// error; with `inside`, (*inside)[i] says whether queries[i], in the mesh's normalised [-1,1]^3
// box, lies inside it.
std::string check_envelope_obj(std::string_view text, const std::vector<glm::vec3>& queries = {},
                               std::vector<bool>* inside = nullptr);

// One influence step: for each point, the index of its nearest node closer than d_i (ties: the lower
// index), or -1. Uses the same incremental grid as the generator.
std::vector<int32_t> find_influencing_nodes(const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& nodes,
                                            float d_i);

// `to` turned back towards `from` (both unit) so that it is at most max_angle radians off it, in the
// plane of the two; `to` itself when it is already within the limit.
glm::vec3 limit_turn(const glm::vec3& from, const glm::vec3& to, float max_angle);
// Growth direction from the sum of unit pulls; a zero sum (opposite points) keeps `previous`.
glm::vec3 growth_direction(const glm::vec3& pull_sum, const glm::vec3& previous, const glm::vec3& tropism,
                           float weight);

// Grows from the given attraction points (the root at the origin). debug->point_value is the step a
// point was removed in, or -1.
tree_skeleton grow_colonization_from_points(const space_colonization_params& p, const std::vector<glm::vec3>& points,
                                            const grow_options& o, grow_report* report = nullptr,
                                            growth_debug* debug = nullptr);

tree_skeleton grow_space_colonization(const space_colonization_params& p, const grow_options& o,
                                      grow_report* report = nullptr, growth_debug* debug = nullptr);

}  // namespace sylva
