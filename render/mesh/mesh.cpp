// Skeleton -> generalized-cylinder bark (one ring per node) and leaf instances, sorted by birth step.
#include "render/mesh/mesh.h"

#include "generators/wood.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstring>
#include <functional>
#include <numeric>
#include <thread>

#include "generators/job_pool.h"
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

// The bark: the frame, budget, rings and index stages of mesh_tree (their times in st); turn and
// disp are the gnarl, which the leaves follow too.
void mesh_bark(const tree_skeleton& t, const mesh_params& p, tree_mesh& m, mesh_stage_times& st,
               std::vector<rotation_terms>& turn, std::vector<glm::vec3>& disp) {
  auto lap_start = clock_type::now();
  auto lap = [&](double& field) {   // adds the time since the last lap to one stage
    const auto now = clock_type::now();
    field += ms_between(lap_start, now);
    lap_start = now;
  };
  const size_t n = t.size();
  const int seg = m.radial_segments, stride = seg + 1;
  const float min_radius = std::isfinite(p.min_radius) && p.min_radius > 0 ? p.min_radius : 1e-5f;
  const float uv_repeat = std::isfinite(p.uv_repeat) ? p.uv_repeat : 1.0f;

  // Radii of the final tree; shed nodes (radius 0 there) keep their recorded radius or the minimum.
  m.final_radius = t.pipe_exponent > 0 ? radii_at_step(t, m.steps) : t.radius;
  for (size_t i = 0; i < n; ++i) {
    float r = m.final_radius[i] > 0 ? m.final_radius[i] : t.radius[i];
    m.final_radius[i] = r >= min_radius ? r : min_radius;  // NaN lands here too
  }

  // Gnarl: every internode turned by seeded angular noise, its subtree carried along.
  turn = gnarl_turns(gnarl_rotations(t, p));
  disp = gnarl_offsets(t, turn);
  std::vector<glm::vec3> q(n);
  for (size_t i = 0; i < n; ++i) q[i] = t.position[i] + disp[i];

  // Unit direction of each internode (parent -> node); roots and zero-length ones inherit.
  std::vector<glm::vec3> dir(n);
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
  std::vector<int32_t> cont(n, -1);
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
  std::vector<glm::vec3> vel(n), tangent(n);
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i], c = cont[i];
    glm::vec3 v;
    if (par >= 0 && c >= 0) v = cr_velocity(q[par], q[i], q[c]);
    else if (par >= 0) v = chord_velocity(q[par], q[i]);
    else if (c >= 0) v = glm::dot(dir[c], up_axis) > 0.5f ? up_axis * std::sqrt(glm::length(q[c] - q[i])) : chord_velocity(q[i], q[c]);
    else v = up_axis;
    const float len = glm::length(v);
    vel[i] = v;
    tangent[i] = len > 1e-12f && std::isfinite(len) ? v / len : (par >= 0 ? dir[i] : up_axis);
  }

  // Root flare: arc length up the trunk from its root (-1 off the trunk) and the flare's
  // height for that tree (flare_height, at most 6 root radii so a sapling's flare stays low).
  const float flare_strength = std::isfinite(p.flare_strength) ? std::clamp(p.flare_strength, 0.0f, 4.0f) : 0.0f;
  // Lobes need two ring vertices each; rings too coarse for three (a reduced LOD) flare round.
  const int lobes = seg / 2 >= 3 ? std::min(std::clamp(p.flare_lobes, 3, 6), seg / 2) : 0;
  std::vector<float> trunk_h(n, -1.0f), flare_h(n, 0.0f);
  std::vector<float> flare_phase(n, 0.0f);
  if (flare_strength > 0) {
    const float height = std::isfinite(p.flare_height) ? std::clamp(p.flare_height, 0.0f, 100.0f) : 0.0f;
    for (size_t i = 0; i < n; ++i) {
      const int32_t par = t.parent[i];
      if (par < 0) {
        trunk_h[i] = 0;
        flare_h[i] = std::min(height, 6.0f * m.final_radius[i]);
        flare_phase[i] = 6.2831853f * float(position_hash(t.position[i], 0x666c617265ull) >> 40) / 16777216.0f;
      } else if (trunk_h[par] >= 0 && cont[par] == int32_t(i) && trunk_h[par] < flare_h[par]) {
        trunk_h[i] = trunk_h[par] + glm::length(q[i] - q[par]);
        flare_h[i] = flare_h[par];
        flare_phase[i] = flare_phase[par];
      }
    }
  }

  const float twist = std::isfinite(p.twist) ? std::tan(glm::radians(std::clamp(p.twist, -80.0f, 80.0f))) : 0.0f;
  const float curve_step = glm::radians(std::isfinite(p.curve_angle) ? std::clamp(p.curve_angle, 0.5f, 180.0f) : 12.0f);
  const int curve_rings = std::clamp(p.curve_rings, 0, 16);
  const float cos_half_step = std::cos(0.4999f * curve_step);
  const float collar = std::isfinite(p.collar) ? std::clamp(p.collar, 0.0f, 4.0f) : 0.0f;
  const float collar_length = std::isfinite(p.collar_length) ? std::clamp(p.collar_length, 0.0f, 100.0f) : 0.0f;
  const float collar_min = std::isfinite(p.collar_min_radius) ? p.collar_min_radius : 0.0f;
  const float root_depth = std::isfinite(p.root_depth) ? std::clamp(p.root_depth, 0.0f, 10.0f) : 0.0f;

  std::vector<float> cos_a(stride), sin_a(stride), u_of(stride);
  for (int k = 0; k < stride; ++k) {
    const float a = 6.2831853f * float(k % seg) / float(seg);  // k = seg repeats k = 0 exactly
    cos_a[k] = std::cos(a);
    sin_a[k] = std::sin(a);
    u_of[k] = float(k) / float(seg);
  }
  // Constant texel density from trunk to twig: the texture wraps round(circumference * uv_repeat)
  // times around each axis (at least once), counted at the axis's base so it never jumps along it.
  std::vector<float> wraps(n, 1.0f);
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    if (par >= 0 && cont[par] == int32_t(i)) { wraps[i] = wraps[par]; continue; }
    const float w = std::round(6.2831853f * m.final_radius[i] * std::abs(uv_repeat));
    wraps[i] = std::isfinite(w) ? std::clamp(w, 1.0f, 64.0f) : 1.0f;
  }
  // One ring: centre c, axis tan, frame normal nrm, radius r, v coordinate v. With h >= 0 it is a
  // trunk ring h metres above the root, widened into buttress lobes; its normals then come from
  // the partial derivatives of the lobed surface. A cap's apex ring (apex) has every vertex at c,
  // its normal along tan. The walk below only plans the rings (their frames are carried from ring
  // to ring, so it is sequential); their vertices are written afterwards, in parallel chunks of
  // rings, each ring at the vertex index the walk gave it.
  struct ring_plan {
    glm::vec3 c, tan, nrm;
    float r, v, h, fh, phase;
    uint32_t node;
    bool apex;
  };
  std::vector<ring_plan> plans;
  auto emit_ring = [&](const glm::vec3& c, const glm::vec3& tan, const glm::vec3& nrm, float r, float v,
                       uint32_t node, float h, float fh, float phase) {
    plans.push_back({c, tan, nrm, r, v, h, fh, phase, node, false});
    return uint32_t((plans.size() - 1) * size_t(stride));
  };
  auto emit_apex = [&](const glm::vec3& c, const glm::vec3& nrm, float v, uint32_t node) {
    plans.push_back({c, nrm, nrm, 0, v, -1, 0, 0, node, true});
    return uint32_t((plans.size() - 1) * size_t(stride));
  };
  auto write_ring = [&](const ring_plan& rp, size_t at) {
    glm::vec3* out_pos = m.position.data() + at;
    glm::vec3* out_nrm = m.normal.data() + at;
    glm::vec2* out_uv = m.uv.data() + at;
    uint32_t* out_node = m.node.data() + at;
    const float w = wraps[rp.node];
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
        const float phi = 6.2831853f * u_of[k], x = float(lobes) * (phi - phase);
        const float c1 = 0.5f + 0.5f * std::cos(x);
        const float lobe = lobes ? c1 * c1 : 0.375f, dlobe = lobes ? -c1 * float(lobes) * std::sin(x) : 0.0f;  // 0.375: the lobes' mean
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
  };
  lap(st.frame);
  // Hermite form of each internode's centripetal Catmull-Rom segment (Yuksel, Schaefer & Keyser
  // 2011): the end velocities scaled by the segment's knot interval |b - a|^(1/2). A lateral leaves
  // its parent straight along its first internode; the trunk leaves its upright root upright.
  std::vector<glm::vec3> m1s(n), m2s(n);
  std::vector<float> want_score(n, 0.0f), collar_score(n, 0.0f);
  std::vector<uint8_t> want(n, 0), keep(n, 0), collared(n, 0);
  size_t tubes = 0, fixed_rings = 0, tips = 0;
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    if (par < 0) { tips += p.caps && cont[i] >= 0; continue; }
    ++tubes;
    tips += p.caps && cont[i] < 0;
    const bool lateral = cont[par] != int32_t(i);
    const glm::vec3 chord = q[i] - q[par];
    const float len = glm::length(chord), knot = std::sqrt(len);
    glm::vec3 m1 = lateral ? chord : vel[par] * knot, m2 = vel[i] * knot;
    if (t.parent[par] < 0 && !lateral) m1 = tangent[par] * len;
    const glm::vec3 dirn = len > 1e-12f ? chord / len : dir[i];
    auto clamp_speed = [&](glm::vec3 mv) {
      const float l = glm::length(mv);
      if (!(l > 1e-12f) || !std::isfinite(l)) return dirn * len;
      return mv * (std::clamp(l, 0.2f * len, 2.0f * len) / l);
    };
    m1s[i] = clamp_speed(m1);
    m2s[i] = clamp_speed(m2);
    if (!(len > 1e-9f)) continue;
    const float r = 0.5f * (m.final_radius[i] + m.final_radius[par]);
    // An internode whose curve turns by under curve_step at both ends together wants no ring, and
    // its turn is read for nothing else: when both ends' cosines lie above that of a little under
    // half the step (so that the two acosf, within an ulp or two each, sum to less than it), the
    // arc cosines are not taken.
    if (curve_rings > 0 && !(cosine_between(m1s[i], chord) > cos_half_step && cosine_between(chord, m2s[i]) > cos_half_step)) {
      float turn = angle_between(m1s[i], chord) + angle_between(chord, m2s[i]);
      if (!std::isfinite(turn)) turn = 0;
      want[i] = uint8_t(std::min(curve_rings, int(turn / curve_step)));
      want_score[i] = r * turn;   // the crease a kink leaves is about radius x angle wide
      if (!std::isfinite(want_score[i])) want[i] = 0, want_score[i] = 0;   // (no NaN in the sort below)
    }
    if (lateral && collar > 0 && m.final_radius[i] >= collar_min && std::isfinite(m.final_radius[i]))
      collar_score[i] = collar * m.final_radius[i];
    if (!lateral && trunk_h[par] >= 0 && trunk_h[par] < flare_h[par])
      for (float frac : {0.1f, 0.25f, 0.45f, 0.7f}) {
        const float u = (frac * flare_h[par] - trunk_h[par]) / len;
        fixed_rings += u > 0.02f && u < 0.98f;
      }
  }
  // Detail budget: curve and collar rings go where they show most, the widest creases first (the
  // j-th ring of an internode removes r x turn x (1/j - 1/(j+1)) of crease; a collar, its swell),
  // until the bark has detail_budget times the triangles of one ring per node. Caps and the
  // flare's rings come first.
  {
    const double per_ring = 2.0 * seg, budget = std::isfinite(p.detail_budget) ? std::clamp(p.detail_budget, 1.0f, 16.0f) : 1.5;
    const double base = per_ring * double(tubes), fixed = per_ring * double(fixed_rings) + double(seg) * double(tips);
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
        for (int j = keep[i] + 1; j <= want[i] && left > 0; ++j) {
          const float sc = want_score[i] / float(j * (j + 1));
          if (pass == 0 ? sc > threshold : sc == threshold) { keep[i] = uint8_t(j); --left; } else break;
        }
        if (collar_score[i] > 0 && !collared[i] && left > 0 &&
            (pass == 0 ? collar_score[i] > threshold : collar_score[i] == threshold)) { collared[i] = 1; --left; }
      }
  }
  lap(st.budget);
  // Every ring the loop below can plan (a ring too close to the last is skipped): the plans are
  // allocated once, at no more than this, and the vertex arrays at exactly the planned rings, so
  // the mesh bound (render/io/mesh_bound.h) holds with no vector slack.
  {
    size_t rings = n + tips, inner = 0;
    for (size_t i = 0; i < n; ++i) {
      const int32_t par = t.parent[i];
      inner += keep[i] + collared[i];
      if (par >= 0 && cont[par] != int32_t(i)) ++rings;   // a lateral's base ring
    }
    rings += inner + fixed_rings;
    plans.reserve(rings);
  }

  constexpr uint32_t none = UINT32_MAX;
  std::vector<glm::vec3> frame(n);
  std::vector<float> vcoord(n, 0.0f);
  std::vector<uint32_t> ring_start(n, 0), cap_apex(n, none);
  // The rings each internode's triangles run through, parent's ring first: chain[off[i]..off[i+1]).
  std::vector<uint32_t> chain, off(n + 1, 0);
  chain.reserve(2 * tubes + fixed_rings + std::accumulate(keep.begin(), keep.end(), size_t(0)) +
                std::accumulate(collared.begin(), collared.end(), size_t(0)));
  std::vector<float> us;
  for (size_t i = 0; i < n; ++i) {
    const int32_t par = t.parent[i];
    off[i] = uint32_t(chain.size());
    if (par < 0) {
      frame[i] = any_perpendicular(tangent[i]);
      // An upright trunk stands in the ground: its foot ring is sunk root_depth below the root, at
      // the flare's full spread (h = 0), so the lobes run into the ground instead of ending in a cut.
      const bool upright = cont[i] >= 0 && glm::dot(tangent[i], up_axis) > 0.999f;
      const float sink = upright ? root_depth : 0.0f;
      const glm::vec3 foot = q[i] - up_axis * sink;
      ring_start[i] = emit_ring(foot, tangent[i], frame[i], m.final_radius[i], -sink * uv_repeat, uint32_t(i),
                                trunk_h[i], flare_h[i], flare_phase[i]);
      if (p.caps && cont[i] >= 0)  // the trunk's foot, flat, facing down
        cap_apex[i] = emit_apex(foot, -tangent[i], -sink * uv_repeat, uint32_t(i));
      continue;
    }
    const bool lateral = cont[par] != int32_t(i);
    const glm::vec3 a = q[par], b = q[i], chord = b - a;
    const float len = glm::length(chord);
    const float ri = m.final_radius[i], ra = m.final_radius[par];
    const glm::vec3 m1 = m1s[i], m2 = m2s[i];
    const glm::vec3 dirn = len > 1e-12f ? chord / len : dir[i];
    const glm::vec3 t_start = lateral ? dirn : tangent[par];

    // Ring parameters inside the internode: where the curve turns, up the flare, at the collar.
    us.clear();
    if (keep[i] > 0) {
      // Rings at equal shares of the curve's turning (16 samples of its tangent), so an S-shaped
      // segment between zig-zag nodes gets them near its ends, where it turns most.
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
      for (int j = 1; j <= keep[i]; ++j) {
        float u = float(j) / float(keep[i] + 1);
        if (total_turn > 1e-6f && std::isfinite(total_turn)) {
          const float goal = total_turn * float(j) / float(keep[i] + 1);
          int sidx = 1;
          while (sidx < samples && cum[sidx] < goal) ++sidx;
          const float span = cum[sidx] - cum[sidx - 1];
          u = (float(sidx - 1) + (span > 0 ? (goal - cum[sidx - 1]) / span : 0.5f)) / samples;
        }
        us.push_back(u);
      }
    }
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
    const float swell = collared[i] ? std::min(rb * (1 + collar), std::max(rb, 0.98f * ra)) : rb;
    if (collared[i]) {
      const float sin_t = glm::length(glm::cross(dirn, tangent[par])), cos_t = std::abs(glm::dot(dirn, tangent[par]));
      const float d_exit = (ra + swell * cos_t) / std::max(sin_t, 0.25f);
      u2 = std::min(d_exit + collar_length * ri, 0.9f * len) / len;
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
      chain.push_back(emit_ring(a, dirn, from_n, radius_at(0), v, uint32_t(i), -1, 0, 0));
    } else {
      from_n = frame[par];
      chain.push_back(ring_start[par]);
    }
    float last_u = 0;
    for (float u : us) {
      if (u - last_u < 0.02f || u > 0.98f) continue;
      last_u = u;
      const float u2_ = u * u, u3 = u2_ * u;
      const glm::vec3 c = a * (2 * u3 - 3 * u2_ + 1) + m1 * (u3 - 2 * u2_ + u) + b * (-2 * u3 + 3 * u2_) + m2 * (u3 - u2_);
      glm::vec3 tc = a * (6 * u2_ - 6 * u) + m1 * (3 * u2_ - 4 * u + 1) + b * (-6 * u2_ + 6 * u) + m2 * (3 * u2_ - 2 * u);
      const float tl = glm::length(tc);
      tc = tl > 1e-12f && std::isfinite(tl) ? tc / tl : dirn;
      const glm::vec3 nn = transport(from_n, from_t, tc);
      v += glm::length(c - prev_c) * uv_repeat;
      const float h = on_trunk ? trunk_h[par] + u * len : -1.0f;
      chain.push_back(emit_ring(c, tc, nn, radius_at(u), v, uint32_t(i), h, flare_h[par], flare_phase[par]));
      from_t = tc;
      from_n = nn;
      prev_c = c;
    }
    frame[i] = transport(from_n, from_t, tangent[i]);
    v += glm::length(b - prev_c) * uv_repeat;
    vcoord[i] = v;
    ring_start[i] = emit_ring(b, tangent[i], frame[i], ri, v, uint32_t(i), trunk_h[i], flare_h[i], flare_phase[i]);
    chain.push_back(ring_start[i]);
    // A tip's cap: a cone as high as the tip's radius, so it stays a hemisphere's outline as the
    // per-step radius moves its ring and apex (vertex shader) by the same amount.
    if (p.caps && cont[i] < 0) cap_apex[i] = emit_apex(b + tangent[i] * ri, tangent[i], v + ri * uv_repeat, uint32_t(i));
  }
  off[n] = uint32_t(chain.size());
  // What only the walk needed goes before the vertex arrays come, so the plans cost no peak memory.
  auto release = [](auto& v) { std::remove_reference_t<decltype(v)>().swap(v); };
  release(q), release(dir), release(best), release(vel), release(tangent), release(trunk_h), release(flare_h);
  release(flare_phase), release(m1s), release(m2s), release(want_score), release(collar_score), release(want);
  release(keep), release(collared), release(frame), release(vcoord), release(us);
  // Each node's share of the index buffer (its internode through its rings, and its cap). The
  // buffer, the largest array, is made first: the heap's large holes are an older mesh's, and made
  // last it often found none left (self_organizing_default).
  const uint32_t quad_ring = uint32_t(6 * seg), cap_idx = uint32_t(3 * seg);
  auto index_count = [&](size_t i) {
    const uint32_t rings = off[i + 1] - off[i];
    return (rings > 1 ? (rings - 1) * quad_ring : 0) + (cap_apex[i] != none ? cap_idx : 0);
  };
  size_t total_index = 0;  // (the stage below checks it against its prefix sums)
  for (size_t i = 0; i < n; ++i) total_index += index_count(i);
  m.index.resize(total_index);
  const size_t vertices = plans.size() * size_t(stride);
  m.position.resize(vertices);
  m.normal.resize(vertices);
  m.uv.resize(vertices);
  m.node.resize(vertices);
  parallel_chunks(plans.size(), 1024, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) write_ring(plans[k], k * size_t(stride));
  });
  release(plans);
  lap(st.rings);

  // Each node's triangles (its internode through its rings, and its cap) sorted by born step so
  // that step s draws a prefix of the index buffer (DESIGN §5).
  std::vector<uint32_t> count(n);
  std::vector<uint32_t> item;
  item.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    count[i] = index_count(i);
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
    for (uint32_t r = off[i]; r + 1 < off[i + 1]; ++r) {
      const uint32_t lo = chain[r], hi = chain[r + 1];
      for (int s = 0; s < seg; ++s) {
        const uint32_t a = lo + s, b = lo + s + 1, c = hi + s, d = hi + s + 1;  // CCW from outside
        *out++ = a; *out++ = b; *out++ = c;
        *out++ = b; *out++ = d; *out++ = c;
      }
    }
    if (cap_apex[i] != none) {
      const uint32_t ring = ring_start[i], apex = cap_apex[i];
      const bool foot = t.parent[i] < 0;   // the foot faces down: the other winding
      for (int s = 0; s < seg; ++s) {
        *out++ = foot ? ring + s + 1 : ring + s;
        *out++ = foot ? ring + s : ring + s + 1;
        *out++ = apex + s;
      }
    }
  }
  });
  lap(st.index);
}

}  // namespace

