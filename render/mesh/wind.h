// Wind: hierarchical sway as real-time engines do it (trunk bend, branches swaying
// around their bases, leaf flutter), the per-node data the vertex shader reads, the CPU reference
// of the shader's motion, and the skin + looping animation that the glTF export bakes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_precision.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "generators/params.h"
#include "generators/skeleton.h"

namespace sylva {

struct tree_mesh;

// Render-side: changing these never regrows or re-meshes the tree (they are uniforms).
struct wind_params {
  bool enabled = false;
  float strength = 0.5f;      // 0 calm .. 2 storm (scales every sway angle)
  float gustiness = 0.4f;     // 0 steady .. 1: slow swells of the strength between (1 - g) and (1 + g)
  float direction = 0;        // degrees: the compass direction the wind blows toward, from +Z toward +X
  float frequency = 0.4f;     // Hz: the trunk's sway; branches sway faster, leaves faster still
  float leaf_flutter = 0.5f;  // 0 .. 1: leaf tips flapping about their petioles
  bool operator==(const wind_params&) const = default;
};

inline constexpr float wind_strength_max = 2.0f;
inline constexpr float wind_frequency_min = 0.05f, wind_frequency_max = 3.0f;

template <params_of<wind_params> P, class V>
void visit_params(P& p, V&& visitor) {
  auto v = declare_class(visitor, param_render);   // wind sways the kept mesh in the vertex shader
  v(p.enabled, param_info{"wind", "Wind", "", 0, 1, "Sway the tree in the wind (viewport; `sylva export --wind SECONDS` bakes it into glTF)", 0, "Wind"});
  v(p.strength, param_info{"wind_strength", "Strength", "", 0, wind_strength_max, "How far the trunk bends and the branches sway (0 calm, 1 a strong breeze, 2 a storm)"});
  v(p.gustiness, param_info{"wind_gustiness", "Gustiness", "", 0, 1, "Slow swells of the wind: 0 steady, 1 from calm to double strength"});
  v(p.direction, param_info{"wind_direction", "Direction", "", -180, 180, "Compass direction the wind blows toward", param_degrees});
  v(p.frequency, param_info{"wind_frequency", "Frequency", "", wind_frequency_min, wind_frequency_max, "Sway frequency of the trunk in Hz; thinner branches sway faster", param_log});
  v(p.leaf_flutter, param_info{"leaf_flutter", "Leaf flutter", "", 0, 1, "Leaves flap about their petioles (viewport only; the glTF skin carries the branches' sway)"});
}

inline bool param_relevant(const wind_params& p, const void* field, const param_info&) {
  return field == &p.enabled || p.enabled;
}

// Clamps every wind value into its range (NaN -> default); returns "" or a message naming what
// was clamped, for the status bar / stderr. The renderer and the exporter only see clamped values.
std::string clamp_wind(wind_params& p);

// The time functions of the sway. Frequencies in Hz; a loop of `loop_seconds` > 0 rounds each one
// to a whole number of cycles per loop, so the motion at t = loop equals the motion at t = 0.
struct wind_motion {
  glm::vec3 toward{0, 0, 1};   // unit, horizontal: where the wind blows
  glm::vec3 bend_axis{1, 0, 0}; // cross(up, toward): rotating about it tips things toward the wind
  float strength = 0, gustiness = 0, flutter = 0;
  float trunk_hz = 0.4f, branch_hz = 0.4f * 1.7f, leaf_hz = 0.4f * 7.0f;
  float gust_hz[2] = {0.4f * 0.23f, 0.4f * 0.37f};
  bool looped = false;
  float loop = 0;
};
wind_motion make_wind_motion(const wind_params& p, float loop_seconds = 0);
float wind_gust(const wind_motion& m, float t);            // 1 - g .. 1 + g
float wind_trunk_angle(const wind_motion& m, float t);     // radians: the trunk's tip slope toward the wind

// Per skeleton node: the bases (pivots) of the major branch (first lateral off the trunk) and of the
// node's own minor branch (order >= 2) it sits on, each with a sway amplitude (radians at strength
// 1; 0: no such branch), phase and frequency multiplier from the branch's radius and order. Trunk
// nodes have neither and only bend with the trunk. Three RGBA32F texels per node in the shader.
struct wind_node {
  glm::vec3 major_pivot{0};
  float major_amp = 0;
  glm::vec3 minor_pivot{0};
  float minor_amp = 0;
  float major_phase = 0, major_freq = 1, minor_phase = 0, minor_freq = 1;
};
static_assert(sizeof(wind_node) == 48, "three vec4 texels");

struct wind_rig {
  std::vector<wind_node> nodes;
  std::vector<int32_t> branch_start;   // per node: the first node of its branch (same order)
  std::vector<int32_t> major, minor;   // per node: the branch-start node of its major / minor branch, -1 none
  float ground = 0;                    // lowest root's height: the trunk bends from here
  float height = 1;                    // tallest node above the ground (metres, >= 0.1)
};
wind_rig build_wind_rig(const tree_skeleton& t);

// The shader's displacement on the CPU (reference for tests and the export): the rest position `p`
// of a point on `node` at time t (seconds). `leaf_tip` > 0 adds the flutter of a leaf card point
// that far (0..1 of the blade) from the petiole along the leaf normal `n`.
glm::vec3 wind_displace(const wind_rig& rig, const wind_motion& m, uint32_t node, glm::vec3 p, float t);

// The rotation (axis * angle, radians) of a branch with amplitude `amp`, phase, frequency multiplier at t.
glm::vec3 wind_branch_rotation(const wind_motion& m, float amp, float phase, float freq, float t);

// GLSL (#version-less) that declares the wind uniforms and
// `vec3 wind_sway_frame(vec3 p, int node, inout vec3 n, inout vec3 t, inout vec3 b)` (the sway of a
// point and of its normal and tangents), `vec3 wind_sway(vec3 p, int node)` (position only),
// `vec3 wind_flutter_frame(vec3 p, inout vec3 n, inout vec3 b, float tip, float size, float phase)`;
// included by the bark and leaf vertex shaders (render/gl/renderer.cpp). Uniforms: set_wind_uniforms.
const char* wind_glsl();

// ---------------------------------------------------------------- glTF skin (export)

inline constexpr int wind_max_joints = 64;

struct wind_joint {
  int32_t parent = -1;       // joint index, -1 for the scene-root joint 0
  glm::vec3 pivot{0};        // world rest position
  int kind = 0;              // 0 the static root, 1 a trunk segment, 2 a branch
  float trunk_share = 0;     // kind 1: share of the trunk's tip slope this segment adds
  float amp = 0, phase = 0, freq = 1;   // kind 2: as wind_node
  int32_t branch = -1;       // kind 2: the branch-start node
};

struct wind_skin {
  std::vector<wind_joint> joints;           // joints[0] is the static root; parents come first
  std::vector<glm::u8vec4> node_joints;     // per skeleton node: up to 4 joints (distinct)
  std::vector<glm::vec4> node_weights;      // per skeleton node: their weights, sum 1
  int candidates = 0;                       // branches that wanted a joint
  int merged = 0;                           // of which merged into their nearest jointed ancestor
  std::string message;                      // "" or a note for the user (merges)
};
inline constexpr int wind_trunk_segments_max = 12;

// Joints on each trunk (one segment per trunk internode, at least 8 when the trunk has them and up
// to `max_trunk_segments` as far as the major branches leave joints over) and on the thickest major
// and minor branches up to `max_joints`; the other branches merge into their nearest jointed
// ancestor branch (the trunk last).
wind_skin build_wind_skin(const tree_skeleton& t, const wind_rig& rig, int max_joints = wind_max_joints,
                          int max_trunk_segments = wind_trunk_segments_max);

// Local rotation of joint j at time t (the joint's rest frame is the identity rotation).
glm::quat wind_joint_rotation(const wind_skin& s, const wind_motion& m, size_t j, float t);

}  // namespace sylva
