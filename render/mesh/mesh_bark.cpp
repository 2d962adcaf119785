// The bark of mesh_tree (render/mesh/mesh_bark.h): generalized cylinders, one ring per node and
// more where the axis turns, in stages (docs/design/05-mesh.md): the per-node frame, the detail
// budget, the ring walk, the ring vertices and the index buffer sorted by born step.
#include "render/mesh/mesh_bark.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <functional>
#include <numeric>

#include "generators/job_pool.h"
#include "generators/skeleton.h"
#include "generators/timing.h"
#include "generators/vec_util.h"
#include "render/mesh/position_hash.h"

namespace sylva {
namespace {

constexpr glm::vec3 up_axis{0, 1, 0};

// Parallel transport (Bishop 1975; Wang et al. 2008): carry normal n from unit tangent t0 to t1 by
// the smallest rotation between them, so rings along an axis do not twist.
glm::vec3 transport(const glm::vec3& n, const glm::vec3& t0, const glm::vec3& t1) {
  const glm::vec3 axis = glm::cross(t0, t1);
  const float s = glm::length(axis), c = glm::dot(t0, t1);
  glm::vec3 r = n;
  if (s > 1e-7f) {
    const glm::vec3 k = axis / s;  // Rodrigues' rotation formula
    r = n * c + glm::cross(k, n) * s + k * glm::dot(k, n) * (1 - c);
  }
  r -= t1 * glm::dot(r, t1);  // re-orthogonalise against rounding drift
  const float len = glm::length(r);
  return len > 1e-7f ? r / len : any_perpendicular(t1);
}

// Stable counting sort of `count` items by a born step clamped into 0..steps; writes the
// per-step "end" table (size steps+1) and returns the permutation (order[k] = item index).
template <class BornOf>
std::vector<uint32_t> sort_by_born(size_t count, int steps, BornOf born_of, std::vector<uint32_t>& end) {
  end.assign(size_t(steps) + 1, 0);
  for (size_t k = 0; k < count; ++k) ++end[std::min<int>(born_of(k), steps)];
  for (int s = 1; s <= steps; ++s) end[s] += end[s - 1];
  std::vector<uint32_t> cursor(size_t(steps) + 1, 0);
  for (int s = 1; s <= steps; ++s) cursor[s] = end[s - 1];
  std::vector<uint32_t> perm(count);
  for (size_t k = 0; k < count; ++k) perm[cursor[std::min<int>(born_of(k), steps)]++] = uint32_t(k);
  return perm;
}

// Cosine of the angle between two vectors, unclamped (1 when either is zero).
float cosine_between(const glm::vec3& a, const glm::vec3& b) {
  const float la = glm::length(a), lb = glm::length(b);
  if (!(la > 1e-12f) || !(lb > 1e-12f)) return 1.0f;
  return glm::dot(a, b) / (la * lb);
}
// Angle in radians between two vectors (0 when either is zero).
float angle_between(const glm::vec3& a, const glm::vec3& b) {
  return std::acos(std::clamp(cosine_between(a, b), -1.0f, 1.0f));
}

// Velocity at p1 of the centripetal Catmull-Rom curve through p0, p1, p2 (Yuksel, Schaefer &
// Keyser 2011: alpha = 1/2, knots t_{j+1} = t_j + |p_{j+1} - p_j|^(1/2)), per unit of knot:
// (p1 - p0)/(t1 - t0) - (p2 - p0)/(t2 - t0) + (p2 - p1)/(t2 - t1) (Barry & Goldman 1988).
glm::vec3 cr_velocity(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
  const float d01 = std::max(std::sqrt(glm::length(p1 - p0)), 1e-6f), d12 = std::max(std::sqrt(glm::length(p2 - p1)), 1e-6f);
  return (p1 - p0) / d01 - (p2 - p0) / (d01 + d12) + (p2 - p1) / d12;
}
// The same at the end of a straight run (a mirrored neighbour): the chord over its knot interval.
glm::vec3 chord_velocity(const glm::vec3& p0, const glm::vec3& p1) {
  return (p1 - p0) / std::max(std::sqrt(glm::length(p1 - p0)), 1e-6f);
}

// The mesh parameters the bark reads, made safe (finite and clamped), and one ring's angle tables.
struct bark_settings {
  int seg = 0, stride = 0;
  float min_radius = 0, uv_repeat = 0, flare_strength = 0;
  int lobes = 0;   // buttress lobes; 0: the flare stays round
  float twist = 0, curve_step = 0;
  int curve_rings = 0;
  float cos_half_step = 0, collar = 0, collar_length = 0, collar_min = 0, root_depth = 0;
  std::vector<float> cos_a, sin_a, u_of;   // per ring vertex k (k = seg repeats k = 0)
};

bark_settings settings_of(const mesh_params& p, int seg) {
  bark_settings s;
  s.seg = seg, s.stride = seg + 1;
  s.min_radius = std::isfinite(p.min_radius) && p.min_radius > 0 ? p.min_radius : 1e-5f;
  s.uv_repeat = std::isfinite(p.uv_repeat) ? p.uv_repeat : 1.0f;
  s.flare_strength = std::isfinite(p.flare_strength) ? std::clamp(p.flare_strength, 0.0f, 4.0f) : 0.0f;
  // Lobes need two ring vertices each; rings too coarse for three (a reduced LOD) flare round.
  s.lobes = seg / 2 >= 3 ? std::min(std::clamp(p.flare_lobes, 3, 6), seg / 2) : 0;
  s.twist = std::isfinite(p.twist) ? std::tan(glm::radians(std::clamp(p.twist, -80.0f, 80.0f))) : 0.0f;
  s.curve_step = glm::radians(std::isfinite(p.curve_angle) ? std::clamp(p.curve_angle, 0.5f, 180.0f) : 12.0f);
  s.curve_rings = std::clamp(p.curve_rings, 0, 16);
  s.cos_half_step = std::cos(0.4999f * s.curve_step);
  s.collar = std::isfinite(p.collar) ? std::clamp(p.collar, 0.0f, 4.0f) : 0.0f;
  s.collar_length = std::isfinite(p.collar_length) ? std::clamp(p.collar_length, 0.0f, 100.0f) : 0.0f;
  s.collar_min = std::isfinite(p.collar_min_radius) ? p.collar_min_radius : 0.0f;
  s.root_depth = std::isfinite(p.root_depth) ? std::clamp(p.root_depth, 0.0f, 10.0f) : 0.0f;
  s.cos_a.resize(s.stride), s.sin_a.resize(s.stride), s.u_of.resize(s.stride);
  for (int k = 0; k < s.stride; ++k) {
    const float a = 6.2831853f * float(k % seg) / float(seg);  // k = seg repeats k = 0 exactly
    s.cos_a[k] = std::cos(a);
    s.sin_a[k] = std::sin(a);
    s.u_of[k] = float(k) / float(seg);
  }
  return s;
}

// The frame stage's answer, per node: where it stands after gnarl (q), its internode's direction,
// the child continuing its axis, the axis curve's velocity and tangent, the root flare, and how
// many times the texture wraps round it.
struct bark_axes {
  std::vector<glm::vec3> q, dir, vel, tangent;
  std::vector<int32_t> cont;
  std::vector<float> trunk_h, flare_h, flare_phase, wraps;
};

// The final radii (into m), the gnarl (turn, disp) and the axes.
bark_axes frame_axes(const tree_skeleton& t, const mesh_params& p, const bark_settings& s, tree_mesh& m,
                     std::vector<rotation_terms>& turn, std::vector<glm::vec3>& disp) {
  const size_t n = t.size();
  bark_axes ax;
  // Radii of the final tree; shed nodes (radius 0 there) keep their recorded radius or the minimum.
  m.final_radius = t.pipe_exponent > 0 ? radii_at_step(t, m.steps) : t.radius;
  for (size_t i = 0; i < n; ++i) {
    float r = m.final_radius[i] > 0 ? m.final_radius[i] : t.radius[i];
    m.final_radius[i] = r >= s.min_radius ? r : s.min_radius;  // NaN lands here too
  }

  // Gnarl: every internode turned by seeded angular noise, its subtree carried along.
  turn = gnarl_turns(gnarl_rotations(t, p));
  disp = gnarl_offsets(t, turn);
  std::vector<glm::vec3>& q = ax.q;
  q.resize(n);
  for (size_t i = 0; i < n; ++i) q[i] = t.position[i] + disp[i];

  // Unit direction of each internode (parent -> node); roots and zero-length ones inherit.
  std::vector<glm::vec3>& dir = ax.dir;
  dir.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    assert(par < int32_t(i) && "mesh_tree: parent[i] < i (structurally_sound lets no other skeleton in)");
    if (par < 0) { dir[i] = up_axis; continue; }
    const glm::vec3 d = q[i] - q[par];
    const float len = glm::length(d);
    dir[i] = len > 1e-12f && std::isfinite(len) ? d / len : dir[par];
  }
  // The child continuing each node's axis: same order first, then the most aligned. The others are
  // laterals and get their own base ring, sunk into the parent tube, instead of sharing its ring.
  std::vector<int32_t>& cont = ax.cont;
  cont.assign(n, -1);
  std::vector<float> best(n, -1e30f);
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    if (par < 0) continue;
    const float score = (t.order[i] == t.order[par] ? 4.0f : 0.0f) + glm::dot(dir[par], dir[i]);
    if (!(score <= best[par])) { best[par] = score; cont[par] = int32_t(i); }   // (a NaN score too: every parent continues)
  }

