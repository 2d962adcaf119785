// `sylva export … --wind SECONDS`: the wind baked into glTF as a skin (joints on the
// trunk and the major branches, weights from the branch hierarchy) and a seamless looping animation.
// Used by render/io/export.cpp; kept apart so that the exporter only carries small hooks.
#pragma once

#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

#include "generators/skeleton.h"
#include "render/mesh/wind.h"

namespace sylva {

struct wind_bake {
  wind_rig rig;
  wind_skin skin;
  wind_motion motion;
  float seconds = 0;
  std::vector<float> times;                    // key times, 0 .. seconds, first and last keys equal
  std::vector<std::vector<glm::quat>> keys;    // per joint: its rotation at each time
  std::string note;                            // for the user: merges, the leaf flutter left out
};

inline constexpr float wind_min_seconds = 0.5f, wind_max_seconds = 60.0f;
inline constexpr int wind_keys_per_second = 12;

// Samples the skin's joints over one loop of `seconds` (clamped to 0.5 .. 60 s with a note).
wind_bake bake_wind(const tree_skeleton& t, const wind_params& p, float seconds, int max_joints = wind_max_joints);

// Weights (sum 1) as normalised bytes summing to exactly 255, as WEIGHTS_0 stores them.
glm::u8vec4 quantize_weights(glm::vec4 w);

// JOINTS_0 / WEIGHTS_0 accessors (appended to the document `j` and its binary `bin`) for the
// vertices of one primitive, given each vertex's skeleton node.
nlohmann::json wind_skin_attributes(nlohmann::json& j, std::string& bin, const wind_bake& b,
                                    const std::vector<uint32_t>& vertex_node);

// The joint nodes (their root is appended to `scene_roots`), the inverse bind matrices and the
// skin; returns the skin's index. Appends the joints' rotation channels to `channels`/`samplers`
// (the caller makes them an animation). `name_prefix` names the joints (growth steps).
int wind_add_skin(nlohmann::json& j, std::string& bin, const wind_bake& b, const std::string& name_prefix,
                  std::vector<int>& scene_roots, nlohmann::json& channels, nlohmann::json& samplers);

// The root joint's node index of the last wind_add_skin (the growth animation scales it).
int wind_root_joint(const nlohmann::json& j, int skin);

}  // namespace sylva
