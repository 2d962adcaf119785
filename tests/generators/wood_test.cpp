// The wood pass (generators/wood.h): beam formulas, history, reaction wood, the pipe model, lean,
// extremes and determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>

#include "generators/tree_spec.h"
#include "generators/wood.h"
#include "render/io/preset.h"
#include "render/mesh/mesh.h"

using namespace sylva;

namespace {

constexpr double g0 = 9.80665;
constexpr double pi = 3.14159265358979;

// A horizontal branch along +x from the origin: `segments` internodes of equal length and radius.
// born_per_step: node k is born in step k (a branch growing one internode a step), else all at 0.
tree_skeleton cantilever(int segments, float length, float radius, bool born_per_step = false) {
  tree_skeleton t;
  t.add_node(glm::vec3(0), -1, radius, 0, 0);
  for (int k = 1; k <= segments; ++k)
    t.add_node(glm::vec3(length * float(k) / float(segments), 0, 0), k - 1, radius,
               uint16_t(born_per_step ? k : 0), 1);
  t.steps = born_per_step ? segments : 0;
  return t;
}

wood_params beam_wood() {
  wood_params p;
  p.gravity = 1;
  p.leaf_mass = 0;
  p.recovery = 0;
  p.max_bend = 90;
  p.ground_rest = -1;   // a cantilever in the air: the beam formulas have no soil under the tip
  return p;
}

bool all_finite(const std::vector<glm::vec3>& v) {
  for (const glm::vec3& p : v)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
  return true;
}

// The soil: a heavy horizontal branch 1 m up sags to the ground and rests there, level, at
// ground_rest above its base, with every internode's length kept; off (ground_rest < 0) it passes
// through. A branch that stays above the soil is bit for bit the pass without it.
TEST(Wood, AShootBentDownToTheSoilRestsOnIt) {
  // A 3 m branch of 8 mm radius, held level 0.5 m up on a short stiff stem.
  auto branch = [] {
    tree_skeleton t;
    t.add_node(glm::vec3(0), -1, 0.2f, 0, 0);
    t.add_node(glm::vec3(0, 0.5f, 0), 0, 0.2f, 0, 1);
    for (int k = 1; k <= 10; ++k) t.add_node(glm::vec3(0.3f * float(k), 0.5f, 0), k, 0.008f, 0, 1);
    return t;
  };
  const tree_skeleton t = branch();
  wood_params p = beam_wood();
  p.max_bend = 30;
  p.ground_rest = 0.1f;
  const std::vector<glm::vec3> rest = bend_static(t, p);
  p.ground_rest = -1;
  const std::vector<glm::vec3> through = bend_static(t, p);
  ASSERT_LT(through.back().y, -0.1f) << "the load must reach below the soil for the test to mean anything";
  float lowest = INFINITY;
  for (size_t k = 1; k < t.size(); ++k) {
    lowest = std::min(lowest, rest[k].y);
    const float len0 = glm::length(t.position[k] - t.position[size_t(t.parent[k])]);
    EXPECT_NEAR(glm::length(rest[k] - rest[size_t(t.parent[k])]), len0, 1e-4f) << k;
  }
  EXPECT_NEAR(lowest, 0.1f, 1e-4f);
  EXPECT_NEAR(rest.back().y, 0.1f, 1e-4f);   // the tip lies on the soil
  EXPECT_GT(rest.back().x, through.back().x);   // heading on where it headed, not folded back
  EXPECT_EQ(rest[5], through[5]);   // the part still in the air is the pass's own bend
  // Light enough to stay in the air: the soil changes nothing.
  p.gravity = 0.05f;
  p.ground_rest = 0.1f;
  const std::vector<glm::vec3> air = bend_static(t, p);
  p.ground_rest = -1;
  EXPECT_EQ(air, bend_static(t, p));
}

}  // namespace

