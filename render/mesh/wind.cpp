// Wind: per-node sway data, the motion's time functions, the shader text and the glTF skin.
//
// The model is the hierarchical one of real-time vegetation (Sousa, "Vegetation Procedural
// Animation and Shading in Crysis", GPU Gems 3 ch. 16, 2007): a main bend of the whole tree
// whose sideways offset grows with the square of the height, branch sway about each branch's
// base, and a fast leaf flutter on top. Thinner branches are more flexible and sway faster: for a
// cantilever beam of round section the first natural frequency grows with r / L^2 (Euler-Bernoulli),
// so with similar lengths the frequency falls as the radius grows toward the trunk's.
#include "render/mesh/wind.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

namespace sylva {

namespace {

constexpr float two_pi = 6.28318530718f;
constexpr float trunk_amp = 0.05f;     // tip slope of the trunk at strength 1 (radians)
constexpr float branch_amp = 0.12f;    // sway of a very thin branch at strength 1 (radians)
constexpr float max_angle = 0.8f;      // no branch turns further, whatever the strength

float fix(float v, float lo, float hi, float fallback, const char* name, std::string& msg) {
  float out = std::isfinite(v) ? std::clamp(v, lo, hi) : fallback;
  if (out != v) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s%s %g clamped to %g", msg.empty() ? "wind: " : "; ", name, double(v), double(out));
    msg += buf;
  }
  return out;
}

// Hz rounded to whole cycles per loop (at least one) when the motion loops.
float loop_hz(const wind_motion& m, float hz) {
  if (!m.looped) return hz;
  return std::max(1.0f, std::round(hz * m.loop)) / m.loop;
}

float hash01(uint32_t x) {   // integer hash (Wellons' lowbias32) to [0, 1)
  x ^= x >> 16, x *= 0x7feb352dU, x ^= x >> 15, x *= 0x846ca68bU, x ^= x >> 16;
  return float(x >> 8) * (1.0f / 16777216.0f);
}

glm::vec3 rotate(glm::vec3 v, glm::vec3 w) {   // Rodrigues: v rotated by the axis-angle vector w
  const float a = glm::length(w);
  if (a < 1e-9f) return v;
  const glm::vec3 k = w / a;
  return v * std::cos(a) + glm::cross(k, v) * std::sin(a) + k * glm::dot(k, v) * (1.0f - std::cos(a));
}

}  // namespace

std::string clamp_wind(wind_params& p) {
  std::string msg;
  const wind_params d;
  p.strength = fix(p.strength, 0, wind_strength_max, d.strength, "strength", msg);
  p.gustiness = fix(p.gustiness, 0, 1, d.gustiness, "gustiness", msg);
  p.direction = fix(p.direction, -180, 180, d.direction, "direction", msg);
  p.frequency = fix(p.frequency, wind_frequency_min, wind_frequency_max, d.frequency, "frequency", msg);
  p.leaf_flutter = fix(p.leaf_flutter, 0, 1, d.leaf_flutter, "leaf flutter", msg);
  return msg;
}

wind_motion make_wind_motion(const wind_params& in, float loop_seconds) {
  wind_params p = in;
  clamp_wind(p);
  wind_motion m;
  const float a = p.direction * (two_pi / 360.0f);
  m.toward = glm::vec3(std::sin(a), 0, std::cos(a));
  m.bend_axis = glm::cross(glm::vec3(0, 1, 0), m.toward);
  m.strength = p.enabled ? p.strength : 0.0f;
  m.gustiness = p.gustiness;
  m.flutter = p.leaf_flutter;
  m.looped = std::isfinite(loop_seconds) && loop_seconds > 0;
  m.loop = m.looped ? loop_seconds : 0;
  // Frequency ratios: branches ~1.7x the trunk, leaves ~7x, gusts a few times slower than the trunk.
  m.trunk_hz = loop_hz(m, p.frequency);
  m.branch_hz = p.frequency * 1.7f;   // times each branch's multiplier, rounded per branch when looped
  m.leaf_hz = loop_hz(m, p.frequency * 7.0f);
  m.gust_hz[0] = loop_hz(m, p.frequency * 0.23f);
  m.gust_hz[1] = loop_hz(m, p.frequency * 0.37f);
  return m;
}