  // Velocity of the axis curve at each node: centripetal Catmull-Rom through the previous and the
  // next node of its axis; a tip continues its last internode. A root stands upright when its
  // trunk rises (so the base ring lies flat on the ground), else follows its first internode.
  ax.vel.resize(n), ax.tangent.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i], c = cont[i];
    glm::vec3 v;
    if (par >= 0 && c >= 0) v = cr_velocity(q[par], q[i], q[c]);
    else if (par >= 0) v = chord_velocity(q[par], q[i]);
    else if (c >= 0) v = glm::dot(dir[c], up_axis) > 0.5f ? up_axis * std::sqrt(glm::length(q[c] - q[i])) : chord_velocity(q[i], q[c]);
    else v = up_axis;
    const float len = glm::length(v);
    ax.vel[i] = v;
    ax.tangent[i] = len > 1e-12f && std::isfinite(len) ? v / len : (par >= 0 ? dir[i] : up_axis);
  }

  // Root flare: arc length up the trunk from its root (-1 off the trunk) and the flare's
  // height for that tree (flare_height, at most 6 root radii so a sapling's flare stays low).
  ax.trunk_h.assign(n, -1.0f), ax.flare_h.assign(n, 0.0f), ax.flare_phase.assign(n, 0.0f);
  if (s.flare_strength > 0) {
    const float height = std::isfinite(p.flare_height) ? std::clamp(p.flare_height, 0.0f, 100.0f) : 0.0f;
    for (size_t i = 0; i < n; ++i) {
      const int32_t par = t.parent[i];
      if (par < 0) {
        ax.trunk_h[i] = 0;
        ax.flare_h[i] = std::min(height, 6.0f * m.final_radius[i]);
        ax.flare_phase[i] = 6.2831853f * float(position_hash(t.position[i], 0x666c617265ull) >> 40) / 16777216.0f;
      } else if (ax.trunk_h[par] >= 0 && cont[par] == int32_t(i) && ax.trunk_h[par] < ax.flare_h[par]) {
        ax.trunk_h[i] = ax.trunk_h[par] + glm::length(q[i] - q[par]);
        ax.flare_h[i] = ax.flare_h[par];
        ax.flare_phase[i] = ax.flare_phase[par];
      }
    }
  }

  // Constant texel density from trunk to twig: the texture wraps round(circumference * uv_repeat)
  // times around each axis (at least once), counted at the axis's base so it never jumps along it.
  ax.wraps.assign(n, 1.0f);
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    if (par >= 0 && cont[par] == int32_t(i)) { ax.wraps[i] = ax.wraps[par]; continue; }
    const float w = std::round(6.2831853f * m.final_radius[i] * std::abs(s.uv_repeat));
    ax.wraps[i] = std::isfinite(w) ? std::clamp(w, 1.0f, 64.0f) : 1.0f;
  }
  return ax;
}