TEST(Wood, DistributedLoadMatchesTheBeamFormula) {
  // Self-weight w = ρ g π r² per metre: δ = w L⁴ / (8 E I), I = π r⁴ / 4 (Euler-Bernoulli cantilever).
  const float L = 2, r = 0.02f;
  const tree_skeleton t = cantilever(20, L, r);
  const wood_params p = beam_wood();
  const std::vector<glm::vec3> x = bend_static(t, p);
  const double w = p.density * g0 * pi * r * r;
  const double EI = p.modulus * 1e9 * pi * std::pow(r, 4) / 4;
  const double expected = w * std::pow(L, 4) / (8 * EI);
  const double tip = -x.back().y;
  EXPECT_GT(expected, 0.005);   // a visible sag, and still a small deflection (under 2 % of L)
  EXPECT_LT(expected, 0.04);
  EXPECT_NEAR(tip, expected, 0.05 * expected) << "tip " << tip << " formula " << expected;
}

TEST(Wood, EndLoadMatchesTheBeamFormula) {
  // A mass at the tip of a weightless branch: δ = P L³ / (3 E I).
  const float L = 1.5f, r = 0.015f;
  const tree_skeleton t = cantilever(16, L, r);
  wood_params p = beam_wood();
  p.density = 0;
  std::vector<float> mass(t.size(), 0.0f);
  mass.back() = 2.0f;  // kg
  const std::vector<glm::vec3> x = bend_static(t, p, &mass);
  const double EI = p.modulus * 1e9 * pi * std::pow(r, 4) / 4;
  const double expected = 2.0 * g0 * std::pow(L, 3) / (3 * EI);
  EXPECT_NEAR(-x.back().y, expected, 0.05 * expected);
  // Stiffness grows as r⁴: twice the radius, a sixteenth of the sag.
  const tree_skeleton thick = cantilever(16, L, 2 * r);
  const std::vector<glm::vec3> y = bend_static(thick, p, &mass);
  EXPECT_NEAR(-y.back().y, expected / 16, 0.05 * expected / 16);
}

