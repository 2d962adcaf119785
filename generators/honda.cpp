// Honda's parametric binary tree as an L-system (Prusinkiewicz, Hammel, Hanan & Měch 1996).
#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat3x3.hpp>

#include "generators/keyframes.h"
#include "generators/pruning.h"
#include "generators/lsystem.h"
#include "generators/resume.h"

namespace sylva {
namespace {

// An unrewritten apex A(s,w) with the turtle state it was created in.
struct apex {
  glm::mat3 frame;   // columns: heading H, left L, up U (ABOP §1.5)
  glm::vec3 base;    // model units
  float s, w;
  int32_t node;      // node at the apex's base
  uint8_t order;
};

}  // namespace

// Everything a derivation reads, at the top of derivation `step` (before its keyframes and cuts):
// resuming from it grows what a full regrow grows from there (generators/resume.h).
struct honda_state {
  tree_skeleton t;
  std::vector<apex> current;
  lsystem_params p;
  float wq1 = 0, wq2 = 0;
  grow_report rep;
};

tree_skeleton grow_honda(const lsystem_params& p_in, const grow_options& o, grow_report* report) {
  lsystem_params p = p_in;   // growth phases change it from a keyed derivation on
  grow_report local;
  grow_report& rep = report ? *report : local;
  const int steps = o.steps >= 0 ? o.steps : p.derivations;
  const float radius_of_width = 0.5f * p.scale * p.width_scale;

  tree_skeleton t;
  // H = +Y (up), L = +X, U = −Z: the text turtle's right-handed start frame (lsystem_turtle.cpp).
  const glm::mat3 frame0 = lsystem_start_frame();
  t.add_node(glm::vec3(0), -1, p.w0 * radius_of_width, 0, 0);

  // Derivations proceed in parallel over all apices (breadth first), so the nodes of derivation
  // k follow those of k-1: growing s steps yields exactly the prefix born <= s.
  std::vector<apex> current{{frame0, glm::vec3(0), p.s0, p.w0, 0, 0}}, next;
  float wq1 = std::pow(p.q, p.e), wq2 = std::pow(1 - p.q, p.e);
  int step = 0;
  int first = 1;
  growth_resume* const resume = o.resume;
  if (resume && resume->from_step >= 1 && resume->from_step <= steps && size_t(resume->from_step) < resume->honda.size() &&
      resume->honda[size_t(resume->from_step)]) {
    const honda_state& s = *resume->honda[size_t(resume->from_step)];
    t = s.t;
    current = s.current;
    p = s.p;
    wq1 = s.wq1, wq2 = s.wq2;
    rep = s.rep;
    first = resume->from_step;
    step = first - 1;
    resume->resumed_at = first;
  }
  if (resume && resume->record) resume->honda.resize(size_t(first));   // what is recorded from here on is replaced
  for (int k = first; k <= steps && !current.empty(); ++k) {
    if (o.cancelled()) { rep.cancelled = true; break; }
    if (resume && resume->record) {
      const std::vector<int>& only = resume->record_steps;
      resume->honda.resize(size_t(k) + 1);
      if (only.empty() || std::find(only.begin(), only.end(), k) != only.end())
        resume->honda[size_t(k)] = std::make_shared<const honda_state>(honda_state{t, current, p, wq1, wq2, rep});
    }
    // Growth phases: derivation k rewrites with the values keyed up to k (the daughters it
    // creates carry them into the internodes of derivation k+1).
    if (apply_keyframes(p, o.keyframes, k)) {
      clamp_all_params(p);
      wq1 = std::pow(p.q, p.e), wq2 = std::pow(1 - p.q, p.e);
    }
    // Pruning: the apices on a cut branch go with it; nothing else in the model responds.
    if (!apply_cuts(t, o.cuts, k, rep).empty())
      std::erase_if(current, [&](const apex& a) { return t.died[size_t(a.node)] != never_died; });
    next.clear();
    for (const apex& a : current) {
      if (!(a.s >= p.min_length)) continue;  // condition fails: A stays as it is, forever
      if (int64_t(t.size()) >= p.node_cap) {
        rep.hit_node_cap = true;
        break;
      }
      // !(w)F(s): draw an internode of length s and width w.
      const glm::vec3 tip = a.base + a.frame[0] * a.s;
      const int32_t node = t.add_node(tip * p.scale, a.node, a.w * radius_of_width, uint16_t(k), a.order);
      // Daughters; the longer one continues the axis (same order), the other is a lateral.
      const bool first_main = p.r1 >= p.r2;
      // [+(α)/(φ)A...]: turn by R_U(α), then roll by '/' = R_H(−φ) (ABOP §1.5).
      next.push_back({turtle_roll(turtle_turn(a.frame, p.alpha1), -p.phi1), tip, a.s * p.r1, a.w * wq1, node,
                      uint8_t(a.order + (first_main ? 0 : 1))});
      next.push_back({turtle_roll(turtle_turn(a.frame, p.alpha2), -p.phi2), tip, a.s * p.r2, a.w * wq2, node,
                      uint8_t(a.order + (first_main ? 1 : 0))});
    }
    step = k;
    std::swap(current, next);
    if (rep.hit_node_cap) break;
    if (o.progress) o.progress(float(k) / float(std::max(steps, 1)));
  }
  t.steps = step;
  if (rep.hit_node_cap)
    rep.message = "node cap reached (" + std::to_string(p.node_cap) + " nodes) at derivation " +
                  std::to_string(step) + "; raise node_cap or lower the derivation count";
  rep.stop = rep.hit_node_cap ? grow_stop::node_cap : rep.cancelled ? grow_stop::cancelled : grow_stop::finished;
  rep.stop_reason = rep.hit_node_cap ? "node cap" : rep.cancelled ? "cancelled" : "derivations done";
  return t;
}

}  // namespace sylva
