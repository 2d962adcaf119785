// The 3D turtle (ABOP ch. 1, §2.4 tropism) that turns a derived string into a tree skeleton.
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "generators/history.h"
#include "generators/lsystem_engine.h"

namespace sylva {

glm::mat3 lsystem_start_frame() { return glm::mat3(glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), glm::vec3(0, 0, -1)); }
glm::mat3 turtle_turn(const glm::mat3& f, float deg) {   // R_U(δ) = Rz(−δ)
  return f * glm::mat3(glm::rotate(glm::mat4(1), glm::radians(-deg), glm::vec3(0, 0, 1)));
}
glm::mat3 turtle_pitch(const glm::mat3& f, float deg) {  // R_L(δ) = Ry(−δ)
  return f * glm::mat3(glm::rotate(glm::mat4(1), glm::radians(-deg), glm::vec3(0, 1, 0)));
}
glm::mat3 turtle_roll(const glm::mat3& f, float deg) {   // R_H(δ) = Rx(δ)
  return f * glm::mat3(glm::rotate(glm::mat4(1), glm::radians(deg), glm::vec3(1, 0, 0)));
}

namespace {

// Frame columns: heading H, left L, up U (ABOP §1.5), always right-handed (H × L = U).
// Handedness, one choice for all six turns: ABOP §1.5's rotation matrices exactly as printed,
// [H' L' U'] = [H L U]·R, with R_U(δ) for +, R_L(δ) for &, R_H(δ) for \ and the negated angles
// for -, ^, /. In glm's column terms R_U(δ) = Rz(−δ), R_L(δ) = Ry(−δ), R_H(δ) = Rx(δ). The start
// frame H = +Y, L = +X, U = −Z makes + turn H towards −L = −X: anticlockwise for a viewer on +Z,
// which is ABOP's "turn left" and its printed 2D figures (1.24, the Koch curves) as they stand.
// The matrices then fix & and / relative to +, as in the program that drew the book's 3D figures.
// honda.cpp uses the same functions, so Honda's production written as text gives the same tree.
glm::mat3 turn_u(const glm::mat3& f, float deg) { return turtle_turn(f, deg); }
glm::mat3 pitch_l(const glm::mat3& f, float deg) { return turtle_pitch(f, deg); }
glm::mat3 roll_h(const glm::mat3& f, float deg) { return turtle_roll(f, deg); }

struct turtle_state {
  glm::vec3 pos{0};      // model units
  glm::mat3 frame{1};
  float width = 1;
  int32_t node = -1;     // node at the turtle's position, -1 after f (a new piece starts)
  uint8_t order = 0;
  int colour = 0;
};

}  // namespace

