// The wood pass: each internode is a cantilever beam segment that bends under the wood and leaves
// it carries; the growth is replayed by born step so that a branch sags as it gets heavier.
//
// Model (small deflection, Euler-Bernoulli): the bending moment at the middle of internode k is
// M = Σ m_i (x_i - c_k) × g over the loads beyond that point, its curvature M / (E I) with
// I = π r⁴ / 4, so the internode turns by θ = M⊥ L / (E I) about M. Half of θ is applied at the
// internode's base and the rest at its tip (a hinge at its middle), which makes a chain of n equal
// segments match the beam formulas to O(1/n²). Loads and moments are accumulated from the tips down
// in one reverse sweep (parents precede children), positions in one forward sweep: O(n) per step.
//
// History (permanent set): as in Jirasek, Prusinkiewicz & Moulia 2000 ("Integrating biomechanics
// into developmental plant models expressed using L-systems"), new wood is laid down on the bent
// branch, so at each bend step an internode turns by the *increase* of its moment since the last
// bend divided by its stiffness *now*: load added while the branch was thin bends it for good.
// Reaction wood then turns young shoots back toward their set direction by a share per step.
#include "generators/wood.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

namespace sylva {

namespace {

constexpr float standard_gravity = 9.80665f;  // m/s² (CGPM 1901)
constexpr float pi = 3.14159265358979f;
constexpr float min_beam_radius = 1e-4f;      // metres: a zero radius would have no stiffness

// The rotation by vector v (axis · angle in radians).
glm::quat rotation_quat(const glm::vec3& v) {
  const float a = glm::length(v);
  if (!(a > 1e-12f)) return glm::quat(1, 0, 0, 0);
  const float s = std::sin(0.5f * a) / a;
  return glm::quat(std::cos(0.5f * a), v.x * s, v.y * s, v.z * s);
}

// The square root of a unit quaternion: half the rotation about the same axis.
glm::quat half_rotation(const glm::quat& q) {
  glm::quat h(1 + q.w, q.x, q.y, q.z);
  if (h.w < 1e-6f) return glm::quat(1, 0, 0, 0);  // a half turn: cannot happen under max_bend
  return glm::normalize(h);
}

struct engine {
  const tree_skeleton& t;
  const std::vector<glm::vec3>& rest;
  wood_params p;
  size_t n;
  bool recover = true;
  const std::vector<float>* point_mass = nullptr;

  std::vector<glm::quat> bend;     // per internode: its turn relative to its parent's end frame
  std::vector<glm::quat> frame;    // per node: the rotation of everything beyond it
  std::vector<glm::vec3> x;        // bent positions
  std::vector<glm::vec3> moment;   // moment at the middle of each internode
  std::vector<glm::vec3> moment_prev;
  std::vector<float> r;            // radii at the bend step
  std::vector<float> pipe_sum;
  std::vector<float> sub_m;        // mass beyond each node
  std::vector<glm::vec3> sub_s;    // first moment of that mass
  std::vector<uint8_t> clamped;

  engine(const tree_skeleton& tree, const std::vector<glm::vec3>& rest_pos, const wood_params& params)
      : t(tree), rest(rest_pos), p(params), n(tree.size()) {
    bend.assign(n, glm::quat(1, 0, 0, 0));
    frame.assign(n, glm::quat(1, 0, 0, 0));
    x = rest;
    moment.assign(n, glm::vec3(0));
    moment_prev.assign(n, glm::vec3(0));
    r.assign(n, 0.0f);
    sub_m.assign(n, 0.0f);
    sub_s.assign(n, glm::vec3(0));
    clamped.assign(n, 0);
  }

  bool alive(size_t k, int s) const { return t.born[k] <= s && s < t.died[k]; }

  // Positions and frames of nodes [0, end) from the current bends.
  void forward(size_t end) {
    for (size_t k = 0; k < end; ++k) {
      const int32_t par = t.parent[k];
      if (par < 0) {
        x[k] = rest[k];
        frame[k] = bend[k];
        continue;
      }
      const glm::vec3 d = rest[k] - rest[par];
      const glm::quat& b = bend[k];
      if (b.x == 0 && b.y == 0 && b.z == 0) {  // unbent (young nodes): skip the half rotation
        x[k] = x[par] + frame[par] * d;
        frame[k] = frame[par];
      } else {
        x[k] = x[par] + frame[par] * (half_rotation(b) * d);
        frame[k] = frame[par] * b;
      }
    }
  }

  // Radii of the nodes alive at s among [0, end): pipe radii of that step, else the fixed ones.
  void radii(int s, size_t end) {
    if (t.pipe_exponent > 0) {
      pipe_sum.assign(end, 0.0f);
      const float e = t.pipe_exponent, rt = std::pow(t.pipe_tip_radius, e), inv = 1.0f / e;
      for (size_t k = end; k-- > 0;) {
        if (!alive(k, s)) continue;
        const float sum = pipe_sum[k] > 0 ? pipe_sum[k] : rt;  // as compute_pipe_radii (skeleton.cpp)
        r[k] = std::pow(sum, inv);
        if (t.parent[k] >= 0) pipe_sum[size_t(t.parent[k])] += sum;
      }
    } else {
      for (size_t k = 0; k < end; ++k) r[k] = t.radius[k];
    }
  }

