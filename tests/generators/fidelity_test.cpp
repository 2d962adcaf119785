// Issue 16 "Fidelity": the seed presets use exactly their seeds' mechanisms, the seed options do
// what the seeds print, and --set reaches a text L-system's #define constants.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "generators/guiding_vectors.h"
#include "generators/lsystem_engine.h"
#include "generators/self_organizing.h"
#include "generators/tree_spec.h"
#include "render/io/preset.h"
#include "tests/fixtures.h"

using namespace sylva;

namespace {

// A seed preset, which must load without a warning.
preset load(const std::string& name) {
  std::vector<std::string> warnings;
  preset p = sylva_test::shipped_preset(name, &warnings);
  EXPECT_TRUE(warnings.empty()) << name << ": " << (warnings.empty() ? "" : warnings.front());
  return p;
}

bool same_tree(const tree_skeleton& a, const tree_skeleton& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a.parent[i] != b.parent[i] || a.position[i] != b.position[i] || a.died[i] != b.died[i]) return false;
  return true;
}

}  // namespace

// Seed 000 has no light conversion, no upkeep and no shedding, and its terminal bud always ranks
// first; its priority model sorts by the average light of what a node supports.
TEST(Fidelity, Seed000PresetsUseOnlySeed000Mechanisms) {
  for (const char* name : {"self_organizing_seed000_priority", "self_organizing_seed000_planar"}) {
    const preset pr = load(name);
    const auto& p = std::get<self_organizing_params>(pr.spec.params);
    EXPECT_EQ(p.sigma, 0) << name;
    EXPECT_EQ(p.bm, 0) << name;
    EXPECT_EQ(p.shed_min_buds, 0) << name;
    EXPECT_GE(p.terminal_priority_steps, p.steps) << name;
    EXPECT_EQ(p.allocation, so_allocation::priority) << name;
    EXPECT_EQ(p.priority_rank, so_priority_rank::average) << name;
    EXPECT_EQ(p.environment, so_environment::shadow) << name;
    EXPECT_EQ(p.shadow_a, 0.2f);
    EXPECT_EQ(p.shadow_b, 2.0f);
    EXPECT_EQ(p.q_max, 4);
    EXPECT_EQ(p.w_min, 0.006f);
    const tree_skeleton t = grow(pr.spec, {});
    EXPECT_GT(t.size(), 500u) << name;
    for (size_t i = 0; i < t.size(); ++i) ASSERT_EQ(t.died[i], never_died) << name << ": nothing is shed";
    EXPECT_NE(pr.description.find("average"), std::string::npos) << name;
    EXPECT_NE(pr.description.find("No light conversion"), std::string::npos) << name;
  }
}

TEST(Fidelity, PriorityRankAverageAndSummedDiffer) {
  tree_spec s = load("self_organizing_seed000_priority").spec;
  const tree_skeleton avg = grow(s, {});
  std::get<self_organizing_params>(s.params).priority_rank = so_priority_rank::summed;
  const tree_skeleton sum = grow(s, {});
  EXPECT_FALSE(same_tree(avg, sum));
  EXPECT_EQ(validate_skeleton(avg), "");
  EXPECT_EQ(validate_skeleton(sum), "");
}

// Seed 001 eq. 2 as printed, BM·r^BE/r₀ (r in metres), is the relative form with BM scaled by
// r₀^(BE−1): both grow the identical tree.
TEST(Fidelity, Seed001UpkeepFormIsTheRelativeFormScaled) {
  self_organizing_params a;
  a.steps = 14;
  a.bm = 0.3f;
  a.be = 1.6f;
  a.tip_radius = 0.01f;
  a.upkeep_form = so_upkeep_form::seed001;
  self_organizing_params b = a;
  b.upkeep_form = so_upkeep_form::relative;
  b.bm = a.bm * std::pow(a.tip_radius, a.be - 1);
  const tree_skeleton ta = grow_self_organizing(a, {}), tb = grow_self_organizing(b, {});
  EXPECT_GT(ta.size(), 100u);
  EXPECT_TRUE(same_tree(ta, tb));
  b.bm = a.bm;  // unscaled: a different (more heavily taxed) tree
  EXPECT_FALSE(same_tree(ta, grow_self_organizing(b, {})));
}