// The detail budget's answer, per internode: its Hermite end velocities, the curve rings kept and
// whether its collar ring is; and the counts the walk reserves by.
struct ring_budget {
  std::vector<glm::vec3> m1s, m2s;
  std::vector<uint8_t> keep, collared;
  size_t tubes = 0, fixed_rings = 0, tips = 0;
};

// Detail budget: curve and collar rings go where they show most, the widest creases first (the
// j-th ring of an internode removes r x turn x (1/j - 1/(j+1)) of crease; a collar, its swell),
// until the bark has detail_budget times the triangles of one ring per node. Caps and the
// flare's rings come first.
void spend_budget(const mesh_params& p, int seg, const std::vector<uint8_t>& want, const std::vector<float>& want_score,
                  const std::vector<float>& collar_score, ring_budget& b) {
  const size_t n = want.size();
  const double per_ring = 2.0 * seg, budget = std::isfinite(p.detail_budget) ? std::clamp(p.detail_budget, 1.0f, 16.0f) : 1.5;
  const double base = per_ring * double(b.tubes), fixed = per_ring * double(b.fixed_rings) + double(seg) * double(b.tips);
  const double spare = (budget - 1.0) * base - fixed;
  size_t left = spare > 0 ? size_t(spare / per_ring) : 0;
  std::vector<float> score;
  size_t asked = 0;
  for (size_t i = 0; i < n; ++i) asked += want[i] + (collar_score[i] > 0);
  score.reserve(asked);
  for (size_t i = 0; i < n; ++i) {
    for (int j = 1; j <= want[i]; ++j) score.push_back(want_score[i] / float(j * (j + 1)));
    if (collar_score[i] > 0) score.push_back(collar_score[i]);
  }
  float threshold = 0;
  if (score.size() > left) {
    if (left == 0) threshold = INFINITY;
    else {
      std::nth_element(score.begin(), score.begin() + std::ptrdiff_t(left - 1), score.end(), std::greater<float>());
      threshold = score[left - 1];
    }
  }
  // Above the threshold every ring is kept; rings at it only while the budget lasts.
  for (int pass = 0; pass < 2; ++pass)
    for (size_t i = 0; i < n; ++i) {
      for (int j = b.keep[i] + 1; j <= want[i] && left > 0; ++j) {
        const float sc = want_score[i] / float(j * (j + 1));
        if (pass == 0 ? sc > threshold : sc == threshold) { b.keep[i] = uint8_t(j); --left; } else break;
      }
      if (collar_score[i] > 0 && !b.collared[i] && left > 0 &&
          (pass == 0 ? collar_score[i] > threshold : collar_score[i] == threshold)) { b.collared[i] = 1; --left; }
    }
}