  // Moments at the middle of every internode alive at s, from the tips down.
  void moments(int s, size_t end) {
    std::fill(sub_m.begin(), sub_m.begin() + long(end), 0.0f);
    std::fill(sub_s.begin(), sub_s.begin() + long(end), glm::vec3(0));
    const glm::vec3 g(0, -standard_gravity * p.gravity, 0);
    const float leaf_kg_per_m = p.leaf_mass * 1e-3f * p.leaves_per_metre;
    for (size_t k = end; k-- > 0;) {
      if (!alive(k, s)) continue;
      if (point_mass && k < point_mass->size() && (*point_mass)[k] > 0) {
        sub_m[k] += (*point_mass)[k];
        sub_s[k] += (*point_mass)[k] * x[k];
      }
      const int32_t par = t.parent[k];
      if (par < 0) continue;
      const float len = glm::length(rest[k] - rest[par]);
      const float rr = std::max(0.5f * (r[k] + r[par]), min_beam_radius);
      float m = p.density * pi * rr * rr * len;   // wood: density × volume
      if (s - int(t.born[k]) <= p.leaf_age) m += leaf_kg_per_m * len;  // foliage of a young shoot
      const glm::vec3 c = 0.5f * (x[par] + x[k]);
      // The internode's own outer half acts at its three-quarter point.
      const float tm = sub_m[k] + 0.5f * m;
      const glm::vec3 ts = sub_s[k] + (0.5f * m) * (0.25f * x[par] + 0.75f * x[k]);
      moment[k] = glm::cross(ts - tm * c, g);
      sub_m[size_t(par)] += sub_m[k] + m;
      sub_s[size_t(par)] += sub_s[k] + m * c;
    }
  }

  // Turns each internode alive at s by its moment increase over its stiffness, plus reaction wood.
  // `prev`: the previous bend step; a shoot recovers for each step of (prev, s] in which it was young.
  void update(int s, int prev, size_t end) {
    const float E = p.modulus * 1e9f;
    const float max_turn = p.max_bend * pi / 180.0f;
    for (size_t k = 0; k < end; ++k) {
      const int32_t par = t.parent[k];
      if (par < 0 || !alive(k, s)) continue;
      const glm::vec3 rd = rest[k] - rest[size_t(par)];
      const glm::vec3 dv = x[k] - x[size_t(par)];
      const float len = glm::length(dv);
      if (!(len > 1e-9f)) continue;
      const glm::vec3 axis = dv / len;
      glm::vec3 dm = moment[k] - moment_prev[k];
      moment_prev[k] = moment[k];
      dm -= glm::dot(dm, axis) * axis;   // the axial part twists; only the rest bends
      const float rr = std::max(0.5f * (r[k] + r[size_t(par)]), min_beam_radius);
      const float ei = E * pi * rr * rr * rr * rr * 0.25f;   // E·I, I = π r⁴ / 4
      glm::vec3 turn = dm * (len / ei);
      // Reaction wood (gravitropic recovery): a young shoot turns its tip back toward its set
      // direction by `recovery` of the angle between them per step.
      if (recover && p.recovery > 0) {
        // Steps of (prev, s] in which the shoot was young.
        const int first = std::max(prev + 1, int(t.born[k]));
        const int last = std::min(s, int(t.born[k]) + p.recovery_age);
        const int young = last - first + 1;
        if (young > 0) {
          glm::vec3 target = rd / std::max(glm::length(rd), 1e-12f);
          if (p.recovery_up > 0) {
            const glm::vec3 up = (1 - p.recovery_up) * target + glm::vec3(0, p.recovery_up, 0);
            const float l = glm::length(up);
            if (l > 1e-6f) target = up / l;
          }
          const glm::vec3 tip = frame[k] * (rd / std::max(glm::length(rd), 1e-12f));  // its direction now
          const glm::vec3 c = glm::cross(tip, target);
          const float sn = glm::length(c);
          const float angle = std::atan2(sn, glm::dot(tip, target));
          if (sn > 1e-7f) {
            const float share = 1.0f - std::pow(1.0f - p.recovery, float(young));
            turn += c * (angle * share / sn);
          }
        }
      }
      float a = glm::length(turn);
      if (!(a > 1e-12f)) continue;
      if (!(a <= max_turn)) {  // NaN or a fold: clamp
        turn = std::isfinite(a) ? turn * (max_turn / a) : glm::vec3(0);
        clamped[k] = 1;
      }
      // World rotation at the joint -> the parent's end frame: q' = rot(R_p⁻¹ θ) q.
      const glm::vec3 local = glm::conjugate(frame[size_t(par)]) * turn;
      glm::quat b = glm::normalize(rotation_quat(local) * bend[k]);
      if (b.w < 0) b = -b;
      const float total = 2.0f * std::acos(std::min(b.w, 1.0f));
      if (total > max_turn) {  // the accumulated bend of one internode stays below max_bend
        const glm::vec3 v(b.x, b.y, b.z);
        const float vl = glm::length(v);
        b = vl > 1e-12f ? glm::angleAxis(max_turn, v / vl) : glm::quat(1, 0, 0, 0);
        clamped[k] = 1;
      }
      bend[k] = b;
    }
  }

