// What every generator promises, checked once over all four (and both L-system modes): a node cap
// stops growth with a message, the same seed gives the same tree, and hostile parameters give a
// valid tree and a message rather than a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "generators/tree_spec.h"
#include "tests/generators/generator_specs.h"

namespace sylva {
namespace {

constexpr float nan_value = std::numeric_limits<float>::quiet_NaN();

struct generator_case {
  const char* name;
  std::vector<tree_spec> small;          // quick trees, each grown twice with one seed
  bool seed_matters = true;              // another seed gives another tree
  tree_spec capped;                      // grows past its node cap
  size_t cap = 0;
  bool cap_exact = true;                 // stops at exactly `cap` nodes (Honda's model: at most)
  int capped_steps_below = -1;           // the cap is reached before this step (-1: not checked)
  std::optional<tree_spec> bad;          // hostile parameters
};

void PrintTo(const generator_case& c, std::ostream* os) { *os << c.name; }

tree_spec spec_of(generator_params p) {
  tree_spec s;
  s.params = std::move(p);
  return s;
}

using sylva_test::small_guiding_vectors;
using sylva_test::text_params;

generator_case self_organizing_case() {
  generator_case c{"self_organizing", {}, true, {}, 1000, true, 60, std::nullopt};
  for (so_allocation a : {so_allocation::borchert_honda, so_allocation::priority}) {
    self_organizing_params p;
    p.steps = 12;
    p.allocation = a;
    c.small.push_back(spec_of(p));
  }
  self_organizing_params cap;
  cap.steps = 60;
  cap.node_cap = 1000;
  c.capped = spec_of(cap);
  self_organizing_params bad;
  bad.steps = 12;
  bad.alpha = nan_value;
  bad.lambda = -3;
  bad.shadow_b = 0;
  bad.voxel_size = 1e9f;
  bad.tropism = glm::vec3(nan_value);
  bad.positions = {glm::vec3(1e30f)};
  bad.placement = so_placement::explicit_positions;
  c.bad = spec_of(bad);
  return c;
}

generator_case space_colonization_case() {
  generator_case c{"space_colonization", {}, true, {}, 1000, true, -1, std::nullopt};
  space_colonization_params p;
  p.points = 1500;
  c.small.push_back(spec_of(p));
  space_colonization_params cap;   // the default tree has over 2,000 nodes
  cap.max_branches = 100000;
  cap.node_cap = 1000;
  c.capped = spec_of(cap);
  space_colonization_params bad;   // an envelope mesh that is not there
  bad.envelope = envelope_shape::mesh;
  bad.envelope_mesh = testing::TempDir() + "generator_suite_no_such_file.obj";
  c.bad = spec_of(bad);
  return c;
}

generator_case guiding_vectors_case() {
  generator_case c{"guiding_vectors", {spec_of(small_guiding_vectors())}, true, {}, 30, true, -1, std::nullopt};
  guiding_vectors_params cap = small_guiding_vectors();
  cap.node_cap = 30;
  c.capped = spec_of(cap);
  guiding_vectors_params bad = small_guiding_vectors();
  bad.spacing = nan_value;
  bad.domain_size = {-1, 2, 3};
  bad.step_endpoints = {};
  bad.step_t = {nan_value};
  c.bad = spec_of(bad);
  return c;
}

generator_case lsystem_text_case() {
  const std::string stochastic = "#angle 25\n#axiom F\nF -> (1) F[+F]F[-F]F\nF -> (1) F[+F]F\nF -> (1) F[-F]F\n";
  generator_case c{"lsystem_text", {spec_of(text_params(stochastic, 4))}, false, {}, 1000, true, -1, std::nullopt};
  lsystem_params cap = text_params("#axiom F\nF -> F[+F]F[-F]F\n", 6);   // 5^6 = 15625 F
  cap.node_cap = 1000;
  c.capped = spec_of(cap);
  c.bad = spec_of(text_params("#axiom F(\nF -> F[+F\n", 3));   // does not parse
  return c;
}

generator_case lsystem_honda_case() {
  lsystem_params p;
  p.phi1 = 137;
  generator_case c{"lsystem_honda", {spec_of(p)}, false, {}, 5000, false, -1, std::nullopt};
  lsystem_params cap;
  cap.derivations = 24;
  cap.node_cap = 5000;
  c.capped = spec_of(cap);
  return c;
}

class GeneratorSuite : public ::testing::TestWithParam<generator_case> {};

TEST_P(GeneratorSuite, NodeCapStopsWithAMessage) {
  const generator_case& c = GetParam();
  grow_report rep;
  const tree_skeleton t = grow(c.capped, {}, &rep);
  EXPECT_TRUE(rep.hit_node_cap);
  EXPECT_EQ(rep.stop, grow_stop::node_cap);
  if (c.cap_exact) {
    EXPECT_EQ(t.size(), c.cap);
  } else {
    EXPECT_LE(t.size(), c.cap);
  }
  EXPECT_NE(rep.message.find("node cap"), std::string::npos) << rep.message;
  if (c.capped_steps_below >= 0) {
    EXPECT_LT(t.steps, c.capped_steps_below);
  }
  EXPECT_EQ(validate_skeleton(t), "");
}

TEST_P(GeneratorSuite, DeterministicPerSeed) {
  const generator_case& c = GetParam();
  for (tree_spec s : c.small) {
    s.seed = 7;
    const tree_skeleton x = grow(s, {}), y = grow(s, {});
    ASSERT_EQ(x.size(), y.size());
    EXPECT_EQ(x.position, y.position);
    EXPECT_EQ(x.parent, y.parent);
    EXPECT_EQ(x.born, y.born);
    EXPECT_EQ(x.died, y.died);
    EXPECT_EQ(x.radius, y.radius);
    ASSERT_EQ(x.leaves.size(), y.leaves.size());
    for (size_t i = 0; i < x.leaves.size(); ++i) EXPECT_EQ(x.leaves[i].position, y.leaves[i].position);
    EXPECT_EQ(validate_skeleton(x), "");
    if (!c.seed_matters) continue;
    s.seed = 8;
    const tree_skeleton z = grow(s, {});
    EXPECT_TRUE(z.size() != x.size() || z.position != x.position);
  }
}

TEST_P(GeneratorSuite, BadInputGivesAValidTreeAndAMessage) {
  const generator_case& c = GetParam();
  if (!c.bad) GTEST_SKIP() << "no hostile parameters for " << c.name;
  grow_report rep;
  const tree_skeleton t = grow(*c.bad, {}, &rep);
  EXPECT_EQ(validate_skeleton(t), "");
  EXPECT_FALSE(rep.message.empty());
}

INSTANTIATE_TEST_SUITE_P(AllGenerators, GeneratorSuite,
                         ::testing::Values(self_organizing_case(), space_colonization_case(), guiding_vectors_case(),
                                           lsystem_text_case(), lsystem_honda_case()),
                         [](const ::testing::TestParamInfo<generator_case>& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace sylva
