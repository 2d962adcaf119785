// Every published parameter range is usable : from each generator's default
// preset, each numeric parameter is set to its min and then its max, one at a time, and the tree
// must grow (more than the root), with finite positions and radii, and no crash.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "generators/tree_spec.h"

using namespace sylva;

namespace {

// Node and module caps small enough that a walk of about 250 growths stays fast; the walked
// parameter itself is never overridden.
template <class P>
void make_small(P& p, const std::string& walked) {
  if (walked != "node_cap") p.node_cap = 3000;
  if constexpr (std::is_same_v<P, space_colonization_params>) {
    if (walked != "points") p.points = std::min(p.points, 3000);
  } else if constexpr (std::is_same_v<P, lsystem_params>) {
    if (walked != "module_cap") p.module_cap = 20000;
    if (walked != "derivations") p.derivations = std::min(p.derivations, 8);
  } else if constexpr (std::is_same_v<P, guiding_vectors_params>) {
    if (walked != "steps") p.steps = std::min(p.steps, 3);
  } else if constexpr (std::is_same_v<P, self_organizing_params>) {
    if (walked != "steps") p.steps = std::min(p.steps, 12);
  }
}

// Sets the value to the range's end `hi` (false: min). Returns false for non-numeric types.
template <class T>
bool set_to_end(T& v, const param_info& info, bool hi) {
  const float x = hi ? info.max : info.min;
  if constexpr (std::is_same_v<T, float>) {
    v = x;
  } else if constexpr (std::is_same_v<T, int>) {
    v = int(x);
  } else if constexpr (std::is_same_v<T, glm::vec3>) {
    v = glm::vec3(x);
  } else if constexpr (std::is_same_v<T, std::vector<float>>) {
    for (float& e : v) e = x;
  } else {
    return false;
  }
  return true;
}

template <class P>
void walk(const P& defaults, const char* generator) {
  int index = 0, count = 0;
  visit_params(defaults, [&](const auto&, const param_info&) { ++count; });
  for (int k = 0; k < count; ++k)
    for (bool hi : {false, true}) {
      P p = defaults;
      std::string key;
      bool numeric = false;
      index = 0;
      visit_params(p, [&](auto& value, const param_info& info) {
        if (index++ != k) return;
        key = info.key;
        numeric = set_to_end(value, info, hi);
      });
      if (!numeric) continue;
      make_small(p, key);
      const std::string what = std::string(generator) + "." + key + (hi ? " = max" : " = min");
      SCOPED_TRACE(what);
      grow_report rep;
      const auto t0 = std::chrono::steady_clock::now();
      const tree_skeleton t = grow(tree_spec{p, 1}, grow_options{}, &rep);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      // Either a tree grows, or the report says why not. Zero steps or derivations is the
      // seedling by definition: the root alone, without a message.
      const bool seedling = !hi && (key == "steps" || key == "derivations");
      const size_t roots = size_t(std::max(1, t.tree_count));
      EXPECT_TRUE(t.size() > roots || !rep.message.empty() || seedling) << "a bare root and no message";
      EXPECT_GE(t.size(), 1u);
      if (t.size() <= roots && !seedling) std::printf("  %s: %s\n", what.c_str(), rep.message.c_str());
      // No wall-clock assertion (a loaded machine makes any limit flaky): ctest's 300 s timeout
      // catches a hang, and a slow extreme is printed so it shows in the log.
      if (s > 20.0) std::printf("  %s: %.1f s\n", what.c_str(), s);
      for (size_t i = 0; i < t.size(); ++i) {
        ASSERT_TRUE(std::isfinite(t.position[i].x) && std::isfinite(t.position[i].y) && std::isfinite(t.position[i].z))
            << "node " << i;
        ASSERT_TRUE(std::isfinite(t.radius[i])) << "node " << i;
      }
    }
}

}  // namespace

// The values a hostile walk found failing inside their ranges now grow a tree without an error.
TEST(ParamWalk, FormerlyFailingValuesGrow) {
  auto grows = [](generator_params params, const std::string& what) {
    SCOPED_TRACE(what);
    std::visit([](auto& p) { make_small(p, ""); }, params);
    grow_report rep;
    const tree_skeleton t = grow(tree_spec{params, 1}, grow_options{}, &rep);
    EXPECT_FALSE(rep.error) << rep.message;
    EXPECT_GT(t.size(), 10u) << rep.message;
  };
  guiding_vectors_params gv;
  gv.candidates = 2;  // the new minimum: 1 candidate ends the Poisson-disc front at once
  grows(gv, "candidates");
  gv = {};
  gv.spacing = 0.05f;  // the new minimum (0.01 needs more grid cells than the limit)
  gv.steps = 1;
  grows(gv, "spacing");
  gv = {};
  gv.domain_size = glm::vec3(20);  // the new maximum (100 needs more grid cells than the limit)
  gv.steps = 1;
  grows(gv, "domain_size");
  gv = {};
  gv.volume_outer = 0.01f;  // smaller than the spacing: stands for its nearest vertex
  grows(gv, "volume_outer");
  space_colonization_params sc;
  sc.kill_distance = 50;  // used as 0.9 d_i, with a message
  grows(sc, "kill_distance");
}

TEST(ParamWalk, SelfOrganizing) { walk(self_organizing_params{}, "self_organizing"); }
TEST(ParamWalk, SpaceColonization) { walk(space_colonization_params{}, "space_colonization"); }
TEST(ParamWalk, GuidingVectors) { walk(guiding_vectors_params{}, "guiding_vectors"); }
TEST(ParamWalk, LSystem) { walk(lsystem_params{}, "lsystem"); }
