// Growth phases: keyframes leave the tree before their step untouched, bit for bit,
// for every generator and every keyable parameter; bad keyframes are refused with a message.
#include <gtest/gtest.h>

#include <cstring>
#include <set>
#include <string>

#include "tests/generators/generator_cases.h"
#include "generators/keyframes.h"
#include "generators/tree_spec.h"
#include "tests/tree_compare.h"

using namespace sylva;

namespace {

// A value of the same type as `base`, inside [min, max] and different from it where the range allows.
template <class T>
glm::vec3 other_value(const T& base, const param_info& info) {
  if constexpr (std::is_same_v<T, bool>) return glm::vec3(base ? 0.0f : 1.0f, 0, 0);
  else if constexpr (std::is_enum_v<T>) return glm::vec3(float((int(base) + 1) % option_count(info)), 0, 0);
  else if constexpr (std::is_same_v<T, int>)
    return glm::vec3(float(base < int(info.max) ? base + (int(info.max) - base + 1) / 2 : base - 1), 0, 0);
  else if constexpr (std::is_same_v<T, float>)
    return glm::vec3(base < info.max ? base + 0.5f * (info.max - base) : 0.5f * (info.min + base), 0, 0);
  else return base + 0.5f * (glm::vec3(info.max) - base);
}

// Calls f(key, value) for every keyable parameter of the spec's generator with a value that differs from the base.
template <class F>
void for_each_keyable(const tree_spec& s, F&& f) {
  std::visit(
      [&](const auto& p) {
        visit_params(p, [&](const auto& value, const param_info& info) {
          using T = std::remove_cvref_t<decltype(value)>;
          if constexpr (keyable_type<T>)
            if (keyframe_refusal(s, info.key).empty()) f(std::string(info.key), other_value(value, info));
        });
      },
      s.params);
}

using sylva_test::case_t;
using sylva_test::cases;

}  // namespace

TEST(Keyframes, RefusedKeysNameParametersOfTheirGenerator) {
  for (int g = 0; g < generator_count; ++g) {
    std::set<std::string> keys;
    std::visit([&](const auto& p) { visit_params(p, [&](const auto&, const param_info& i) { keys.insert(i.key); }); },
               default_params(g));
    for (const std::string& k : keyframe_refused_keys(g)) EXPECT_TRUE(keys.count(k)) << generator_names[g] << "." << k;
  }
}

// The heart of the feature: every keyable parameter, keyed at a middle step k, leaves the tree up to
// k − 1 exactly as it grows without the keyframe.
TEST(Keyframes, TreeBeforeTheKeyedStepIsBitIdenticalForEveryGeneratorAndKey) {
  for (const case_t& c : cases) {
    const tree_spec base = small_spec(c.generator, c.markers);
    const tree_skeleton plain = grow(base, {});
    const int k = std::max(2, plain.steps / 2);
    int keys = 0, changed = 0;
    for_each_keyable(base, [&](const std::string& key, const glm::vec3& value) {
      tree_spec s = base;
      ASSERT_EQ(set_keyframe(s, {k, key, value}), "") << c.name << "." << key;
      grow_report rep;
      const tree_skeleton keyed = grow(s, {}, &rep);
      EXPECT_FALSE(rep.error) << c.name << "." << key << ": " << rep.message;
      expect_same_up_to(plain, keyed, k - 1, std::string(c.name) + " keyed " + key + "@" + std::to_string(k));
      ++keys;
      changed += !same_tree(plain, keyed);
    });
    EXPECT_GE(keys, 3) << c.name;
    EXPECT_GE(changed, 1) << c.name << ": no keyframe changed the tree after its step";
  }
}