tree_mesh mesh_tree(const tree_skeleton& t, const mesh_params& p, uint64_t seed, mesh_stage_times* times) {
  tree_mesh m;
  mesh_stage_times unused;
  mesh_stage_times& st = times ? *times : unused;
  st = {};
  auto lap_start = clock_type::now();
  auto lap = [&](double& field) {   // adds the time since the last lap to one stage
    const auto now = clock_type::now();
    field += ms_between(lap_start, now);
    lap_start = now;
  };
  m.steps = std::max(t.steps, 0);
  m.radial_segments = std::clamp(p.radial_segments, 3, 256);
  m.blade = leaf_blade_shape{p.leaves.blades, std::isfinite(p.leaves.fold) ? p.leaves.fold : 0.0f,
                             std::isfinite(p.leaves.curl) ? p.leaves.curl : 0.0f,
                             std::isfinite(p.leaves.needle_spread) ? p.leaves.needle_spread : 360.0f};
  m.index_end.assign(size_t(m.steps) + 1, 0);
  m.leaf_end.assign(size_t(m.steps) + 1, 0);
  if (!structurally_sound(t)) return m;

  const size_t n = t.size();
  std::vector<rotation_terms> turn;
  std::vector<glm::vec3> disp;
  foliage placed;
  const bool own = p.leaves.mode == leaf_mode::generator && !t.leaves.empty();
  const bool fruit = p.fruits.count > 0;   // the generator's own leaves are then copied, fruit added
  // Leaf placement and the crown's sky field read only the skeleton: they run on a pool helper
  // beside the bark (job_pool.h), or after it here when none is free (st.leaf_place and st.sky are
  // their own times). The bark runs here only (a helper taking both runs the leaves), so its arrays
  // never fill a helper's malloc arena.
  const std::thread::id caller = std::this_thread::get_id();
  const bool place = p.leaves_enabled && (!own || fruit);
  const std::vector<leaf>& src = own && !fruit ? t.leaves : placed.leaves;   // the generator's, uncopied
  const size_t cap = size_t(std::clamp(p.leaves.cap, 1, 2000000));
  const float scale = std::isfinite(p.leaf_scale) ? p.leaf_scale : 1.0f;
  auto usable = [&](const leaf& l) { return l.node >= 0 && size_t(l.node) < n && finite3(l.position); };
  auto step_of = [&](const leaf& l) { return std::min<int>(l.born, m.steps); };
  size_t kept = 0, end = 0;   // leaves kept (usable, up to the cap); src[0, end) holds them
  crown_sky sky;
  std::vector<uint32_t> slot;   // each kept leaf's place in m.leaves (the leaves job's counting sort)
  std::atomic<bool> bark_taken{false}, leaves_taken{!p.leaves_enabled};
  auto bark = [&] { mesh_bark(t, p, m, st, turn, disp); };
  auto leaves = [&] {
    const auto t0 = clock_type::now();
    if (place) {
      if (!own) placed = place_leaves(t, p.leaves, seed);
      else placed.leaves = t.leaves;
      if (fruit) place_fruits(t, p.fruits, seed, p.leaves.ground, placed.leaves);
    }
    const auto t1 = clock_type::now();
    st.leaf_place = ms_between(t0, t1);
    // One pass over the leaves the sort below keeps (usable, up to the cap): each step's count for
    // the counting sort, and where they hang before gnarl for the sky field.
    std::vector<glm::vec4> crown;
    crown.reserve(std::min(src.size(), cap));
    end = src.size();
    for (size_t k = 0; k < src.size(); ++k) {
      const leaf& l = src[k];
      if (!usable(l)) continue;
      if (kept == cap) { end = k; placed.capped = true; break; }
      ++kept;
      ++m.leaf_end[step_of(l)];
      crown.emplace_back(l.position, l.size * scale);
    }
    sky = bake_crown_sky(crown);
    // Each kept leaf's slot in the sort by born step below (a counting sort: prefix sums, then
    // the leaves in order), here beside the bark rather than after it.
    std::vector<uint32_t> cursor(m.leaf_end.size(), 0);
    for (size_t s = 1; s < m.leaf_end.size(); ++s) {
      m.leaf_end[s] += m.leaf_end[s - 1];
      cursor[s] = m.leaf_end[s - 1];
    }
    slot.assign(end, UINT32_MAX);
    for (size_t k = 0; k < end; ++k)
      if (usable(src[k])) slot[k] = cursor[step_of(src[k])]++;
    st.sky = ms_since(t1);
  };
  parallel_jobs(p.leaves_enabled ? 2 : 1, [&](size_t) {
    if (std::this_thread::get_id() == caller && !bark_taken.exchange(true)) bark();
    if (!leaves_taken.exchange(true)) leaves();
  });
  if (!bark_taken.exchange(true)) bark();
  lap_start = clock_type::now();

  // Leaves: the foliage model (leaves.h) or the generator's own, capped at the leaf cap, sorted by
  // born straight into m.leaves (no temporary copy of every leaf): the leaves job counted each
  // step's leaves and gave each its slot. Chunks of them are written, and shaded from the crown
  // field, in the batch that shades the bark.
  crown_leaf_jobs leaf_jobs;
  if (p.leaves_enabled) {
    if (placed.capped)
      m.message = "leaf cap reached: " + std::to_string(kept) + " leaves placed (raise Leaf cap or Leaf spacing)";
    m.leaves.resize(m.leaf_end.back());
    const uint8_t fallback = uint8_t(std::clamp(int(p.leaves.archetype), 0, leaf_archetype_count - 1));
    // Sun and shade leaves for the foliage model's leaves; a generator's own keep the sizes it gave.
    const float shade_size = own || !std::isfinite(p.leaves.shade_size) ? 0.0f : std::clamp(p.leaves.shade_size, 0.0f, 1.0f);
    constexpr size_t grain = 2048;
    leaf_jobs.count = (end + grain - 1) / grain;
    leaf_jobs.run = [&, fallback, shade_size](size_t j, glm::vec3& box_lo, glm::vec3& box_hi) {
      glm::vec3 lo = box_lo, hi = box_hi;   // (in registers: the leaves written could alias the box)
      for (size_t k = j * grain; k < std::min(end, (j + 1) * grain); ++k) {
        if (slot[k] == UINT32_MAX) continue;
        const leaf& l = src[k];
        const glm::quat q = l.orientation;
        const uint8_t tex = l.archetype < leaf_archetype_count ? l.archetype : fallback;  // texture = archetype
        leaf_instance& out = m.leaves[slot[k]];
        out = {gnarled_point(t, turn, disp, size_t(l.node), l.position), glm::vec4(q.x, q.y, q.z, q.w), l.size * scale,
               l.born, l.died, uint32_t(l.node), tex};
        shade_leaf(out, sky, lo, hi);
        if (shade_size > 0 && !leaf_archetype_fruit[tex]) {   // sun and shade leaves (leaves.h leaf_shade_size)
          const float open = std::clamp((float(out.occlusion) / 255.0f - 0.35f) / 0.65f, 0.0f, 1.0f);
          out.size *= 1.0f + shade_size * (0.5f - open);
          lo = glm::min(lo, out.position - glm::vec3(out.size)), hi = glm::max(hi, out.position + glm::vec3(out.size));
        }
      }
      box_lo = lo, box_hi = hi;
    };
  }
  shade_by_crown(m, sky, true, &leaf_jobs);   // and the bounds, in the same parallel passes
  lap(st.occlusion);
  std::vector<rotation_terms>().swap(turn), std::vector<glm::vec3>().swap(disp), std::vector<leaf>().swap(placed.leaves),
      std::vector<uint32_t>().swap(slot);  // done with
  return m;
}

}  // namespace sylva
