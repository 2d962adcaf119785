// Guiding-vector shortest-path trees (Xu & Mould 2015, seed 002): Poisson-disc graph, lazy Yao-8 Dijkstra.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "generators/params.h"
#include "generators/skeleton.h"

namespace sylva {

// How the turn angle t of a guiding vector is chosen (Xu & Mould 2015 §C: t, t(s), t(v)).
enum class gv_t_mode : int { constant = 0, hop_ramp = 1, radial = 2 };
inline constexpr const char* gv_t_mode_names[] = {"constant", "hop_ramp", "radial", nullptr};

// The volume that step 1 samples its endpoints from (Xu & Mould 2015 §D.1).
enum class gv_volume : int { sphere = 0, annulus = 1, box = 2, cone = 3 };
inline constexpr const char* gv_volume_names[] = {"sphere", "annulus", "box", "cone", nullptr};

// Memory caps (memory_bound.h): Poisson points of the graph, and cells of the sampling grid.
inline constexpr int64_t gv_point_cap = 4000000;
inline constexpr uint64_t gv_grid_cell_cap = uint64_t(1) << 26;

struct guiding_vectors_params {
  int steps = 5;
  // Per-step schedules; entry k-1 drives step k, the last entry repeats for later steps.
  std::vector<float> step_t{-3, -3, 1, 1, 1};            // degrees
  std::vector<float> step_endpoints{3, 16, 40, 90, 160};
  std::vector<float> step_hops{1, 5, 4, 3, 2};           // step 1 samples the volume, so entry 0 is unused
  float source_fraction = 1;
  float clear_trunk = 1.2f;  // metres above the root kept free of border endpoints
  gv_t_mode t_mode = gv_t_mode::constant;
  float t_end = 0;           // degrees, hop ramp end
  int ramp_hops = 20;
  float radial_T = 1.0f;     // metres from the trunk axis
  float search_corridor = 2; // later steps search within corridor·h hops of the tree; 0: unbounded
  // Graph.
  float spacing = 0.2f;      // r
  int candidates = 12;       // k
  glm::vec3 domain_size{4.4f, 5.6f, 4.4f};
  float ground_rise = 0;     // no vertex below y = rise·(ρ − base): stems leave the base climbing (0: off)
  float ground_base = 0.1f;  // metres: radius around the root that the rise rule spares
  // Endpoint volume of step 1.
  gv_volume volume = gv_volume::sphere;
  glm::vec3 volume_offset{0, 3.6f, 0};
  glm::vec3 volume_scale{1, 0.9f, 1};
  float volume_outer = 1.5f;
  float volume_inner = 1.2f;
  // Output.
  float pipe_exponent = 2.5f;
  float tip_radius = 0.006f;
  float pipe_taper = 0;   // disused pipes per metre (skeleton.h)
  int node_cap = 2000000;
  bool operator==(const guiding_vectors_params&) const = default;
};

template <params_of<guiding_vectors_params> P, class V>
void visit_params(P& p, V&& visitor) {
  auto v = declare_class(visitor, param_regrow);   // the generator reads them: a change regrows
  v(p.steps, param_info{"steps", "Growth steps", "n", 0, 200, "Number of generation steps; each connects new endpoints to the tree by shortest paths", param_on_release, "Growth"});
  v(p.step_t, param_info{"step_t", "Turn angle per step", "t", -45, 45, "Per step: angle the guiding vector turns per hop about up × g (negative bends up, positive droops); the last entry repeats", param_degrees});
  v(p.step_endpoints, param_info{"step_endpoints", "Endpoints per step", "", 0, 100000, "Per step: how many endpoints (destinations) are sampled; the last entry repeats", param_on_release});
  v(p.step_hops, param_info{"step_hops", "Hop distance per step", "h", 1, 200, "Per step from step 2 on: endpoints are vertices exactly h hops from the tree (border set B_h); longer h gives longer branches. The first entry is unused (step 1 samples the volume)", param_on_release});
  v(p.source_fraction, param_info{"source_fraction", "Source fraction", "", 0, 1, "Share of each step's new path vertices that become sources of the next step"});
  v(p.clear_trunk, param_info{"clear_trunk", "Clear trunk height", "", 0, 50, "From step 2 on, border vertices lower than this above the root are not endpoints, so the trunk base stays bare (not in the paper)"});
  v(p.t_mode, param_info{"t_mode", "Turn rule", "", 0, 2, "constant: t per hop; hop_ramp: t ramps from the step's t to t_end over ramp_hops hops from the source; radial: t inside distance T of the trunk axis, −t beyond (Xu & Mould's t1)", 0, "Guiding vectors", gv_t_mode_names});
  v(p.t_end, param_info{"t_end", "Ramp end angle", "t_end", -45, 45, "hop_ramp: the turn angle reached after ramp_hops hops", param_degrees});
  v(p.ramp_hops, param_info{"ramp_hops", "Ramp length", "", 1, 1000, "hop_ramp: hops from the source over which t goes from the step's t to t_end"});
  v(p.radial_T, param_info{"radial_T", "Radial flip distance", "T", 0, 50, "radial: distance from the trunk axis beyond which t changes sign (metres)"});
  v(p.search_corridor, param_info{"search_corridor", "Search corridor", "", 0, 20, "Steps after the first search shortest paths only within this many times h hops of the tree (Sylva's speed-up, not in the paper); 0 searches the whole graph, exactly as Xu & Mould 2015", param_on_release | param_advanced});
  v(p.spacing, param_info{"spacing", "Point spacing", "r", 0.05f, 2, "Minimum distance between Poisson-disc graph vertices (metres); smaller gives smoother, costlier trees", param_log | param_on_release, "Graph"});
  v(p.candidates, param_info{"candidates", "Candidates per point", "k", 2, 100, "Poisson-disc candidates tried around each accepted point; more leaves fewer holes", param_on_release | param_advanced});
  v(p.domain_size, param_info{"domain_size", "Domain size", "", 0.1f, 20, "Extent of the point box (metres): centred on the trunk in x and z, from the ground up in y", param_on_release});
  v(p.ground_rise, param_info{"ground_rise", "Ground rise", "", 0, 10, "Graph vertices lower than this slope times their distance from the base are left out, so every path leaves the base climbing at least this steeply and no stem runs along the ground (0: off; not in the paper)", param_on_release});
  v(p.ground_base, param_info{"ground_base", "Base radius", "", 0, 5, "Around the root, within this distance (metres), the ground-rise rule keeps every vertex: the stems' common base", param_on_release | param_advanced});
  v(p.volume, param_info{"volume", "Endpoint volume", "", 0, 3, "Shape that step 1 samples endpoints from (sphere, annulus = torus between inner and outer radius, box, cone)", 0, "Endpoint volume", gv_volume_names});
  v(p.volume_offset, param_info{"volume_offset", "Volume centre", "", -50, 50, "Centre of the endpoint volume (metres)"});
  v(p.volume_scale, param_info{"volume_scale", "Volume stretch", "", 0.01f, 50, "Per-axis stretch of the endpoint volume"});
  v(p.volume_outer, param_info{"volume_outer", "Outer radius", "", 0.01f, 50, "Radius of the sphere, outer radius of the annulus, half size of the box, base radius and half height of the cone (metres)"});
  v(p.volume_inner, param_info{"volume_inner", "Inner radius", "", 0, 50, "annulus: inner radius (metres); a large one gives a wide tree"});
  v(p.pipe_exponent, param_info{"pipe_exponent", "Pipe exponent", "n", 1, 4, "Pipe model r^n = Σ r_i^n at branch points", 0, "Branch radii"});
  v(p.tip_radius, param_info{"tip_radius", "Tip radius", "", 0.0005f, 0.1f, "Radius of every branch tip (metres)", param_log});
  v(p.pipe_taper, param_info{"pipe_taper", "Pipe taper", "τₚ", 0, 1, "Disused pipes (Shinozaki 1964): each metre of internode makes its base this fraction wider than its tip, so every axis tapers from base to tip even where nothing branches off (0: the plain pipe model) (per metre)"});
  v(p.node_cap, param_info{"node_cap", "Node cap", "", 1000, 20000000, "Growth stops at this many nodes and says so", param_log | param_advanced});
}

// Endpoints and sources land in growth_debug::points: endpoints with point_value = their step,
// sources with point_value = 0. Lines hold Yao-8 edges of tree vertices (grey) and guiding-vector
// arrows (orange).
tree_skeleton grow_guiding_vectors(const guiding_vectors_params& p, const grow_options& o, grow_report* report = nullptr,
                                   growth_debug* debug = nullptr);

// ---- Building blocks, exposed for the tests --------------------------------------------------

// Poisson-disc points in the box [lo, hi], every pair at least r apart, grown from `first` with a
// FIFO queue and k candidates in the shell [r, 2r] around each point (Xu & Mould 2015 §A). Returns
// false (and no points) when the background grid would be too large or growth was cancelled.
bool sample_poisson_disc(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& first, float r, int k,
                         uint64_t seed, const grow_options& o, std::vector<glm::vec3>& out, std::string* error = nullptr,
                         int64_t point_cap = gv_point_cap);

// The vertices with lazily built Yao-8 out-edges. `point` is reordered into an implicit k-d tree.
struct gv_graph {
  std::vector<glm::vec3> point;
  glm::vec3 lo{0}, hi{0};            // bounding box of the points
  std::vector<glm::vec3> box;        // k-d node id -> tight box (lo at 2·id, hi at 2·id+1)
  float search_radius = 0;           // first-pass Yao-8 search radius (0: one unbounded pass)
  std::vector<int32_t> edge_at;      // per vertex: offset into `edges`, or -1 when not built yet
  std::vector<int32_t> edges;        // 8 targets per built vertex (octant order), -1 for an empty octant
};
// `spacing` (the Poisson r, or 0) only speeds up the edge search; the edges are exact either way.
gv_graph make_gv_graph(std::vector<glm::vec3> points, float spacing = 0);
// Octant of w seen from v: bit c set when w[c] > v[c] (Xu & Mould 2015 §A's partition S_v).
inline int octant_of(const glm::vec3& v, const glm::vec3& w) {
  return (w.x > v.x ? 1 : 0) | (w.y > v.y ? 2 : 0) | (w.z > v.z ? 4 : 0);
}
// The 8 Yao-8 targets of v: the nearest point in each octant (-1 when empty), built on first use.
const int32_t* yao8_edges(gv_graph& g, int32_t v);
// Builds the edges of every vertex not built yet, in parallel on the job pool. The edges equal
// those yao8_edges builds one at a time.
void build_all_yao8_edges(gv_graph& g);

// Xu & Mould 2015 §B: c = ‖v−u‖·(1 − ê·g_u).
float gv_edge_cost(const glm::vec3& u, const glm::vec3& v, const glm::vec3& g_u);
// Xu & Mould 2015 §C: the parent's guiding vector turned by t (radians) about up × g_parent. It stops at
// the pole it turns toward instead of overshooting; at a pole the axis falls back to up × edge_dir.
glm::vec3 turn_guiding_vector(const glm::vec3& g_parent, const glm::vec3& edge_dir, float t);

// The turn-angle rule of one step (radians).
struct gv_turn_rule {
  gv_t_mode mode = gv_t_mode::constant;
  float t = 0, t_end = 0;
  int ramp_hops = 1;
  float radial_T = 1;
  glm::vec3 axis_origin{0};   // trunk axis: the vertical through this point
};

// Per-vertex Dijkstra state, sized once and reset through `touched`.
struct gv_search_state {
  std::vector<float> dist;
  std::vector<int32_t> parent;
  std::vector<glm::vec3> guide;
  std::vector<int32_t> hops;
  std::vector<uint8_t> settled;
  std::vector<int32_t> touched;
};
// Multi-source Dijkstra with lazily built edges and costs (Xu & Mould 2015 §B). Stops when every
// target is settled or nothing is left to reach. With a corridor, only vertices whose entry is
// >= 0 are entered. Returns false when cancelled.
bool search_gv_paths(gv_graph& g, const std::vector<int32_t>& sources, const std::vector<glm::vec3>& source_guide,
                     const gv_turn_rule& rule, const std::vector<int32_t>& targets, gv_search_state& s,
                     const grow_options& o, const std::vector<int32_t>* corridor = nullptr);

}  // namespace sylva