// A keyframe at step 1 is the same as changing the parameter itself: so the generators recompute
// everything they derive from a keyed value. (Two exceptions are used before step 1 as well: space
// colonization's segment length fixes the trunk's internode count, and the self-organizing
// occupancy radius clears the markers around the seedling.)
TEST(Keyframes, KeyAtStepOneEqualsChangingTheParameter) {
  for (const case_t& c : cases) {
    const tree_spec base = small_spec(c.generator, c.markers);
    for_each_keyable(base, [&](const std::string& key, const glm::vec3& value) {
      if (c.generator == 1 && key == "segment_length") return;
      if (c.generator == 0 && key == "occupancy_radius") return;   // also clears the markers at the root, before step 1
      tree_spec keyed = base;
      ASSERT_EQ(set_keyframe(keyed, {1, key, value}), "");
      tree_spec changed = base;
      std::visit([&](auto& p) { apply_keyframes(p, &keyed.keyframes, 1); }, changed.params);
      ASSERT_NE(changed, base) << key;
      EXPECT_TRUE(same_tree(grow(keyed, {}), grow(changed, {}))) << c.name << "." << key;
    });
  }
}

TEST(Keyframes, ChosenKeysChangeTheTreeAfterTheirStep) {
  const struct { int g; const char* key; glm::vec3 v; } picks[] = {
      {0, "lambda", glm::vec3(0.3f, 0, 0)}, {1, "tropism_weight", glm::vec3(0.6f, 0, 0)},
      {2, "source_fraction", glm::vec3(0.1f, 0, 0)}, {3, "alpha1", glm::vec3(60, 0, 0)}};
  for (const auto& pk : picks) {
    tree_spec s = small_spec(pk.g);
    const tree_skeleton plain = grow(s, {});
    const int k = std::max(2, plain.steps / 2);
    ASSERT_EQ(set_keyframe(s, {k, pk.key, pk.v}), "");
    const tree_skeleton keyed = grow(s, {});
    EXPECT_FALSE(same_tree(plain, keyed)) << pk.key;
    expect_same_up_to(plain, keyed, k - 1, pk.key);
  }
}

TEST(Keyframes, ParamsAtStepApplyKeysInStepOrder) {
  tree_spec s = small_spec(0);
  ASSERT_EQ(set_keyframe(s, {6, "lambda", glm::vec3(0.7f, 0, 0)}), "");
  ASSERT_EQ(set_keyframe(s, {3, "lambda", glm::vec3(0.6f, 0, 0)}), "");
  ASSERT_EQ(set_keyframe(s, {3, "alpha", glm::vec3(3, 0, 0)}), "");
  const auto& base = std::get<self_organizing_params>(s.params);
  EXPECT_EQ(params_at_step(base, s.keyframes, 2).lambda, base.lambda);
  EXPECT_EQ(params_at_step(base, s.keyframes, 3).lambda, 0.6f);
  EXPECT_EQ(params_at_step(base, s.keyframes, 5).alpha, 3.0f);
  EXPECT_EQ(params_at_step(base, s.keyframes, 6).lambda, 0.7f);
  EXPECT_EQ(params_at_step(base, s.keyframes, 10).lambda, 0.7f);
  // Sorted by step, then key.
  ASSERT_EQ(s.keyframes.size(), 3u);
  EXPECT_EQ(s.keyframes[0].key, "alpha");
  EXPECT_EQ(s.keyframes[1].key, "lambda");
  EXPECT_EQ(s.keyframes[2].step, 6);
  // Setting the same key at the same step again replaces its value.
  ASSERT_EQ(set_keyframe(s, {6, "lambda", glm::vec3(0.8f, 0, 0)}), "");
  EXPECT_EQ(s.keyframes.size(), 3u);
  EXPECT_EQ(s.keyframes[2].value.x, 0.8f);
}