// Hermite form of each internode's centripetal Catmull-Rom segment (Yuksel, Schaefer & Keyser
// 2011): the end velocities scaled by the segment's knot interval |b - a|^(1/2). A lateral leaves
// its parent straight along its first internode; the trunk leaves its upright root upright. Then
// the rings each internode asks for, and those the budget gives.
ring_budget budget_rings(const tree_skeleton& t, const mesh_params& p, const bark_settings& s, const bark_axes& ax,
                         const std::vector<float>& final_radius) {
  const size_t n = t.size();
  ring_budget b;
  b.m1s.resize(n), b.m2s.resize(n);
  b.keep.assign(n, 0), b.collared.assign(n, 0);
  std::vector<float> want_score(n, 0.0f), collar_score(n, 0.0f);
  std::vector<uint8_t> want(n, 0);
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    if (par < 0) { b.tips += p.caps && ax.cont[i] >= 0; continue; }
    ++b.tubes;
    b.tips += p.caps && ax.cont[i] < 0;
    const bool lateral = ax.cont[par] != int32_t(i);
    const glm::vec3 chord = ax.q[i] - ax.q[par];
    const float len = glm::length(chord), knot = std::sqrt(len);
    glm::vec3 m1 = lateral ? chord : ax.vel[par] * knot, m2 = ax.vel[i] * knot;
    if (t.parent[par] < 0 && !lateral) m1 = ax.tangent[par] * len;
    const glm::vec3 dirn = len > 1e-12f ? chord / len : ax.dir[i];
    auto clamp_speed = [&](glm::vec3 mv) {
      const float l = glm::length(mv);
      if (!(l > 1e-12f) || !std::isfinite(l)) return dirn * len;
      return mv * (std::clamp(l, 0.2f * len, 2.0f * len) / l);
    };
    b.m1s[i] = clamp_speed(m1);
    b.m2s[i] = clamp_speed(m2);
    if (!(len > 1e-9f)) continue;
    const float r = 0.5f * (final_radius[i] + final_radius[par]);
    // An internode whose curve turns by under curve_step at both ends together wants no ring, and
    // its turn is read for nothing else: when both ends' cosines lie above that of a little under
    // half the step (so that the two acosf, within an ulp or two each, sum to less than it), the
    // arc cosines are not taken.
    if (s.curve_rings > 0 &&
        !(cosine_between(b.m1s[i], chord) > s.cos_half_step && cosine_between(chord, b.m2s[i]) > s.cos_half_step)) {
      float turn = angle_between(b.m1s[i], chord) + angle_between(chord, b.m2s[i]);
      if (!std::isfinite(turn)) turn = 0;
      want[i] = uint8_t(std::min(s.curve_rings, int(turn / s.curve_step)));
      want_score[i] = r * turn;   // the crease a kink leaves is about radius x angle wide
      if (!std::isfinite(want_score[i])) want[i] = 0, want_score[i] = 0;   // (no NaN in the sort below)
    }
    if (lateral && s.collar > 0 && final_radius[i] >= s.collar_min && std::isfinite(final_radius[i]))
      collar_score[i] = s.collar * final_radius[i];
    if (!lateral && ax.trunk_h[par] >= 0 && ax.trunk_h[par] < ax.flare_h[par])
      for (float frac : {0.1f, 0.25f, 0.45f, 0.7f}) {
        const float u = (frac * ax.flare_h[par] - ax.trunk_h[par]) / len;
        b.fixed_rings += u > 0.02f && u < 0.98f;
      }
  }
  spend_budget(p, s.seg, want, want_score, collar_score, b);
  return b;
}