float wind_gust(const wind_motion& m, float t) {
  return 1.0f + m.gustiness * (0.6f * std::sin(two_pi * m.gust_hz[0] * t + 1.1f) + 0.4f * std::sin(two_pi * m.gust_hz[1] * t + 2.3f));
}

float wind_trunk_angle(const wind_motion& m, float t) {
  return m.strength * trunk_amp * wind_gust(m, t) * (0.6f + 0.4f * std::sin(two_pi * m.trunk_hz * t));
}

glm::vec3 wind_branch_rotation(const wind_motion& m, float amp, float phase, float freq, float t) {
  if (amp <= 0 || m.strength <= 0) return glm::vec3(0);
  const float w = two_pi * loop_hz(m, m.branch_hz * freq) * t + phase;
  // A mean lean with the wind plus an oscillation about it, and a smaller sideways swing a quarter
  // period later, so the tip traces an ellipse.
  const float along = 0.45f + 0.55f * std::sin(w), side = 0.3f * std::sin(w + 1.9f);
  glm::vec3 r = m.strength * amp * wind_gust(m, t) * (along * m.bend_axis + side * m.toward);
  const float a = glm::length(r);
  return a > max_angle ? r * (max_angle / a) : r;
}

wind_rig build_wind_rig(const tree_skeleton& t) {
  wind_rig rig;
  const size_t n = t.size();
  rig.nodes.resize(n);
  rig.branch_start.assign(n, -1);
  rig.major.assign(n, -1);
  rig.minor.assign(n, -1);
  if (n == 0) return rig;
  float ground = 1e30f, top = -1e30f;
  float root_radius = 1e-4f;
  for (size_t i = 0; i < n; ++i) {
    const int32_t p = t.parent[i];
    const uint8_t ord = i < t.order.size() ? t.order[i] : 0;
    const uint8_t pord = p >= 0 && size_t(p) < t.order.size() ? t.order[size_t(p)] : 0;
    if (p < 0) {
      ground = std::min(ground, t.position[i].y);
      root_radius = std::max(root_radius, t.radius[i]);
    }
    top = std::max(top, t.position[i].y);
    rig.branch_start[i] = (p < 0 || ord != pord) ? int32_t(i) : rig.branch_start[size_t(p)];
    if (p >= 0 && ord > 0) {
      if (pord == 0) rig.major[i] = rig.branch_start[i];
      else rig.major[i] = rig.major[size_t(p)];
      // The own branch is a minor one when it is not the major branch itself.
      if (rig.major[i] >= 0 && rig.branch_start[i] != rig.major[i]) rig.minor[i] = rig.branch_start[i];
    }
  }
  rig.ground = ground;
  rig.height = std::max(top - ground, 0.1f);
  // Per branch start: pivot, amplitude (from stiffness), phase, frequency multiplier.
  auto branch = [&](int32_t b, glm::vec3& pivot, float& amp, float& phase, float& freq) {
    const size_t s = size_t(b);
    const int32_t p = t.parent[s];
    pivot = p >= 0 ? t.position[size_t(p)] : t.position[s];
    const float r = std::max(t.radius[s], 0.0f);
    // Stiffness 0..1 from the base radius against the trunk's and the order; thin, high-order branches bend most.
    const float stiff = std::clamp(std::sqrt(r / root_radius), 0.05f, 1.0f);
    const int ord = s < t.order.size() ? t.order[s] : 1;
    amp = branch_amp * (1.1f - stiff) * (1.0f + 0.25f * float(std::max(ord - 1, 0)));
    phase = two_pi * hash01(uint32_t(b) * 2654435761u + 17u);
    freq = 1.0f + 1.5f * (1.0f - stiff);
  };
  for (size_t i = 0; i < n; ++i) {
    wind_node& w = rig.nodes[i];
    if (rig.major[i] >= 0) branch(rig.major[i], w.major_pivot, w.major_amp, w.major_phase, w.major_freq);
    if (rig.minor[i] >= 0) branch(rig.minor[i], w.minor_pivot, w.minor_amp, w.minor_phase, w.minor_freq);
  }
  return rig;
}