TEST(Wood, OneStepOfThePassIsTheStaticBend) {
  const tree_skeleton t0 = cantilever(20, 2, 0.02f);
  tree_skeleton t = t0;
  grow_report rep;
  apply_wood(t, beam_wood(), &rep);
  EXPECT_EQ(rep.message, "");
  const std::vector<glm::vec3> x = bend_static(t0, beam_wood());
  for (size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(glm::length(t.position[i] - x[i]), 0, 1e-6f);
  // Internode lengths are kept: bending turns, it does not stretch.
  for (size_t i = 1; i < t.size(); ++i)
    EXPECT_NEAR(glm::length(t.position[i] - t.position[i - 1]), 0.1f, 1e-5f);
}

TEST(Wood, OffIsExactlyTheGeneratorsTree) {
  tree_spec spec;
  spec.params = self_organizing_params{};
  std::get<self_organizing_params>(spec.params).steps = 10;
  const tree_skeleton a = grow(spec, {});
  const tree_skeleton b = grow_self_organizing(std::get<self_organizing_params>(spec.params), {});
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(0, std::memcmp(a.position.data(), b.position.data(), a.size() * sizeof(glm::vec3)));
  EXPECT_EQ(a.wood, nullptr);
}

TEST(Wood, AGrowingBranchSagsMoreAsItGetsHeavier) {
  // One internode a step; the history bends each step by the new load over today's stiffness.
  tree_skeleton t = cantilever(12, 3, 0.03f, true);
  wood_params p = beam_wood();
  p.gravity = 3;
  apply_wood(t, p);
  ASSERT_NE(t.wood, nullptr);
  float last_sag = 0;
  for (int s = 2; s <= t.steps; ++s) {
    const std::vector<glm::vec3> x = positions_at_step(t, s);
    const float sag = -x[size_t(s)].y;   // the tip at step s is node s
    EXPECT_GT(sag, last_sag) << "step " << s;
    last_sag = sag;
  }
  const std::vector<glm::vec3> final_x = positions_at_step(t, t.steps);
  EXPECT_EQ(0, std::memcmp(final_x.data(), t.position.data(), t.size() * sizeof(glm::vec3)));
  // The permanent set: load that came while the branch was short stays; the sag is at least the
  // elastic sag of the final branch.
  const std::vector<glm::vec3> elastic = bend_static(cantilever(12, 3, 0.03f), p);
  EXPECT_GE(-t.position.back().y, -elastic.back().y * 0.99f);
}

TEST(Wood, ReactionWoodTurnsTheTipBackUp) {
  tree_skeleton base = cantilever(12, 3, 0.02f, true);
  wood_params p = beam_wood();
  p.gravity = 3;
  tree_skeleton sagging = base;
  apply_wood(sagging, p);
  p.recovery = 0.5f;
  p.recovery_age = 2;
  tree_skeleton recovering = base;
  apply_wood(recovering, p);
  auto slope = [](const tree_skeleton& t, size_t i) {
    const glm::vec3 d = glm::normalize(t.position[i] - t.position[i - 1]);
    return d.y;
  };
  const size_t tip = base.size() - 1, mid = base.size() / 2;
  // Without reaction wood a cantilever is steepest at its tip; with it, the tip turns up.
  EXPECT_LT(slope(sagging, tip), slope(sagging, mid));
  EXPECT_GT(slope(recovering, tip), slope(recovering, mid));
  EXPECT_GT(recovering.position.back().y, sagging.position.back().y);
}

TEST(Wood, PipeModelHoldsAfterBending) {
  tree_spec spec;
  spec.params = self_organizing_params{};
  std::get<self_organizing_params>(spec.params).steps = 14;
  spec.wood.gravity = 2;
  const tree_skeleton t = grow(spec, {});
  ASSERT_NE(t.wood, nullptr);
  ASSERT_GT(t.pipe_exponent, 0);
  std::vector<float> r;
  compute_pipe_radii(t.parent, t.born, t.died, t.steps, t.pipe_exponent, t.pipe_tip_radius, r);
  ASSERT_EQ(r.size(), t.radius.size());
  for (size_t i = 0; i < r.size(); ++i) ASSERT_EQ(r[i], t.radius[i]) << i;
  EXPECT_EQ(validate_skeleton(t), "");
  // And it did bend: some node moved by a centimetre or more.
  float moved = 0;
  for (size_t i = 0; i < t.size(); ++i) moved = std::max(moved, glm::length(t.position[i] - t.wood->rest[i]));
  EXPECT_GT(moved, 0.01f);
}

TEST(Wood, NoLeanWithSymmetricSettings) {
  // The self-organizing lean test (20 seeds, no tropism) with the tree bending under its weight.
  tree_spec spec;
  self_organizing_params so;
  so.steps = 12;
  so.w_tropism = 0;
  so.w_optimal = 1;
  spec.params = so;
  spec.wood.gravity = 2;
  glm::dvec2 com(0);
  double height = 0;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    spec.seed = seed;
    const tree_skeleton t = grow(spec, {});
    glm::dvec2 c(0);
    size_t n = 0;
    float top = 0;
    for (size_t i = 0; i < t.size(); ++i) {
      top = std::max(top, t.position[i].y);
      if (t.order[i] == 0) continue;
      c += glm::dvec2(t.position[i].x, t.position[i].z);
      ++n;
    }
    ASSERT_GT(n, 0u);
    com += c / double(n) / 20.0;
    height += top / 20.0;
  }
  EXPECT_LT(glm::length(com), 0.05 * height);
}