// One ring: centre c, axis tan, frame normal nrm, radius r, v coordinate v. With h >= 0 it is a
// trunk ring h metres above the root, widened into buttress lobes; its normals then come from
// the partial derivatives of the lobed surface. A cap's apex ring (apex) has every vertex at c,
// its normal along tan. The walk only plans the rings (their frames are carried from ring to
// ring, so it is sequential); their vertices are written afterwards, in parallel chunks of rings,
// each ring at the vertex index the walk gave it.
struct ring_plan {
  glm::vec3 c, tan, nrm;
  float r, v, h, fh, phase;
  uint32_t node;
  bool apex;
};

constexpr uint32_t none = UINT32_MAX;

// The walk's answer: the rings planned, and the rings each internode's triangles run through,
// parent's ring first (chain[off[i]..off[i+1])), each node's own ring and its cap's apex ring.
struct ring_walk {
  size_t stride = 0;
  std::vector<ring_plan> plans;
  std::vector<uint32_t> chain, off, ring_start, cap_apex;

  uint32_t ring(const glm::vec3& c, const glm::vec3& tan, const glm::vec3& nrm, float r, float v, uint32_t node, float h,
                float fh, float phase) {
    plans.push_back({c, tan, nrm, r, v, h, fh, phase, node, false});
    return uint32_t((plans.size() - 1) * stride);
  }
  uint32_t apex(const glm::vec3& c, const glm::vec3& nrm, float v, uint32_t node) {
    plans.push_back({c, nrm, nrm, 0, v, -1, 0, 0, node, true});
    return uint32_t((plans.size() - 1) * stride);
  }
  // Node i's share of the index buffer: its internode through its rings, and its cap.
  uint32_t index_count(size_t i, int seg) const {
    const uint32_t rings = off[i + 1] - off[i];
    return (rings > 1 ? (rings - 1) * uint32_t(6 * seg) : 0) + (cap_apex[i] != none ? uint32_t(3 * seg) : 0);
  }
};

// Curve rings at equal shares of the curve's turning (16 samples of its tangent), so an S-shaped
// segment between zig-zag nodes gets them near its ends, where it turns most: `keep` parameters
// of the Hermite segment a, m1, b, m2 appended to us.
void turn_shares(const glm::vec3& a, const glm::vec3& m1, const glm::vec3& b, const glm::vec3& m2, int keep,
                 std::vector<float>& us) {
  constexpr int samples = 16;
  float cum[samples + 1];
  glm::vec3 prev_t = m1;
  cum[0] = 0;
  for (int sidx = 1; sidx <= samples; ++sidx) {
    const float u = float(sidx) / samples, uu = u * u;
    const glm::vec3 tc = a * (6 * uu - 6 * u) + m1 * (3 * uu - 4 * u + 1) + b * (-6 * uu + 6 * u) + m2 * (3 * uu - 2 * u);
    cum[sidx] = cum[sidx - 1] + angle_between(prev_t, tc);
    prev_t = tc;
  }
  const float total_turn = cum[samples];
  for (int j = 1; j <= keep; ++j) {
    float u = float(j) / float(keep + 1);
    if (total_turn > 1e-6f && std::isfinite(total_turn)) {
      const float goal = total_turn * float(j) / float(keep + 1);
      int sidx = 1;
      while (sidx < samples && cum[sidx] < goal) ++sidx;
      const float span = cum[sidx] - cum[sidx - 1];
      u = (float(sidx - 1) + (span > 0 ? (goal - cum[sidx - 1]) / span : 0.5f)) / samples;
    }
    us.push_back(u);
  }
}

// Every ring the walk can plan (a ring too close to the last is skipped): the plans are allocated
// once, at no more than this, and the vertex arrays at exactly the planned rings, so the mesh
// bound (render/io/mesh_bound.h) holds with no vector slack.
void reserve_walk(const tree_skeleton& t, const bark_axes& ax, const ring_budget& b, ring_walk& w) {
  const size_t n = t.size();
  size_t rings = n + b.tips, inner = 0;
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    inner += b.keep[i] + b.collared[i];
    if (par >= 0 && ax.cont[par] != int32_t(i)) ++rings;   // a lateral's base ring
  }
  rings += inner + b.fixed_rings;
  w.plans.reserve(rings);
  w.chain.reserve(2 * b.tubes + b.fixed_rings + std::accumulate(b.keep.begin(), b.keep.end(), size_t(0)) +
                  std::accumulate(b.collared.begin(), b.collared.end(), size_t(0)));
}