glm::vec3 wind_displace(const wind_rig& rig, const wind_motion& m, uint32_t node, glm::vec3 p, float t) {
  if (m.strength <= 0 || node >= rig.nodes.size()) return p;
  const wind_node& w = rig.nodes[node];
  // Innermost first, each about its rest pivot: the child's motion in the parent's frame.
  if (w.minor_amp > 0) p = w.minor_pivot + rotate(p - w.minor_pivot, wind_branch_rotation(m, w.minor_amp, w.minor_phase, w.minor_freq, t));
  if (w.major_amp > 0) p = w.major_pivot + rotate(p - w.major_pivot, wind_branch_rotation(m, w.major_amp, w.major_phase, w.major_freq, t));
  // Main bend: a beam whose slope grows linearly with height, tip slope theta: offset theta h^2 / 2H.
  const float h = std::clamp(p.y - rig.ground, 0.0f, rig.height);
  p += m.toward * (wind_trunk_angle(m, t) * h * h / (2.0f * rig.height));
  return p;
}

const char* wind_glsl() {
  // Mirrors wind_branch_rotation and wind_displace above; the gust and the trunk's angle are the
  // same for every vertex, so the CPU computes them once per frame (uniforms).
  return R"(
uniform samplerBuffer u_wind;   // 3 texels per node: wind_node
uniform int u_wind_on; uniform float u_wind_time; uniform float u_wind_strength;
uniform float u_wind_gust; uniform float u_wind_trunk;   // wind_gust and wind_trunk_angle at this time (CPU)
uniform vec3 u_wind_toward; uniform vec3 u_wind_axis; uniform float u_wind_branch_hz;
uniform float u_wind_leaf_hz; uniform float u_wind_flutter; uniform float u_wind_ground; uniform float u_wind_height;
const float WIND_TWO_PI = 6.28318530718;
vec3 wind_rotate(vec3 v, vec3 w) {
  float a = length(w);
  if (a < 1e-9) return v;
  vec3 k = w / a;
  float c = cos(a);
  return v * c + cross(k, v) * sin(a) + k * dot(k, v) * (1.0 - c);
}
vec3 wind_branch(float amp, float phase, float freq) {
  float w = WIND_TWO_PI * u_wind_branch_hz * freq * u_wind_time + phase;
  vec3 r = u_wind_strength * amp * u_wind_gust * ((0.45 + 0.55 * sin(w)) * u_wind_axis + 0.3 * sin(w + 1.9) * u_wind_toward);
  float a = length(r);
  return a > 0.8 ? r * (0.8 / a) : r;
}
mat3 wind_rotation(vec3 w) {   // Rodrigues as a matrix: c I + s [k]x + (1 - c) k k^T
  float a = length(w);
  if (a < 1e-9) return mat3(1.0);
  vec3 k = w / a;
  float c = cos(a);
  return c * mat3(1.0) + sin(a) * mat3(0.0, k.z, -k.y, -k.z, 0.0, k.x, k.y, -k.x, 0.0) + (1.0 - c) * outerProduct(k, k);
}
// The sway of point p on `node`, and of the surface frame there: the normal n and the tangents t, b
// turn with the branch rotations; the trunk's bend is a shear p += toward f(h), f = theta h^2 / 2H,
// whose Jacobian J = I + toward (f'(h) up)^T moves tangents by J (t += toward f' t.y) and normals by
// J^-T (n -= up f' (toward . n)), so the lighting follows the sway exactly.
vec3 wind_sway_frame(vec3 p, int node, inout vec3 n, inout vec3 t, inout vec3 b) {
  if (u_wind_on == 0) return p;
  vec4 ta = texelFetch(u_wind, 3 * node), tb = texelFetch(u_wind, 3 * node + 1), tc = texelFetch(u_wind, 3 * node + 2);
  if (tb.w > 0.0) {
    mat3 r = wind_rotation(wind_branch(tb.w, tc.z, tc.w));
    p = tb.xyz + r * (p - tb.xyz); n = r * n; t = r * t; b = r * b;
  }
  if (ta.w > 0.0) {
    mat3 r = wind_rotation(wind_branch(ta.w, tc.x, tc.y));
    p = ta.xyz + r * (p - ta.xyz); n = r * n; t = r * t; b = r * b;
  }
  float h = p.y - u_wind_ground;
  float hc = clamp(h, 0.0, u_wind_height);
  float slope = h > 0.0 && h < u_wind_height ? u_wind_trunk * h / u_wind_height : 0.0;   // f'(h)
  n.y -= slope * dot(u_wind_toward, n);
  t += u_wind_toward * (slope * t.y);
  b += u_wind_toward * (slope * b.y);
  return p + u_wind_toward * (u_wind_trunk * hc * hc / (2.0 * u_wind_height));
}
vec3 wind_sway(vec3 p, int node) {   // position only (the frame's work is dead code, dropped by the compiler)
  vec3 n = vec3(0.0), t = vec3(0.0), b = vec3(0.0);
  return wind_sway_frame(p, node, n, t, b);
}
// Leaf flutter: the blade flaps along its normal n, more toward the tip (tip 0 at the petiole, 1 at
// the tip): offset n A tip sin(psi), psi = w t + phase + 2 tip, A = flutter 0.3 size. Along the
// blade (b, `size` metres per unit of tip) that offset's slope is g = A / size (sin psi + 2 tip cos psi),
// so the blade's frame turns about its tangent: b += g n, n -= g b.
vec3 wind_flutter_frame(vec3 p, inout vec3 n, inout vec3 b, float tip, float size, float phase) {
  if (u_wind_on == 0) return p;
  float psi = WIND_TWO_PI * u_wind_leaf_hz * u_wind_time + phase + 2.0 * tip;
  float k = u_wind_flutter * min(u_wind_strength, 1.0) * 0.3;
  vec3 out_p = p + n * (k * size * tip * sin(psi));
  float g = k * (sin(psi) + 2.0 * tip * cos(psi));
  vec3 n0 = n;
  n = n - b * g;
  b = b + n0 * g;
  return out_p;
}
)";
}