  // Replays the bend steps up to `step`, then leaves x as the tree at `step`.
  void run(const std::vector<uint16_t>& steps, int step) {
    int prev = -1;
    for (uint16_t s : steps) {
      if (int(s) > step) break;
      const size_t reach = prefix_end(s);
      forward(reach);
      radii(s, reach);
      moments(s, reach);
      update(s, prev, reach);
      prev = s;
    }
    forward(n);
  }

  // One past the last node born at or before s.
  size_t prefix_end(int s) const {
    size_t lo = 0, hi = n;
    if (monotone) {
      while (lo < hi) {
        const size_t mid = (lo + hi) / 2;
        if (t.born[mid] <= s) lo = mid + 1;
        else hi = mid;
      }
      return lo;
    }
    return n;
  }
  bool monotone = false;
};

bool born_in_order(const tree_skeleton& t) {
  for (size_t i = 1; i < t.size(); ++i)
    if (t.born[i] < t.born[i - 1]) return false;
  return true;
}

// The steps at which the pass bends the tree. Every step while that costs at most 4 sweeps of the
// final tree; beyond, a step is kept when the tree has grown by half since the last kept one
// (counted back from the last step), so a large tree costs about 3 sweeps whatever its step count.
std::vector<uint16_t> choose_bend_steps(const tree_skeleton& t, bool monotone) {
  std::vector<size_t> alive_end(size_t(t.steps) + 1, t.size());
  if (monotone) {
    size_t k = 0;
    for (int s = 0; s <= t.steps; ++s) {
      while (k < t.size() && t.born[k] <= s) ++k;
      alive_end[size_t(s)] = k;
    }
  }
  double total = 0;
  for (size_t e : alive_end) total += double(e);
  std::vector<uint16_t> steps;
  if (total <= 4.0 * double(std::max<size_t>(t.size(), 1))) {
    for (int s = 0; s <= t.steps; ++s) steps.push_back(uint16_t(s));
    return steps;
  }
  size_t last = 0;
  for (int s = t.steps; s >= 0; --s)
    if (steps.empty() || double(alive_end[size_t(s)]) * 1.5 <= double(last) || alive_end[size_t(s)] < 64) {
      steps.push_back(uint16_t(s));
      last = alive_end[size_t(s)];
    }
  std::reverse(steps.begin(), steps.end());
  return steps;
}

void add_message(grow_report* report, const std::string& m) {
  if (!report) return;
  report->message += (report->message.empty() ? "" : "; ") + m;
}

}  // namespace

void apply_wood(tree_skeleton& t, const wood_params& params, grow_report* report) {
  t.wood.reset();
  if (!(params.gravity > 0) || t.size() < 2) return;
  wood_params p = params;
  const std::vector<std::string> fixed = clamp_all_params(p);
  if (!fixed.empty()) {
    std::string keys;
    for (const std::string& k : fixed) keys += (keys.empty() ? "" : ", ") + k;
    add_message(report, "wood: " + keys + " out of range, clamped");
  }
  auto h = std::make_shared<wood_history>();
  h->rest = t.position;
  h->params = p;
  const bool monotone = born_in_order(t);
  h->bend_steps = choose_bend_steps(t, monotone);
  engine e(t, h->rest, p);
  e.monotone = monotone;
  e.run(h->bend_steps, t.steps);
  size_t folds = 0;
  for (uint8_t c : e.clamped) folds += c;
  if (folds)
    add_message(report, "wood: " + std::to_string(folds) + " internode" + (folds == 1 ? "" : "s") +
                            " reached the maximum bend; the load is more than the wood can carry (check gravity, "
                            "wood density, Young's modulus and leaf mass)");
  for (leaf& l : t.leaves)
    if (l.node >= 0 && size_t(l.node) < t.size()) l.position += e.x[size_t(l.node)] - h->rest[size_t(l.node)];
  t.position = std::move(e.x);
  t.wood = std::move(h);
}

std::vector<glm::vec3> positions_at_step(const tree_skeleton& t, int step) {
  if (!t.wood || t.wood->rest.size() != t.size()) return t.position;
  if (step >= t.steps) return t.position;
  engine e(t, t.wood->rest, t.wood->params);
  e.monotone = born_in_order(t);
  e.run(t.wood->bend_steps, std::max(step, 0));
  return std::move(e.x);
}

std::vector<glm::vec3> bend_static(const tree_skeleton& t, const wood_params& p, const std::vector<float>* point_mass) {
  engine e(t, t.position, p);
  e.recover = false;
  e.point_mass = point_mass;
  e.run({uint16_t(std::max(t.steps, 0))}, t.steps);
  return std::move(e.x);
}

}  // namespace sylva