// Seed 001 counts a node's light once when it has either bud. After one step the seedling's shoot
// is the same either way, and only its tip node holds two buds (a terminal and a lateral); so in
// step 2 the root's flow differs by exactly that node's light l, with 0 < l ≤ C + a.
TEST(Fidelity, Seed001PerNodeLightCountsANodeOnce) {
  self_organizing_params p;
  p.steps = 2;
  p.bm = 0;
  p.shed_min_buds = 0;
  p.sigma = 0;
  growth_debug per_bud, per_node;
  grow_options o;
  o.steps = 2;
  const tree_skeleton a = grow_self_organizing(p, o, nullptr, &per_bud);
  p.light_count = so_light_count::per_node;
  const tree_skeleton b = grow_self_organizing(p, o, nullptr, &per_node);
  ASSERT_FALSE(per_bud.node_flow.empty());
  ASSERT_FALSE(per_node.node_flow.empty());
  int step1 = 0;
  for (size_t i = 0; i < a.size(); ++i) step1 += a.born[i] <= 1;
  ASSERT_GT(step1, 2);
  for (size_t i = 0; i < size_t(step1); ++i) ASSERT_EQ(a.position[i], b.position[i]);
  const float l = per_bud.node_flow[0] - per_node.node_flow[0];
  EXPECT_GT(l, 0);
  EXPECT_LE(l, p.full_exposure + p.shadow_a + 1e-5f);
  EXPECT_EQ(validate_skeleton(b), "");
}

TEST(Fidelity, Seed001PresetsFollowTheSeed) {
  for (const char* name : {"self_organizing_seed001_fig2"}) {
    const preset pr = load(name);
    const auto& p = std::get<self_organizing_params>(pr.spec.params);
    EXPECT_EQ(p.internode_length, 0.5f) << name;  // seed 001 §5: a 50 cm metamer
    EXPECT_EQ(p.upkeep_form, so_upkeep_form::seed001) << name;
    EXPECT_EQ(p.light_count, so_light_count::per_node) << name;
    EXPECT_EQ(p.allocation, so_allocation::borchert_honda) << name;
    EXPECT_EQ(p.alpha, 3.0f);  // Table 2, fig. 2
    EXPECT_EQ(p.lambda, 0.52f);
    EXPECT_EQ(p.sigma, 0.5f);
    EXPECT_EQ(p.w_tropism, 0.1f);
    EXPECT_EQ(p.bm, 0.03f);
    EXPECT_EQ(p.be, 1.3f);
    EXPECT_EQ(p.shed_min_buds, 35);
    EXPECT_EQ(p.shadow_a, 0.1f);
    EXPECT_EQ(p.shadow_b, 1.5f);
    EXPECT_EQ(p.w_default, 0.8f);  // eq. 6
    EXPECT_EQ(p.w_optimal, 0.2f);
  }
  EXPECT_EQ(std::get<self_organizing_params>(load("self_organizing_seed001_fig2").spec.params).steps, 35);
}

