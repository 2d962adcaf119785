// The tree every generator produces: flat arrays with a birth/death step per node (DESIGN §2).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace sylva {

struct wood_history;  // generators/wood.h

inline constexpr uint16_t never_died = std::numeric_limits<uint16_t>::max();

struct leaf {
  glm::vec3 position{0};      // metres
  glm::quat orientation{1, 0, 0, 0};  // leaf blade in local XY, normal +Z, petiole along -Y
  float size = 0.1f;          // blade length in metres
  uint16_t born = 0;          // growth step in which it appeared
  uint16_t died = never_died; // step in which it was shed (with its node)
  int32_t node = -1;          // node it hangs on
  uint8_t archetype = 255;    // leaf_archetype of its card; 255: the mesh's leaf archetype
};

struct tree_skeleton {               // node i is the tip of the internode from parent[i] to i
  std::vector<glm::vec3> position;   // metres, +Y up (glTF convention)
  std::vector<int32_t> parent;       // -1 for a root; always parent[i] < i
  std::vector<float> radius;         // at the node, once fully grown (the final tree)
  std::vector<uint16_t> born;        // growth step in which the node appeared (0 = seedling)
  std::vector<uint16_t> died;        // step in which it was shed, or never_died
  std::vector<uint8_t> order;        // branch order: 0 trunk, 1 first lateral, ...
  // Step from which a node stands as dead wood: it stays, bare of leaves (a self-pruned limb's stub,
  // generators/history.h); never_died while it lives. Empty when no node is dead wood.
  std::vector<uint16_t> dead;
  std::vector<leaf> leaves;
  // When pipe_exponent > 0 the radii are pipe-model radii of the living tree, so they change over
  // time: the view at step s recomputes them from the nodes alive at s (O(n), DESIGN §2).
  // When 0, each node keeps `radius` from birth to death.
  float pipe_exponent = 0;
  float pipe_tip_radius = 0;
  float pipe_taper = 0;              // disused pipes per metre (compute_pipe_radii), 0: none
  int steps = 0;                     // number of growth steps taken
  int tree_count = 1;                // forests: roots are the nodes with parent -1, one per tree
  // Set by the wood pass: what positions_at_step (generators/wood.h) replays to show the bend of
  // an earlier step; null when the tree was not bent.
  std::shared_ptr<const wood_history> wood;

  size_t size() const { return position.size(); }
  bool alive(size_t i, int step) const { return born[i] <= step && step < died[i]; }
  // The step from which node i is dead wood (never_died: it lives while it stands).
  uint16_t dead_from(size_t i) const { return dead.empty() ? never_died : dead[i]; }
  // Appends a node and returns its index.
  int32_t add_node(const glm::vec3& p, int32_t par, float r, uint16_t born_step, uint8_t ord);
  void reserve(size_t n);
};

// The minimum a consumer (the mesher) needs to index the arrays safely: every array as long as
// position, and -1 <= parent[i] < i. Anything else degrades the picture, not memory.
bool structurally_sound(const tree_skeleton& t);

// Checks every invariant of DESIGN §2; returns "" when valid, else the first violation.
std::string validate_skeleton(const tree_skeleton& s);

// Pipe model (Shinozaki et al. 1964; Macdonald 1983): r^n = Σ r_i^n over the children, with
// terminal nodes at r_tip. Writes radius for the nodes alive at `step` (every node when step < 0);
// the others get 0. Relies on parent[i] < i, so one reverse sweep suffices.
// Taper (disused pipes): Shinozaki's stem keeps the pipes of the shoots it once carried, so an axis
// thickens downward even where nothing branches off. With `taper` τ > 0 and the node positions,
// each internode of length ℓ is (1 + τ·ℓ) times wider at its base than at its tip, and passes
// (r_i·(1 + τ·ℓ_i))^n down to its parent; τ = 0 (or no positions) is the plain pipe model.
void compute_pipe_radii(const std::vector<int32_t>& parent, const std::vector<uint16_t>& born,
                        const std::vector<uint16_t>& died, int step, float exponent, float r_tip,
                        std::vector<float>& radius, const std::vector<glm::vec3>* position = nullptr,
                        float taper = 0);
// The factor (1 + τ·ℓ) by which internode i (parent -> i) is wider at its base than at node i.
float pipe_taper_factor(const tree_skeleton& s, size_t i);
// Sets s.radius to the pipe radii of the final tree (step s.steps) and records the exponent (and
// taper) so that radii_at_step recomputes earlier steps.
void apply_pipe_radii(tree_skeleton& s, float exponent, float r_tip, float taper = 0);

