// The wind's glTF skin and looping animation (see render/io/export_wind.h).
#include "render/io/export_wind.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

namespace sylva {

namespace {

using json = nlohmann::json;
constexpr int gl_float = 5126, gl_ubyte = 5121, array_buffer = 34962;

int add_view(json& j, std::string& bin, const void* data, size_t bytes, int target) {
  while (bin.size() % 4) bin.push_back('\0');
  json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
  if (target) v["target"] = target;
  bin.append(static_cast<const char*>(data), bytes);
  j["bufferViews"].push_back(v);
  return int(j["bufferViews"].size()) - 1;
}

int add_accessor(json& j, json a) {
  j["accessors"].push_back(std::move(a));
  return int(j["accessors"].size()) - 1;
}

}  // namespace

glm::u8vec4 quantize_weights(glm::vec4 w) {
  glm::u8vec4 q(0);
  int sum = 0, big = 0;
  for (int c = 0; c < 4; ++c) {
    q[c] = uint8_t(std::clamp(int(std::lround(std::max(w[c], 0.0f) * 255.0f)), 0, 255));
    sum += q[c];
    if (w[c] > w[big]) big = c;
  }
  q[big] = uint8_t(std::clamp(int(q[big]) + 255 - sum, 0, 255));   // the largest absorbs the rounding
  return q;
}

wind_bake bake_wind(const tree_skeleton& t, const wind_params& in, float seconds, int max_joints) {
  wind_bake b;
  wind_params p = in;
  p.enabled = true;   // asking for --wind turns it on, with the preset's settings
  std::string clamp_msg = clamp_wind(p);
  if (!std::isfinite(seconds) || seconds < wind_min_seconds || seconds > wind_max_seconds) {
    const float s = std::isfinite(seconds) ? std::clamp(seconds, wind_min_seconds, wind_max_seconds) : 4.0f;
    char buf[120];
    std::snprintf(buf, sizeof buf, "wind: a %g s loop clamped to %g s", double(seconds), double(s));
    clamp_msg += (clamp_msg.empty() ? "" : "; ") + std::string(buf);
    seconds = s;
  }
  b.seconds = seconds;
  b.rig = build_wind_rig(t);
  b.skin = build_wind_skin(t, b.rig, max_joints);
  b.motion = make_wind_motion(p, seconds);
  const int count = std::max(2, int(std::ceil(seconds * float(wind_keys_per_second))) + 1);
  b.times.resize(size_t(count));
  for (int k = 0; k < count; ++k) b.times[size_t(k)] = seconds * float(k) / float(count - 1);
  b.keys.assign(b.skin.joints.size(), {});
  for (size_t j = 0; j < b.skin.joints.size(); ++j) {
    auto& q = b.keys[j];
    q.resize(size_t(count));
    for (int k = 0; k + 1 < count; ++k) q[size_t(k)] = glm::normalize(wind_joint_rotation(b.skin, b.motion, j, b.times[size_t(k)]));
    // Whole cycles per loop make t = seconds the same pose as t = 0; the copy makes it exact.
    q[size_t(count) - 1] = q[0];
  }
  std::vector<std::string> notes;
  if (!clamp_msg.empty()) notes.push_back(clamp_msg);
  if (!b.skin.message.empty()) notes.push_back(b.skin.message);
  notes.push_back("wind: leaf flutter is viewport-only; in the glTF the leaves ride their branches' joints");
  for (const std::string& n : notes) b.note += (b.note.empty() ? "" : "\n") + n;
  return b;
}

json wind_skin_attributes(json& j, std::string& bin, const wind_bake& b, const std::vector<uint32_t>& vertex_node) {
  const size_t n = vertex_node.size();
  // Weights as normalised unsigned bytes (a quarter of floats' size), each vertex's summing to
  // exactly 255; a weight that rounds to 0 gives its slot back to joint 0.
  std::vector<glm::u8vec4> joints(n, glm::u8vec4(0)), weights(n, glm::u8vec4(255, 0, 0, 0));
  std::vector<glm::u8vec4> node_w(b.skin.node_weights.size());
  for (size_t i = 0; i < node_w.size(); ++i) node_w[i] = quantize_weights(b.skin.node_weights[i]);
  for (size_t v = 0; v < n; ++v) {
    const uint32_t node = vertex_node[v];
    if (node >= b.skin.node_joints.size()) continue;   // joint 0, the still root
    weights[v] = node_w[node];
    joints[v] = b.skin.node_joints[node];
    for (int c = 0; c < 4; ++c)
      if (weights[v][c] == 0) joints[v][c] = 0;
  }
  const int jv = add_view(j, bin, joints.data(), n * sizeof(glm::u8vec4), array_buffer);
  const int ja = add_accessor(j, {{"bufferView", jv}, {"componentType", gl_ubyte}, {"count", n}, {"type", "VEC4"}});
  const int wv = add_view(j, bin, weights.data(), n * sizeof(glm::u8vec4), array_buffer);
  const int wa = add_accessor(j, {{"bufferView", wv}, {"componentType", gl_ubyte}, {"normalized", true}, {"count", n}, {"type", "VEC4"}});
  return {{"JOINTS_0", ja}, {"WEIGHTS_0", wa}};
}

int wind_add_skin(json& j, std::string& bin, const wind_bake& b, const std::string& prefix, std::vector<int>& scene_roots,
                  json& channels, json& samplers) {
  const auto& joints = b.skin.joints;
  const size_t first = j.contains("nodes") ? j["nodes"].size() : 0;
  std::vector<json> nodes(joints.size());
  for (size_t k = 0; k < joints.size(); ++k) {
    const wind_joint& jt = joints[k];
    std::string name = jt.kind == 0 ? "wind_root" : jt.kind == 1 ? "trunk_" + std::to_string(k) : "branch_" + std::to_string(jt.branch);
    nodes[k] = {{"name", prefix + name}};
    const glm::vec3 parent_pivot = jt.parent >= 0 ? joints[size_t(jt.parent)].pivot : glm::vec3(0);
    const glm::vec3 tr = jt.pivot - parent_pivot;
    if (tr != glm::vec3(0)) nodes[k]["translation"] = {tr.x, tr.y, tr.z};
  }
  for (size_t k = 1; k < joints.size(); ++k) nodes[size_t(joints[k].parent)]["children"].push_back(int(first + k));
  for (json& n : nodes) j["nodes"].push_back(std::move(n));
  scene_roots.push_back(int(first));
  // Every joint's rest frame is a pure translation to its pivot.
  std::vector<glm::mat4> ibm(joints.size());
  for (size_t k = 0; k < joints.size(); ++k) ibm[k] = glm::translate(glm::mat4(1), -joints[k].pivot);
  const int iv = add_view(j, bin, ibm.data(), ibm.size() * sizeof(glm::mat4), 0);
  const int ia = add_accessor(j, {{"bufferView", iv}, {"componentType", gl_float}, {"count", ibm.size()}, {"type", "MAT4"}});
  json joint_ids = json::array();
  for (size_t k = 0; k < joints.size(); ++k) joint_ids.push_back(int(first + k));
  j["skins"].push_back({{"name", prefix + "wind"}, {"joints", joint_ids}, {"inverseBindMatrices", ia}, {"skeleton", int(first)}});
  const int skin = int(j["skins"].size()) - 1;
  // The loop: one shared time accessor, one rotation track per moving joint (all in one view).
  const int tv = add_view(j, bin, b.times.data(), b.times.size() * 4, 0);
  const int ta = add_accessor(j, {{"bufferView", tv}, {"componentType", gl_float}, {"count", b.times.size()}, {"type", "SCALAR"},
                                  {"min", {b.times.front()}}, {"max", {b.times.back()}}});
  std::vector<glm::vec4> rot;
  std::vector<size_t> moving;
  for (size_t k = 1; k < joints.size(); ++k) {
    moving.push_back(k);
    for (const glm::quat& q : b.keys[k]) rot.emplace_back(q.x, q.y, q.z, q.w);
  }
  if (moving.empty()) return skin;
  const int rv = add_view(j, bin, rot.data(), rot.size() * sizeof(glm::vec4), 0);
  for (size_t m = 0; m < moving.size(); ++m) {
    const int ra = add_accessor(j, {{"bufferView", rv}, {"byteOffset", m * b.times.size() * sizeof(glm::vec4)},
                                    {"componentType", gl_float}, {"count", b.times.size()}, {"type", "VEC4"}});
    samplers.push_back({{"input", ta}, {"output", ra}, {"interpolation", "LINEAR"}});
    channels.push_back({{"sampler", int(samplers.size()) - 1}, {"target", {{"node", int(first + moving[m])}, {"path", "rotation"}}}});
  }
  return skin;
}

int wind_root_joint(const json& j, int skin) { return j["skins"][size_t(skin)]["skeleton"].get<int>(); }

}  // namespace sylva