// The walk from the roots up: each internode's rings, where its curve turns, up the flare and at
// the collar, their frames carried along the axis by parallel transport; a tip's and a trunk's
// foot's caps.
ring_walk plan_rings(const tree_skeleton& t, const mesh_params& p, const bark_settings& s, const bark_axes& ax,
                     const ring_budget& b, const std::vector<float>& final_radius) {
  const size_t n = t.size();
  const std::vector<glm::vec3>&q = ax.q, &tangent = ax.tangent;
  const std::vector<int32_t>& cont = ax.cont;
  const std::vector<float>&trunk_h = ax.trunk_h, &flare_h = ax.flare_h, &flare_phase = ax.flare_phase;
  const float uv_repeat = s.uv_repeat;
  ring_walk w;
  w.stride = size_t(s.stride);
  reserve_walk(t, ax, b, w);
  std::vector<glm::vec3> frame(n);
  std::vector<float> vcoord(n, 0.0f);
  w.ring_start.assign(n, 0), w.cap_apex.assign(n, none), w.off.assign(n + 1, 0);
  std::vector<float> us;
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    w.off[i] = uint32_t(w.chain.size());
    if (par < 0) {
      frame[i] = any_perpendicular(tangent[i]);
      // An upright trunk stands in the ground: its foot ring is sunk root_depth below the root, at
      // the flare's full spread (h = 0), so the lobes run into the ground instead of ending in a cut.
      const bool upright = cont[i] >= 0 && glm::dot(tangent[i], up_axis) > 0.999f;
      const float sink = upright ? s.root_depth : 0.0f;
      const glm::vec3 foot = q[i] - up_axis * sink;
      w.ring_start[i] = w.ring(foot, tangent[i], frame[i], final_radius[i], -sink * uv_repeat, uint32_t(i), trunk_h[i],
                               flare_h[i], flare_phase[i]);
      if (p.caps && cont[i] >= 0)  // the trunk's foot, flat, facing down
        w.cap_apex[i] = w.apex(foot, -tangent[i], -sink * uv_repeat, uint32_t(i));
      continue;
    }
    const bool lateral = cont[par] != int32_t(i);
    const glm::vec3 a = q[par], bn = q[i], chord = bn - a;
    const float len = glm::length(chord);
    const float ri = final_radius[i], ra = final_radius[par];
    const glm::vec3 m1 = b.m1s[i], m2 = b.m2s[i];
    const glm::vec3 dirn = len > 1e-12f ? chord / len : ax.dir[i];
    const glm::vec3 t_start = lateral ? dirn : tangent[par];

    // Ring parameters inside the internode: where the curve turns, up the flare, at the collar.
    us.clear();
    if (b.keep[i] > 0) turn_shares(a, m1, bn, m2, b.keep[i], us);
    const bool on_trunk = !lateral && trunk_h[par] >= 0 && trunk_h[par] < flare_h[par] && len > 1e-9f;
    if (on_trunk)
      for (float frac : {0.1f, 0.25f, 0.45f, 0.7f}) {
        const float u = (frac * flare_h[par] - trunk_h[par]) / len;
        if (u > 0.02f && u < 0.98f) us.push_back(u);
      }
    // Collar: the base ring, sunk in the parent, is swollen; one ring where the swell has faded,
    // collar_length lateral radii beyond where the swollen tube leaves the parent's bark (a
    // cylinder of radius ra round tangent[par]), or within the first 90% of the internode.
    float u2 = -1;
    // A lateral's base: its pipe-model radius where it leaves the parent, wider than its tip by the
    // disused-pipe taper (skeleton.h) and still thinner than the parent there; the collar swells it.
    const float rb = lateral ? std::max(ri, std::min(ri * pipe_taper_factor(t, i), 0.98f * ra)) : ri;
    const float swell = b.collared[i] ? std::min(rb * (1 + s.collar), std::max(rb, 0.98f * ra)) : rb;
    if (b.collared[i]) {
      const float sin_t = glm::length(glm::cross(dirn, tangent[par])), cos_t = std::abs(glm::dot(dirn, tangent[par]));
      const float d_exit = (ra + swell * cos_t) / std::max(sin_t, 0.25f);
      u2 = std::min(d_exit + s.collar_length * ri, 0.9f * len) / len;
      us.push_back(u2);
    }
    std::sort(us.begin(), us.end());
    auto radius_at = [&](float u) {
      if (!lateral) return ra + (ri - ra) * u;
      const float lin = rb + (ri - rb) * u;   // the lateral's own taper
      if (u2 < 0 || u >= u2) return lin;
      const float x = u / u2, fade = 1 - x * x * (3 - 2 * x);  // smoothstep from the swell down
      return lin + (swell - rb) * fade;
    };

    glm::vec3 from_t = t_start, from_n, prev_c = a;
    float v = vcoord[par];
    if (lateral) {
      // Lateral: its own base ring at the parent node, along the child, sunk in the parent's tube.
      from_n = transport(frame[par], tangent[par], dirn);
      w.chain.push_back(w.ring(a, dirn, from_n, radius_at(0), v, uint32_t(i), -1, 0, 0));
    } else {
      from_n = frame[par];
      w.chain.push_back(w.ring_start[par]);
    }
    float last_u = 0;
    for (float u : us) {
      if (u - last_u < 0.02f || u > 0.98f) continue;
      last_u = u;
      const float u2_ = u * u, u3 = u2_ * u;
      const glm::vec3 c = a * (2 * u3 - 3 * u2_ + 1) + m1 * (u3 - 2 * u2_ + u) + bn * (-2 * u3 + 3 * u2_) + m2 * (u3 - u2_);
      glm::vec3 tc = a * (6 * u2_ - 6 * u) + m1 * (3 * u2_ - 4 * u + 1) + bn * (-6 * u2_ + 6 * u) + m2 * (3 * u2_ - 2 * u);
      const float tl = glm::length(tc);
      tc = tl > 1e-12f && std::isfinite(tl) ? tc / tl : dirn;
      const glm::vec3 nn = transport(from_n, from_t, tc);
      v += glm::length(c - prev_c) * uv_repeat;
      const float h = on_trunk ? trunk_h[par] + u * len : -1.0f;
      w.chain.push_back(w.ring(c, tc, nn, radius_at(u), v, uint32_t(i), h, flare_h[par], flare_phase[par]));
      from_t = tc;
      from_n = nn;
      prev_c = c;
    }
    frame[i] = transport(from_n, from_t, tangent[i]);
    v += glm::length(bn - prev_c) * uv_repeat;
    vcoord[i] = v;
    w.ring_start[i] = w.ring(bn, tangent[i], frame[i], ri, v, uint32_t(i), trunk_h[i], flare_h[i], flare_phase[i]);
    w.chain.push_back(w.ring_start[i]);
    // A tip's cap: a cone as high as the tip's radius, so it stays a hemisphere's outline as the
    // per-step radius moves its ring and apex (vertex shader) by the same amount.
    if (p.caps && cont[i] < 0) w.cap_apex[i] = w.apex(bn + tangent[i] * ri, tangent[i], v + ri * uv_repeat, uint32_t(i));
  }
  w.off[n] = uint32_t(w.chain.size());
  return w;
}