// Lowering the steps below a keyframe keeps it, inactive: the tree grows as without it (and says
// so), and raising the steps again applies it. The loader and the editor share this rule, so a
// document with such a keyframe saves and reopens.
TEST(Keyframes, AKeyframePastTheLastStepIsKeptInactiveAndAppliesWhenTheStepsGrowAgain) {
  tree_spec s = small_spec(0);
  auto& p = std::get<self_organizing_params>(s.params);
  const int last = p.steps;
  ASSERT_EQ(set_keyframe(s, {last + 3, "lambda", glm::vec3(0.3f, 0, 0)}), "");
  EXPECT_FALSE(step_active(s, last + 3));
  EXPECT_EQ(inactive_edits(s), 1);
  tree_spec plain = s;
  plain.keyframes.clear();
  grow_report rep;
  const tree_skeleton a = grow(s, {}, &rep), b = grow(plain, {});
  EXPECT_EQ(a.position, b.position);
  EXPECT_NE(rep.message.find("past the last step (" + std::to_string(last) + ")"), std::string::npos) << rep.message;
  p.steps = last + 5;
  plain.params = s.params;
  EXPECT_TRUE(step_active(s, last + 3));
  EXPECT_EQ(inactive_edits(s), 0);
  grow_report rep2;
  const tree_skeleton c = grow(s, {}, &rep2), d = grow(plain, {});
  EXPECT_TRUE(rep2.message.empty()) << rep2.message;
  EXPECT_NE(c.position, d.position);   // lambda 0.3 from step last+3 on changes the tree
}

TEST(Keyframes, BadKeyframesAreRefusedAndLeaveTheSpecAsItWas) {
  tree_spec s = small_spec(0);
  ASSERT_EQ(set_keyframe(s, {4, "lambda", glm::vec3(0.6f, 0, 0)}), "");
  const tree_spec before = s;
  auto refused = [&](const keyframe& k, const char* words) {
    const std::string e = set_keyframe(s, k);
    EXPECT_NE(e.find(words), std::string::npos) << e;
    EXPECT_EQ(s, before);
  };
  refused({201, "lambda", glm::vec3(0.5f, 0, 0)}, "beyond the most steps a growth can have (200)");
  refused({0, "lambda", glm::vec3(0.5f, 0, 0)}, "steps start at 1");
  refused({4, "no_such_key", glm::vec3(0)}, "not a parameter of self_organizing");
  refused({4, "voxel_size", glm::vec3(2, 0, 0)}, "cannot change from a step on");
  refused({4, "positions", glm::vec3(0)}, "cannot be keyed");
  refused({4, "lambda", glm::vec3(1.5f, 0, 0)}, "outside the parameter's range");
  refused({4, "lambda", glm::vec3(NAN, 0, 0)}, "outside the parameter's range");
  refused({4, "shed_min_buds", glm::vec3(2.5f, 0, 0)}, "outside");
  // Two values for one key at one step contradict each other.
  tree_spec twice = s;
  twice.keyframes.push_back({4, "lambda", glm::vec3(0.7f, 0, 0)});
  EXPECT_NE(check_keyframes(twice).find("already keyed at that step"), std::string::npos);
  // grow() never applies a list that fails its checks, and says so.
  grow_report rep;
  const tree_skeleton t = grow(twice, {}, &rep);
  EXPECT_NE(rep.message.find("keyframes ignored"), std::string::npos);
  tree_spec none = s;
  none.keyframes.clear();
  EXPECT_TRUE(same_tree(t, grow(none, {})));
}

TEST(Keyframes, TextLSystemsAndSchedulesSayWhyTheyCannotBeKeyed) {
  tree_spec text;
  lsystem_params l;
  l.mode = lsystem_mode::text;
  text.params = l;
  EXPECT_NE(keyframe_refusal(text, "alpha1").find("text L-systems"), std::string::npos);
  EXPECT_NE(std::string(keyframe_step_meaning(text)).find("not available"), std::string::npos);
  const tree_spec gv = small_spec(2);
  EXPECT_NE(keyframe_refusal(gv, "step_t").find("per-step schedule"), std::string::npos);
  EXPECT_EQ(keyframe_refusal(gv, "t_end"), "");
}