tree_skeleton interpret_lsystem(const lsystem_program& prog, const lsystem_string& s, const lsystem_params& p,
                                int steps, grow_report& rep, const grow_options* o) {
  tree_skeleton t;
  t.steps = steps;
  const float radius_of_width = 0.5f * p.scale * p.width_scale;  // widths are diameters, like Honda's
  auto radius = [&](float w) {
    const float r = w * radius_of_width;
    return std::isfinite(r) && r > 0 ? r : 0.0f;
  };
  turtle_state tu;
  // H = +Y (up), L = +X, U = −Z, as in honda.cpp.
  tu.frame = lsystem_start_frame();
  tu.width = prog.width;
  std::vector<turtle_state> stack;
  std::vector<uint8_t> has_child;
  // The seedling: a root at the origin, born at step 0, even when nothing is drawn.
  tu.node = t.add_node(glm::vec3(0), -1, radius(tu.width), 0, 0);
  has_child.push_back(0);
  int roots = 1;
  const glm::vec3 T = prog.tropism;
  const float e = prog.susceptibility;
  bool bad_position = false;
  // Seasons (generators/history.h): an F written by derivation k grows exp(a·z_k) times as long.
  std::vector<float> season;
  if (p.season_variation > 0 && o) {
    season = season_anomalies(o->seed, steps);
    for (float& z : season) z = season_vigour(p.season_variation, z);
  }
  auto arg = [&](const lsystem_module& m, float fallback) { return m.count ? s.params[m.param] : fallback; };
  auto ensure_node = [&](uint16_t born) {
    if (tu.node >= 0) return;
    tu.node = t.add_node(tu.pos * p.scale, -1, radius(tu.width), born, tu.order);
    has_child.push_back(0);
    ++roots;
  };

  const size_t n = s.modules.size();
  for (size_t i = 0; i < n; ++i) {
    if ((i & 0xFFFF) == 0xFFFF && o && o->cancelled()) {
      rep.cancelled = true;
      break;
    }
    const lsystem_module& m = s.modules[i];
    const uint8_t c = m.symbol;
    if (c == 'F' || prog.draws[c]) {
      const float length = arg(m, prog.step) * (season.empty() ? 1.0f : season[std::min<size_t>(m.born, season.size() - 1)]);
      const glm::vec3 next = tu.pos + tu.frame[0] * length;
      if (!std::isfinite(next.x) || !std::isfinite(next.y) || !std::isfinite(next.z)) {
        bad_position = true;
        continue;
      }
      if (int64_t(t.size()) >= p.node_cap) {
        rep.hit_node_cap = true;
        break;
      }
      ensure_node(m.born);
      const int32_t par = tu.node;
      // A node is never born before its parent: born = max(module's derivation, parent's).
      const uint16_t born = std::max(m.born, t.born[size_t(par)]);
      const float r = radius(tu.width);
      if (!has_child[size_t(par)] && t.parent[size_t(par)] < 0) t.radius[size_t(par)] = r;
      has_child[size_t(par)] = 1;
      tu.pos = next;
      tu.node = t.add_node(tu.pos * p.scale, par, r, born, tu.order);
      has_child.push_back(0);
      // Tropism (ABOP §2.4): rotate H towards T about H×T by α = e·|H × T|.
      if (e != 0) {
        const glm::vec3 axis = glm::cross(tu.frame[0], T);
        const float len = glm::length(axis);
        if (len > 1e-6f) {
          const glm::mat3 rot(glm::rotate(glm::mat4(1), e * len, axis / len));
          tu.frame = rot * tu.frame;
        }
      }
      continue;
    }
    switch (c) {
      case 'f': {
        const glm::vec3 next = tu.pos + tu.frame[0] * arg(m, prog.step);
        if (!std::isfinite(next.x) || !std::isfinite(next.y) || !std::isfinite(next.z)) {
          bad_position = true;
          break;
        }
        tu.pos = next;
        tu.node = -1;
        break;
      }
      // ABOP §1.5: + R_U(δ), - R_U(−δ), & R_L(δ), ^ R_L(−δ), \ R_H(δ), / R_H(−δ), | R_U(180°).
      case '+': tu.frame = turn_u(tu.frame, arg(m, prog.angle)); break;
      case '-': tu.frame = turn_u(tu.frame, -arg(m, prog.angle)); break;
      case '&': tu.frame = pitch_l(tu.frame, arg(m, prog.angle)); break;
      case '^': tu.frame = pitch_l(tu.frame, -arg(m, prog.angle)); break;
      case '\\': tu.frame = roll_h(tu.frame, arg(m, prog.angle)); break;
      case '/': tu.frame = roll_h(tu.frame, -arg(m, prog.angle)); break;
      case '|': tu.frame = turn_u(tu.frame, 180); break;
      case '[':
        stack.push_back(tu);
        if (tu.order < 255) ++tu.order;
        break;
      case ']':
        if (!stack.empty()) {  // an unmatched ']' is ignored rather than trusted
          tu = stack.back();
          stack.pop_back();
        }
        break;
      case '!':
        if (m.count) tu.width = s.params[m.param];
        break;
      case '$': {  // ABOP §1.5: roll so that L is horizontal: L = V×H/|V×H|, U = H×L
        const glm::vec3 V(0, 1, 0);
        const glm::vec3 l = glm::cross(V, tu.frame[0]);
        const float len = glm::length(l);
        if (len > 1e-6f) {
          tu.frame[1] = l / len;
          tu.frame[2] = glm::cross(tu.frame[0], tu.frame[1]);
        }
        break;
      }
      case 'L': {
        ensure_node(m.born);
        leaf lf;
        lf.position = tu.pos * p.scale;
        // Blade along H, normal along U: columns X = H×U (= -L), Y = H, Z = U.
        lf.orientation = glm::quat_cast(glm::mat3(-tu.frame[1], tu.frame[0], tu.frame[2]));
        lf.size = m.count ? std::max(0.0f, s.params[m.param] * p.scale) : p.leaf_size;
        if (!std::isfinite(lf.size)) lf.size = 0;
        lf.node = tu.node;
        lf.born = std::max(m.born, t.born[size_t(tu.node)]);
        t.leaves.push_back(lf);
        break;
      }
      case '\'': ++tu.colour; break;
      default: break;  // other symbols do not move the turtle
    }
  }
  t.tree_count = roots;
  if (rep.hit_node_cap)
    rep.message = "node cap reached (" + std::to_string(p.node_cap) + " nodes): the rest of the string is not drawn";
  else if (bad_position)
    rep.message = "some F/f lengths gave non-finite positions and were skipped";
  return t;
}

tree_skeleton grow_lsystem_text(const lsystem_params& p, const grow_options& o, grow_report* report) {
  grow_report local;
  grow_report& rep = report ? *report : local;
  lsystem_program prog;
  const lsystem_error err = compile_lsystem(p.source, prog);
  if (!err.ok()) {
    tree_skeleton t;
    t.add_node(glm::vec3(0), -1, 0.5f * p.scale * p.width_scale, 0, 0);
    rep.error = true;
    rep.message = "line " + std::to_string(err.line) + ", column " + std::to_string(err.column) + ": " + err.message;
    rep.stop = grow_stop::parse_error;
    rep.stop_reason = "parse error";
    return t;
  }
  const int steps = o.steps >= 0 ? o.steps : p.derivations;
  lsystem_derive_report dr;
  const lsystem_string s = derive_lsystem(prog, steps, o.seed, p.module_cap, o, dr);
  tree_skeleton t = interpret_lsystem(prog, s, p, dr.derivations, rep, &o);
  self_prune(t, p.live_crown, p.stub_length);   // lower limbs shaded out leave stubs (history.h)
  if (p.widths == lsystem_widths::pipe) apply_pipe_radii(t, p.pipe_exponent, p.tip_radius, p.pipe_taper);
  rep.cancelled = rep.cancelled || dr.cancelled;
  if (dr.error || dr.hit_module_cap) {
    rep.error = dr.error;
    rep.message = dr.message + (rep.message.empty() ? "" : "; " + rep.message);
  }
  rep.stop = dr.error ? grow_stop::evaluation_error : dr.hit_module_cap ? grow_stop::module_cap
             : rep.hit_node_cap ? grow_stop::node_cap : dr.cancelled ? grow_stop::cancelled : grow_stop::finished;
  rep.stop_reason = dr.error ? "evaluation error" : dr.hit_module_cap ? "module cap" : rep.hit_node_cap ? "node cap"
                    : dr.cancelled ? "cancelled" : "derivations done";
  if (o.progress) o.progress(1.0f);
  return t;
}

}  // namespace sylva