TEST(Wood, ExtremesAreClampedNeverNaN) {
  for (int g = 0; g < generator_count; ++g) {
    tree_spec spec;
    spec.params = default_params(g);
    if (auto* so = std::get_if<self_organizing_params>(&spec.params)) so->steps = 12;
    if (auto* sc = std::get_if<space_colonization_params>(&spec.params)) sc->steps = 40;
    spec.wood.gravity = 10;
    spec.wood.density = 1500;
    spec.wood.modulus = 0.5f;
    spec.wood.leaf_mass = 50;
    spec.wood.leaves_per_metre = 500;
    grow_report rep;
    const tree_skeleton t = grow(spec, {}, &rep);
    EXPECT_EQ(validate_skeleton(t), "") << generator_names[g];
    EXPECT_NE(rep.message.find("maximum bend"), std::string::npos) << generator_names[g] << ": " << rep.message;
    // Zero density and modulus are outside the ranges: clamped and said.
    spec.wood.density = 0;
    spec.wood.modulus = 0;
    grow_report rep0;
    const tree_skeleton z = grow(spec, {}, &rep0);
    EXPECT_EQ(validate_skeleton(z), "") << generator_names[g];
    EXPECT_NE(rep0.message.find("wood_density, youngs_modulus out of range"), std::string::npos) << rep0.message;
    for (int s = 0; s <= z.steps; s += std::max(1, z.steps / 4))
      EXPECT_TRUE(all_finite(positions_at_step(z, s))) << generator_names[g] << " step " << s;
  }
  // NaN parameters straight into the pass.
  tree_skeleton t = cantilever(10, 1, 0.01f);
  wood_params p = beam_wood();
  p.modulus = std::nanf("");
  p.density = std::numeric_limits<float>::infinity();
  grow_report rep;
  apply_wood(t, p, &rep);
  EXPECT_TRUE(all_finite(t.position));
  EXPECT_NE(rep.message.find("clamped"), std::string::npos);
}

TEST(Wood, DeterministicAndScrubbingReplaysTheSameBend) {
  tree_spec spec;
  self_organizing_params so;
  so.steps = 14;
  spec.params = so;
  spec.wood.gravity = 2;
  spec.wood.recovery = 0.3f;
  const tree_skeleton a = grow(spec, {});
  const tree_skeleton b = grow(spec, {});
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(0, std::memcmp(a.position.data(), b.position.data(), a.size() * sizeof(glm::vec3)));
  // The export of an earlier step (skeleton_at_step) has the bend the viewport shows at that step.
  const int s = a.steps / 2;
  const std::vector<glm::vec3> x = positions_at_step(a, s);
  const tree_skeleton at = skeleton_at_step(a, s);
  size_t k = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (!a.alive(i, s)) continue;
    ASSERT_LT(k, at.size());
    EXPECT_EQ(at.position[k], x[i]) << i;
    ++k;
  }
  EXPECT_EQ(k, at.size());
  // Step s is not the final bend: the tree sagged further after it.
  double before = 0, after = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (a.alive(i, s)) before += x[i].y - a.wood->rest[i].y, after += a.position[i].y - a.wood->rest[i].y;
  EXPECT_LT(after, before);
}

TEST(Wood, PresetsWithoutAWoodSectionLoadWithThePassOff) {
  preset p;
  load_result r = load_preset_json(R"({"sylva_preset": 1, "generator": "self_organizing"})", p);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_EQ(p.spec.wood, wood_params{});
  EXPECT_EQ(p.spec.wood.gravity, 0);
  r = load_preset_json(R"({"sylva_preset": 1, "generator": "lsystem", "wood": {"gravity": 1, "youngs_modulus": 0}})", p);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(p.spec.wood.gravity, 1);
  EXPECT_EQ(p.spec.wood.modulus, 0.5f);  // clamped to its minimum, with a warning
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_EQ(set_preset_param(p, "recovery=0.4"), "");
  EXPECT_EQ(set_preset_param(p, "wood.wood_density=700"), "");
  EXPECT_EQ(p.spec.wood.recovery, 0.4f);
  EXPECT_EQ(p.spec.wood.density, 700);
  preset back;
  ASSERT_TRUE(load_preset_json(save_preset_json(p), back).ok);
  EXPECT_EQ(back, p);
}