TEST(Fidelity, Seed004SnowflakeIsTheD0LSystemOfItsFig4) {
  const preset pr = load("lsystem_seed004_snowflake");
  const auto& p = std::get<lsystem_params>(pr.spec.params);
  ASSERT_EQ(p.mode, lsystem_mode::text);
  // Derivation n has 3·4^n segments, each of length 4/3^n... of side 1/3^n: 3·4^4 = 768 after four.
  grow_report rep;
  const tree_skeleton t = grow(pr.spec, {}, &rep);
  EXPECT_FALSE(rep.error) << rep.message;
  EXPECT_EQ(t.size(), 1u + 768u);
  // A closed curve: the last point is back at the start, and every segment has length 1/81.
  EXPECT_LT(glm::length(t.position.back() - t.position.front()), 1e-4f);
  for (size_t i = 1; i < t.size(); ++i)
    ASSERT_NEAR(glm::length(t.position[i] - t.position[size_t(t.parent[i])]), 1.0f / 81.0f, 1e-5f);
  // Flat: the turns are all about U, so the curve stays in the z = 0 plane.
  for (const glm::vec3& q : t.position) ASSERT_NEAR(q.z, 0, 1e-5f);
}

TEST(Fidelity, Seed002PresetSaysItsValuesAreChosen) {
  const preset pr = load("guiding_vectors_seed002");
  EXPECT_NE(pr.description.find("chosen"), std::string::npos);
  EXPECT_EQ(std::get<guiding_vectors_params>(pr.spec.params).search_corridor, 2.0f);
}

// The 2h corridor is a parameter; 0 is the exact, unbounded search. Both grow a valid tree with
// every endpoint reached, and the unbounded search's paths are no costlier, so the trees differ
// little in size.
TEST(Fidelity, GuidingVectorsCorridorAndExactSearch) {
  guiding_vectors_params p;
  p.spacing = 0.3f;
  grow_report ra, rb;
  const tree_skeleton bounded = grow_guiding_vectors(p, {}, &ra);
  p.search_corridor = 0;
  const tree_skeleton exact = grow_guiding_vectors(p, {}, &rb);
  EXPECT_FALSE(ra.error) << ra.message;
  EXPECT_FALSE(rb.error) << rb.message;
  EXPECT_EQ(validate_skeleton(bounded), "");
  EXPECT_EQ(validate_skeleton(exact), "");
  EXPECT_GT(exact.size(), 50u);
  EXPECT_NEAR(double(exact.size()), double(bounded.size()), 0.5 * double(bounded.size()));
}

TEST(Fidelity, SetReachesDefineConstants) {
  preset pr = load("lsystem_seed004_binary_tree");
  const tree_skeleton before = grow(pr.spec, {});
  ASSERT_EQ(set_preset_param(pr, "define.delta=30"), "");
  const auto& p = std::get<lsystem_params>(pr.spec.params);
  ASSERT_EQ(lsystem_constants(p.source).at(0).value, 30.0f);
  EXPECT_NE(p.source.find("#define delta 30 // [0,90]"), std::string::npos) << p.source;  // comment kept
  const tree_skeleton after = grow(pr.spec, {});
  EXPECT_EQ(after.size(), before.size());
  EXPECT_FALSE(same_tree(after, before));
  // Out of the constant's range, unknown names and non-numbers are refused with the reason.
  EXPECT_NE(set_preset_param(pr, "define.delta=300").find("outside [0, 90]"), std::string::npos);
  EXPECT_NE(set_preset_param(pr, "define.nope=1").find("it defines delta"), std::string::npos);
  EXPECT_NE(set_preset_param(pr, "define.delta=abc").find("not a number"), std::string::npos);
  EXPECT_NE(set_preset_param(pr, "define.delta=nan").find("not a number"), std::string::npos);
  // Honda mode has no #define constants to reach.
  preset honda = load("lsystem_honda_a");
  EXPECT_NE(set_preset_param(honda, "define.delta=30").find("text-mode"), std::string::npos);
  // Sweeps expand over a constant like over any number, checked whole.
  std::vector<std::string> values;
  ASSERT_EQ(expand_param_sweep(pr, "define.delta=10:40:4", values), "");
  EXPECT_EQ(values, (std::vector<std::string>{"define.delta=10", "define.delta=20", "define.delta=30", "define.delta=40"}));
  values.clear();
  EXPECT_NE(expand_param_sweep(pr, "define.delta=10:100:4", values), "");
  EXPECT_TRUE(values.empty());
}