// One planned ring's vertices at vertex index `at`; w is its axis's texture wraps.
void write_ring(const bark_settings& cfg, float w, const ring_plan& rp, tree_mesh& m, size_t at) {
  const int stride = cfg.stride;
  const std::vector<float>&cos_a = cfg.cos_a, &sin_a = cfg.sin_a, &u_of = cfg.u_of;
  const float twist = cfg.twist, flare_strength = cfg.flare_strength;
  glm::vec3* out_pos = m.position.data() + at;
  glm::vec3* out_nrm = m.normal.data() + at;
  glm::vec2* out_uv = m.uv.data() + at;
  uint32_t* out_node = m.node.data() + at;
  if (rp.apex) {
    for (int k = 0; k < stride; ++k) {
      out_pos[k] = rp.c;
      out_nrm[k] = rp.tan;
      out_uv[k] = {(u_of[k] + rp.v * twist / w) * w, rp.v};
      out_node[k] = rp.node;
    }
    return;
  }
  const glm::vec3 &c = rp.c, &tan = rp.tan, &nrm = rp.nrm;
  const float r = rp.r, v = rp.v, h = rp.h, fh = rp.fh, phase = rp.phase;
  const glm::vec3 bin = glm::cross(tan, nrm);
  const bool flared = h >= 0 && h < fh && fh > 0;
  const float s = flared ? 1.0f - h / fh : 0.0f;
  const float f = flare_strength * s * s, df = flared ? -2.0f * flare_strength * s / fh : 0.0f;
  for (int k = 0; k < stride; ++k) {
    const glm::vec3 d = nrm * cos_a[k] + bin * sin_a[k];
    glm::vec3 normal = d;
    float rr = r;
    if (flared) {
      // Lobe profile: a fifth of the swell all round, the rest in lobes (0.5 + 0.5 cos)^2.
      const float phi = 6.2831853f * u_of[k], x = float(cfg.lobes) * (phi - phase);
      const float c1 = 0.5f + 0.5f * std::cos(x);
      const float lobe = cfg.lobes ? c1 * c1 : 0.375f, dlobe = cfg.lobes ? -c1 * float(cfg.lobes) * std::sin(x) : 0.0f;  // 0.375: the lobes' mean
      const float mult = 1.0f + f * (0.2f + 0.8f * lobe);
      rr = r * mult;
      const float r_phi = r * f * 0.8f * dlobe, r_h = r * df * (0.2f + 0.8f * lobe);
      const glm::vec3 e = -nrm * sin_a[k] + bin * cos_a[k];
      normal = glm::normalize(d - (r_phi / rr) * e - r_h * tan);  // (dP/dphi x dP/dh) / r
    }
    out_pos[k] = c + d * rr;
    out_nrm[k] = normal;
    out_uv[k] = {(u_of[k] + v * twist / w) * w, v};
    out_node[k] = rp.node;
  }
}