// ---------------------------------------------------------------- skin

wind_skin build_wind_skin(const tree_skeleton& t, const wind_rig& rig, int max_joints, int max_trunk_segments) {
  wind_skin s;
  const size_t n = t.size();
  max_joints = std::clamp(max_joints, 2, 255);
  s.joints.push_back({});   // 0: the static root at the origin
  // Trunks: one segment per trunk internode, at least 8 (when the trunk has them) and up to
  // `max_trunk_segments` as far as the major branches leave joints over; all trunks together keep
  // at most half the joints. A rigid chain of N equal segments meets the viewport's bend at the
  // joints and strays from it by theta H / 8 N^2 between them.
  std::vector<int32_t> roots;
  for (size_t i = 0; i < n; ++i)
    if (t.parent[i] < 0) roots.push_back(int32_t(i));
  std::vector<int32_t> tree_of(n, 0);
  for (size_t i = 0; i < n; ++i) tree_of[i] = t.parent[i] < 0 ? int32_t(std::find(roots.begin(), roots.end(), int32_t(i)) - roots.begin()) : tree_of[size_t(t.parent[i])];
  struct trunk_info { float base = 0, top = 0; int nodes = 0; std::vector<int> joints; std::vector<float> heights; };
  std::vector<trunk_info> trunks(roots.size());
  int majors = 0;
  for (size_t i = 0; i < n; ++i) {
    trunk_info& tr = trunks[size_t(tree_of[i])];
    if (t.parent[i] < 0) tr.base = tr.top = t.position[i].y;
    else if (rig.major[i] < 0) tr.top = std::max(tr.top, t.position[i].y);   // trunk nodes
    tr.nodes += rig.major[i] < 0;
    majors += rig.major[i] == int32_t(i);
  }
  const int trees = std::max(int(roots.size()), 1);
  const int trunk_budget = std::max(0, std::min(max_joints / 2, max_joints - 1)) / trees;
  const int left_per_tree = std::max(0, max_joints - 1 - majors) / trees;
  for (size_t k = 0; k < roots.size(); ++k) {
    trunk_info& tr = trunks[k];
    const int edges = std::max(tr.nodes - 1, 1);
    const int want = std::max(std::min(8, edges), left_per_tree);
    const int segments = std::min({want, edges, std::max(max_trunk_segments, 1), trunk_budget});
    if (segments <= 0) continue;
    // The joints sit on the leader (from the root, always the thickest trunk child), spread evenly
    // over its nodes; a node lower than the joint before it (a winding trunk) is skipped.
    std::vector<size_t> leader{size_t(roots[k])};
    for (bool more = true; more;) {
      more = false;
      size_t next = 0;
      for (size_t i = leader.back() + 1; i < n; ++i)
        if (t.parent[i] == int32_t(leader.back()) && rig.major[i] < 0 && (!more || t.radius[i] > t.radius[next]))
          next = i, more = true;
      if (more) leader.push_back(next);
    }
    const int along = std::min(segments, std::max(int(leader.size()) - 1, 1));
    std::vector<glm::vec3> pivots;
    for (int j = 0; j < along; ++j) {
      const glm::vec3 pivot = t.position[leader[size_t(std::lround(double(j) * double(leader.size() - 1) / along))]];
      if (!pivots.empty() && pivot.y <= pivots.back().y) continue;
      pivots.push_back(pivot);
    }
    for (const glm::vec3& p : pivots) tr.heights.push_back(p.y);
    tr.heights.push_back(std::max(tr.top, tr.heights.back()));
    for (size_t j = 0; j < pivots.size(); ++j) {
      wind_joint jt;
      jt.kind = 1;
      jt.parent = j == 0 ? 0 : tr.joints.back();
      jt.pivot = pivots[j];
      // Cumulative slope over segments 0..j = theta * (segment j's mid height above the ground) / H:
      // the chord slope of the viewport's parabola (wind_displace) over the segment, so the chain
      // meets the parabola at every joint. Each segment adds the rise of the mid height.
      auto mid = [&](int q) { return q < 0 ? rig.ground : 0.5f * (tr.heights[size_t(q)] + tr.heights[size_t(q) + 1]); };
      jt.trunk_share = std::max(mid(int(j)) - mid(int(j) - 1), 0.0f) / rig.height;
      tr.joints.push_back(int(s.joints.size()));
      s.joints.push_back(jt);
    }
  }
  // The trunk joint a height on tree k follows, and the blend to the next one.
  auto trunk_weights = [&](int32_t tree, float y, glm::u8vec4& jo, glm::vec4& we) {
    jo = glm::u8vec4(0), we = glm::vec4(0);
    const trunk_info& tr = trunks[size_t(tree)];
    if (tr.joints.empty()) { we.x = 1; return; }
    const size_t m = tr.joints.size();
    size_t j = 0;
    while (j + 1 < m && y >= tr.heights[j + 1]) ++j;
    jo.x = uint8_t(tr.joints[j]);
    if (j + 1 < m) {
      const float f = std::clamp((y - tr.heights[j]) / std::max(tr.heights[j + 1] - tr.heights[j], 1e-6f), 0.0f, 1.0f);
      jo.y = uint8_t(tr.joints[j + 1]);
      we = glm::vec4(1.0f - f, f, 0, 0);
      if (f <= 0) jo.y = 0;
      if (f >= 1) jo.x = jo.y, jo.y = 0, we = glm::vec4(1, 0, 0, 0);
    } else {
      we.x = 1;
    }
  };
  // Branch candidates: every major branch, thickest first, then every minor branch, thickest first.
  std::vector<int32_t> cand;
  for (size_t i = 0; i < n; ++i)
    if (rig.branch_start[i] == int32_t(i) && (rig.major[i] == int32_t(i) || rig.minor[i] == int32_t(i))) cand.push_back(int32_t(i));
  std::stable_sort(cand.begin(), cand.end(), [&](int32_t a, int32_t b) {
    const bool ma = rig.major[size_t(a)] == a, mb = rig.major[size_t(b)] == b;
    return ma != mb ? ma : t.radius[size_t(a)] > t.radius[size_t(b)];
  });
  s.candidates = int(cand.size());
  std::vector<int32_t> joint_of(n, -1);   // branch start -> joint
  std::vector<int32_t> chosen;
  for (int32_t b : cand) {
    if (int(s.joints.size() + chosen.size()) >= max_joints) break;
    const bool major = rig.major[size_t(b)] == b;
    if (!major && joint_of[size_t(rig.major[size_t(b)])] < 0) continue;   // its major branch merged: so does it
    joint_of[size_t(b)] = 0;   // mark; real ids below, parents first
    chosen.push_back(b);
  }
  s.merged = s.candidates - int(chosen.size());
  // Majors before minors, each by node index, so that parents precede children.
  std::stable_sort(chosen.begin(), chosen.end(), [&](int32_t a, int32_t b) {
    const bool ma = rig.major[size_t(a)] == a, mb = rig.major[size_t(b)] == b;
    return ma != mb ? ma : a < b;
  });
  for (int32_t b : chosen) {
    const wind_node& w = rig.nodes[size_t(b)];
    const bool major = rig.major[size_t(b)] == b;
    wind_joint jt;
    jt.kind = 2;
    jt.branch = b;
    jt.pivot = major ? w.major_pivot : w.minor_pivot;
    jt.amp = major ? w.major_amp : w.minor_amp;
    jt.phase = major ? w.major_phase : w.minor_phase;
    jt.freq = major ? w.major_freq : w.minor_freq;
    if (major) {
      glm::u8vec4 jo;
      glm::vec4 we;
      trunk_weights(tree_of[size_t(b)], jt.pivot.y, jo, we);
      jt.parent = jo.x;   // the trunk segment the branch leaves from (rigidly attached)
    } else {
      jt.parent = joint_of[size_t(rig.major[size_t(b)])];
    }
    joint_of[size_t(b)] = int32_t(s.joints.size());
    s.joints.push_back(jt);
  }
  // Weights per node: its minor branch's joint, else its major's, else the trunk at the height
  // where its major branch leaves (or its own height on the trunk).
  s.node_joints.assign(n, glm::u8vec4(0));
  s.node_weights.assign(n, glm::vec4(1, 0, 0, 0));
  for (size_t i = 0; i < n; ++i) {
    const int32_t mi = rig.minor[i], ma = rig.major[i];
    if (mi >= 0 && joint_of[size_t(mi)] > 0) s.node_joints[i].x = uint8_t(joint_of[size_t(mi)]);
    else if (ma >= 0 && joint_of[size_t(ma)] > 0) s.node_joints[i].x = uint8_t(joint_of[size_t(ma)]);
    else trunk_weights(tree_of[i], ma >= 0 ? rig.nodes[i].major_pivot.y : t.position[i].y, s.node_joints[i], s.node_weights[i]);
  }
  if (s.merged > 0 && s.candidates > max_joints - 1)
    s.message = "wind: " + std::to_string(s.candidates) + " branches want a joint; glTF skins keep at most " +
                std::to_string(max_joints) + " joints, so " + std::to_string(s.merged) +
                " thinner branches move with their nearest jointed branch (or the trunk)";
  return s;
}

glm::quat wind_joint_rotation(const wind_skin& s, const wind_motion& m, size_t j, float t) {
  const glm::quat id(1, 0, 0, 0);
  if (j >= s.joints.size()) return id;
  const wind_joint& jt = s.joints[j];
  glm::vec3 w(0);
  if (jt.kind == 1) w = m.bend_axis * (wind_trunk_angle(m, t) * jt.trunk_share);
  else if (jt.kind == 2) w = wind_branch_rotation(m, jt.amp, jt.phase, jt.freq, t);
  const float a = glm::length(w);
  if (a < 1e-9f) return id;
  return glm::angleAxis(a, w / a);
}

}  // namespace sylva