// Radii of the tree as it stood at `step` (same node indices; nodes not alive at step get 0).
std::vector<float> radii_at_step(const tree_skeleton& s, int step);

// What a growth_debug point or line is, so that a viewer needs neither its colour nor the generator.
enum class debug_kind : uint8_t {
  marker,           // point; value: the step in which it was killed, -1 alive at the end (markers,
                    // attraction points)
  shadow_sample,    // point; value: shadow s of its grid cell (> 0)
  source,           // point; a source of the step after the previous endpoints (value 0)
  endpoint,         // point; value: the step k it ends
  influence_link,   // line; point → node, recorded for the last iteration only
  envelope_edge,    // line; the crown envelope's outline
  graph_edge,       // line; an edge of the search graph
  guide_arrow,      // line; a guiding vector
};

// A generator's debug output, drawn as overlays in the editor. Each point and each line pair has a
// kind (point_kind.size() == points.size(), line_kind.size() == line_color.size()).
struct growth_debug {
  std::vector<glm::vec3> points;         // attraction points / markers / shadow samples
  std::vector<float> point_value;        // per point: its kind's value (see debug_kind)
  std::vector<debug_kind> point_kind;
  std::vector<glm::vec3> lines;          // pairs of endpoints: graph edges, influence links, arrows
  std::vector<glm::vec3> line_color;     // one colour per pair
  std::vector<debug_kind> line_kind;     // one kind per pair
  std::vector<uint8_t> node_fate;        // per node: 0 grew, 1 dormant, 2 shed
  std::vector<float> node_flow;          // per node: resource flow (for line width)

  void add_point(const glm::vec3& p, float value, debug_kind k) {
    points.push_back(p), point_value.push_back(value), point_kind.push_back(k);
  }
  void add_line(const glm::vec3& a, const glm::vec3& b, const glm::vec3& colour, debug_kind k) {
    lines.push_back(a), lines.push_back(b), line_color.push_back(colour), line_kind.push_back(k);
  }
};

using progress_fn = std::function<void(float)>;

struct keyframe;   // generators/keyframes.h
struct prune_cut;  // generators/pruning.h
struct growth_resume;   // generators/resume.h

struct grow_options {
  uint64_t seed = 1;
  int steps = -1;                                  // -1: the params' own step count
  const std::atomic<uint32_t>* cancel = nullptr;   // non-zero: stop and return what is grown
  uint32_t cancel_value = 0;                       // cancelled when *cancel != cancel_value
  progress_fn progress;
  // Growth phases: applied by the generator at the top of each step (grow() checks them first).
  const std::vector<keyframe>* keyframes = nullptr;
  // Pruning: cuts the generator makes at the top of their steps (grow() checks them first).
  const std::vector<prune_cut>* cuts = nullptr;
  // Resuming from a recorded step, and recording (generators/resume.h; Honda's L-system only).
  growth_resume* resume = nullptr;
  bool cancelled() const {
    return cancel && cancel->load(std::memory_order_relaxed) != cancel_value;
  }
};

// Why growth stopped, for code to act on; stop_reason says it in words.
enum class grow_stop : uint8_t {
  finished,           // ran its steps or derivations, or ran out of room to grow (stop_reason says which)
  node_cap,
  module_cap,         // L-systems: the derived string hit its module cap
  memory_cap,         // self-organizing: the shadow grid hit its memory cap
  cancelled,
  parse_error,        // L-systems: the source does not parse (the editor keeps the last good tree)
  evaluation_error,   // L-systems: an expression failed while deriving
  bad_input,          // nothing to grow in: an unreadable envelope, no graph, an empty endpoint volume
};

// Why growth stopped and what the user should know.
struct grow_report {
  bool hit_node_cap = false;
  bool cancelled = false;
  grow_stop stop = grow_stop::finished;
  std::string stop_reason;    // e.g. "no attraction points left"
  std::string message;        // warning or error for the status bar ("" when all is well)
  bool error = false;         // true when the result is not a tree the user asked for
  std::vector<int> missed_cuts;   // indices of the cuts that found no branch (generators/pruning.h)
};

// A small, fast, seedable RNG (SplitMix64, Steele et al. 2014) owned by each generator.
struct rng {
  uint64_t state;
  explicit rng(uint64_t seed) : state(seed * 0x9E3779B97F4A7C15ull + 0x2545F4914F6CDD1Dull) {}
  uint64_t next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  float uniform() { return float(next() >> 40) * (1.0f / 16777216.0f); }  // [0,1)
  float uniform(float a, float b) { return a + (b - a) * uniform(); }
  int uniform_int(int n) { return int((next() >> 33) % uint64_t(n)); }      // [0,n)
};

}  // namespace sylva