// The index buffer at its full size, then the vertex arrays, each ring written in parallel chunks.
// The buffer, the largest array, is made first: the heap's large holes are an older mesh's, and
// made last it often found none left (self_organizing_default).
void write_rings(const bark_settings& cfg, const std::vector<float>& wraps, ring_walk& w, tree_mesh& m) {
  size_t total_index = 0;  // (the index stage checks it against its prefix sums)
  for (size_t i = 0; i + 1 < w.off.size(); ++i) total_index += w.index_count(i, cfg.seg);
  m.index.resize(total_index);
  const size_t vertices = w.plans.size() * size_t(cfg.stride);
  m.position.resize(vertices);
  m.normal.resize(vertices);
  m.uv.resize(vertices);
  m.node.resize(vertices);
  parallel_chunks(w.plans.size(), 1024, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) write_ring(cfg, wraps[w.plans[k].node], w.plans[k], m, k * size_t(cfg.stride));
  });
  std::vector<ring_plan>().swap(w.plans);
}

// Each node's triangles (its internode through its rings, and its cap) sorted by born step so
// that step s draws a prefix of the index buffer (docs/design/05-mesh.md).
void write_index(const tree_skeleton& t, const ring_walk& w, int seg, tree_mesh& m) {
  const size_t n = t.size();
  std::vector<uint32_t> count(n);
  std::vector<uint32_t> item;
  item.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    count[i] = w.index_count(i, seg);
    if (count[i]) item.push_back(uint32_t(i));
  }
  std::vector<uint32_t> item_end;
  const std::vector<uint32_t> perm =
      sort_by_born(item.size(), m.steps, [&](size_t k) { return int(t.born[item[k]]); }, item_end);
  std::vector<size_t> cum(perm.size() + 1, 0);
  for (size_t k = 0; k < perm.size(); ++k) cum[k + 1] = cum[k] + count[item[perm[k]]];
  for (size_t s = 0; s < item_end.size(); ++s) m.index_end[s] = uint32_t(cum[item_end[s]]);
  assert(cum.back() == m.index.size());
  // Each item's triangles go to their own range (cum), so chunks of items fill in parallel.
  parallel_chunks(perm.size(), 2048, [&](size_t begin, size_t end) {
    for (size_t pk = begin; pk < end; ++pk) {
      uint32_t* out = m.index.data() + cum[pk];
      const uint32_t i = item[perm[pk]];
      for (uint32_t r = w.off[i]; r + 1 < w.off[i + 1]; ++r) {
        const uint32_t lo = w.chain[r], hi = w.chain[r + 1];
        for (int s = 0; s < seg; ++s) {
          const uint32_t a = lo + s, b = lo + s + 1, c = hi + s, d = hi + s + 1;  // CCW from outside
          *out++ = a; *out++ = b; *out++ = c;
          *out++ = b; *out++ = d; *out++ = c;
        }
      }
      if (w.cap_apex[i] != none) {
        const uint32_t ring = w.ring_start[i], apex = w.cap_apex[i];
        const bool foot = t.parent[i] < 0;   // the foot faces down: the other winding
        for (int s = 0; s < seg; ++s) {
          *out++ = foot ? ring + s + 1 : ring + s;
          *out++ = foot ? ring + s : ring + s + 1;
          *out++ = apex + s;
        }
      }
    }
  });
}

}  // namespace

void mesh_bark(const tree_skeleton& t, const mesh_params& p, tree_mesh& m, mesh_stage_times& st,
               std::vector<rotation_terms>& turn, std::vector<glm::vec3>& disp) {
  auto lap_start = clock_type::now();
  auto lap = [&](double& field) {   // adds the time since the last lap to one stage
    const auto now = clock_type::now();
    field += ms_between(lap_start, now);
    lap_start = now;
  };
  const bark_settings cfg = settings_of(p, m.radial_segments);
  bark_axes ax = frame_axes(t, p, cfg, m, turn, disp);
  lap(st.frame);
  ring_budget budget = budget_rings(t, p, cfg, ax, m.final_radius);
  lap(st.budget);
  ring_walk walk = plan_rings(t, p, cfg, ax, budget, m.final_radius);
  // What only the walk needed goes before the vertex arrays come, so the plans cost no peak memory.
  const std::vector<float> wraps = std::move(ax.wraps);
  ax = {}, budget = {};
  write_rings(cfg, wraps, walk, m);
  lap(st.rings);
  write_index(t, walk, cfg.seg, m);
  lap(st.index);
}

}  // namespace sylva
