// Guiding-vector trees (Xu & Mould 2015): Poisson points, Yao-8 edges, costs, turns, search, tree.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <set>
#include <string>
#include <variant>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "generators/guiding_vectors.h"
#include "generators/tree_spec.h"
#include "render/io/preset.h"
#include "tests/generators/generator_specs.h"

using namespace sylva;

namespace {

std::vector<glm::vec3> poisson(const glm::vec3& lo, const glm::vec3& hi, float r, int k = 20, uint64_t seed = 7) {
  std::vector<glm::vec3> pts;
  EXPECT_TRUE(sample_poisson_disc(lo, hi, lo, r, k, seed, {}, pts));
  return pts;
}

// Nearest point of each octant by exhaustive search (ties to the lower index, as the k-d search).
std::vector<int32_t> brute_yao8(const std::vector<glm::vec3>& p, int32_t v) {
  std::vector<int32_t> best(8, -1);
  std::vector<float> d2(8, INFINITY);
  for (int32_t i = 0; i < int32_t(p.size()); ++i) {
    if (i == v) continue;
    const glm::vec3 d = p[i] - p[v];
    const float dd = glm::dot(d, d);
    const int o = octant_of(p[v], p[i]);
    if (dd < d2[o]) {
      d2[o] = dd;
      best[o] = i;
    }
  }
  return best;
}

// A small tree that grows in a few milliseconds.
guiding_vectors_params small_params() { return sylva_test::small_guiding_vectors(); }

}  // namespace

TEST(GuidingVectors, PoissonPointsAreAtLeastRApart) {
  const glm::vec3 lo(0), hi(2, 2, 2);
  const float r = 0.2f;
  const std::vector<glm::vec3> pts = poisson(lo, hi, r);
  for (size_t i = 0; i < pts.size(); ++i) {
    EXPECT_TRUE(glm::all(glm::greaterThanEqual(pts[i], lo)) && glm::all(glm::lessThanEqual(pts[i], hi)));
    for (size_t j = i + 1; j < pts.size(); ++j) ASSERT_GE(glm::distance(pts[i], pts[j]), r * (1 - 1e-6f));
  }
  // Balls of radius r/2 around the points are disjoint and lie in the box grown by r/2:
  // N ≤ 2.2³ / (4/3·π·0.1³) ≈ 2542. A maximal set would have balls of radius r covering the box:
  // N ≥ 8 / (4/3·π·0.2³) ≈ 239; FIFO dart throwing leaves a few holes, so allow 20% less.
  EXPECT_LE(pts.size(), 2542u);
  EXPECT_GE(pts.size(), 191u);
}

TEST(GuidingVectors, PoissonRefusesBadInput) {
  std::vector<glm::vec3> pts;
  std::string why;
  EXPECT_FALSE(sample_poisson_disc(glm::vec3(0), glm::vec3(1), glm::vec3(0), 0, 10, 1, {}, pts, &why));
  EXPECT_FALSE(why.empty());
  EXPECT_FALSE(sample_poisson_disc(glm::vec3(0), glm::vec3(1000), glm::vec3(0), 0.01f, 10, 1, {}, pts, &why));
  EXPECT_NE(why.find("too large"), std::string::npos);
  EXPECT_TRUE(pts.empty());
}

TEST(GuidingVectors, Yao8EdgesGoToTheNearestPointOfEachOctant) {
  // Uniform random points (empty octants at the faces, uneven gaps) and a Poisson-disc set.
  rng random(3);
  std::vector<glm::vec3> uniform(300);
  for (glm::vec3& q : uniform) q = glm::vec3(random.uniform(), random.uniform(), random.uniform());
  const std::vector<glm::vec3> disc = poisson(glm::vec3(0), glm::vec3(1.5f), 0.2f);
  for (const auto& [pts, spacing] : {std::pair{uniform, 0.0f}, std::pair{uniform, 0.05f}, std::pair{disc, 0.2f}}) {
    gv_graph g = make_gv_graph(pts, spacing);
    ASSERT_EQ(g.point.size(), pts.size());
    for (int32_t v = 0; v < int32_t(g.point.size()); ++v) {
      const int32_t* e = yao8_edges(g, v);
      const std::vector<int32_t> want = brute_yao8(g.point, v);
      int degree = 0;
      for (int o = 0; o < 8; ++o) {
        EXPECT_EQ(e[o], want[o]) << "vertex " << v << " octant " << o;
        if (e[o] >= 0) {
          ++degree;
          EXPECT_NE(e[o], v);
          EXPECT_EQ(octant_of(g.point[v], g.point[e[o]]), o);
        }
      }
      EXPECT_LE(degree, 8);
    }
    // Every vertex asked for its edges got exactly one slot of 8.
    EXPECT_EQ(g.edges.size(), 8 * g.point.size());
  }
}

TEST(GuidingVectors, EdgeCostFollowsTheGuidingVector) {
  // Xu & Mould 2015 §B: 0 along g, l across it, 2l against it.
  const glm::vec3 u(1, 2, 3), v(1, 2, 5);  // l = 2 along +z
  EXPECT_NEAR(gv_edge_cost(u, v, glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
  EXPECT_NEAR(gv_edge_cost(u, v, glm::vec3(0, 1, 0)), 2.0f, 1e-6f);
  EXPECT_NEAR(gv_edge_cost(u, v, glm::vec3(0, 0, -1)), 4.0f, 1e-6f);
  // At 60° the cost is l·(1 − cos 60°) = l/2.
  EXPECT_NEAR(gv_edge_cost(u, v, glm::vec3(0, std::sqrt(3.0f) / 2, 0.5f)), 1.0f, 1e-5f);
}

TEST(GuidingVectors, ConstantTurnAddsUpUntilVertical) {
  const glm::vec3 x(1, 0, 0), edge(0.6f, 0, 0.8f);
  for (float t_deg : {-10.0f, 7.0f}) {
    glm::vec3 g = x;
    const int to_vertical = int(90.0f / std::abs(t_deg));  // 9 hops at 10°, 12 hops at 7°
    for (int m = 1; m <= to_vertical + 3; ++m) {
      g = turn_guiding_vector(g, edge, glm::radians(t_deg));
      EXPECT_NEAR(glm::length(g), 1.0f, 1e-5f);
      EXPECT_NEAR(g.z, 0.0f, 1e-5f);  // the turn stays in the vertical plane of g
      // Angle from the start: m·|t| before the pole, then it rests on the pole.
      const float want = std::min(float(m) * std::abs(t_deg), 90.0f);
      EXPECT_NEAR(glm::degrees(std::acos(std::clamp(glm::dot(g, x), -1.0f, 1.0f))), want, 2e-2f) << "m = " << m;
      // t < 0 turns up (y > 0), t > 0 droops (y < 0).
      EXPECT_EQ(g.y > 0, t_deg < 0);
    }
  }
}

TEST(GuidingVectors, TurnAwayFromThePoleLeansAlongTheEdge) {
  // g = up has no axis up × g; a drooping turn (t > 0) leans toward the edge's direction.
  const glm::vec3 g = turn_guiding_vector(glm::vec3(0, 1, 0), glm::vec3(0, 0.6f, 0.8f), glm::radians(10.0f));
  EXPECT_NEAR(g.x, 0.0f, 1e-6f);
  EXPECT_NEAR(g.y, std::cos(glm::radians(10.0f)), 1e-5f);
  EXPECT_NEAR(g.z, std::sin(glm::radians(10.0f)), 1e-5f);
  // Turning up at the top pole, or along a vertical edge, leaves it as it is.
  EXPECT_EQ(turn_guiding_vector(glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), -0.2f), glm::vec3(0, 1, 0));
  EXPECT_EQ(turn_guiding_vector(glm::vec3(0, 1, 0), glm::vec3(0, 1, 0), 0.2f), glm::vec3(0, 1, 0));
}

TEST(GuidingVectors, DijkstraMatchesBellmanFord) {
  // With t = 0 every guiding vector equals the sources' g0, so edge costs are fixed and a plain
  // Bellman–Ford over all Yao-8 edges gives the exact distances.
  gv_graph g = make_gv_graph(poisson(glm::vec3(0), glm::vec3(1.2f), 0.2f, 20, 11), 0.2f);
  const size_t n = g.point.size();
  ASSERT_GT(n, 40u);
  const glm::vec3 g0 = glm::normalize(glm::vec3(0.3f, 1, 0.2f));
  const std::vector<int32_t> sources{0, int32_t(n / 2)};
  std::vector<int32_t> all(n);
  for (size_t i = 0; i < n; ++i) all[i] = int32_t(i);
  gv_search_state s;
  ASSERT_TRUE(search_gv_paths(g, sources, {g0, g0}, gv_turn_rule{}, all, s, {}));

  std::vector<double> bf(n, INFINITY);
  for (int32_t v : sources) bf[v] = 0;
  for (size_t round = 0; round < n; ++round) {
    bool changed = false;
    for (int32_t u = 0; u < int32_t(n); ++u) {
      if (!std::isfinite(bf[u])) continue;
      const int32_t* e = yao8_edges(g, u);
      for (int o = 0; o < 8; ++o)
        if (e[o] >= 0) {
          const double nd = bf[u] + gv_edge_cost(g.point[u], g.point[e[o]], g0);
          if (nd < bf[e[o]] - 1e-9) {
            bf[e[o]] = nd;
            changed = true;
          }
        }
    }
    if (!changed) break;
  }
  for (size_t v = 0; v < n; ++v) {
    if (!std::isfinite(bf[v])) {  // no Yao-8 edge leads here: Dijkstra must not reach it either
      EXPECT_FALSE(std::isfinite(s.dist[v]));
      continue;
    }
    EXPECT_NEAR(s.dist[v], bf[v], 1e-4 * (1 + bf[v])) << "vertex " << v;
    EXPECT_NEAR(glm::length(s.guide[v] - g0), 0.0f, 1e-5f);
    if (s.parent[v] >= 0) {
      EXPECT_NEAR(s.dist[v], s.dist[s.parent[v]] + gv_edge_cost(g.point[s.parent[v]], g.point[v], g0), 1e-4f);
    }
  }
}

TEST(GuidingVectors, TreeIsValidAndAcyclic) {
  const guiding_vectors_params p = small_params();
  grow_report rep;
  tree_skeleton t = grow_guiding_vectors(p, {}, &rep);
  EXPECT_EQ(validate_skeleton(t), "");
  EXPECT_FALSE(rep.error) << rep.message;
  EXPECT_EQ(t.steps, p.steps);
  ASSERT_GT(t.size(), 20u);
  EXPECT_EQ(t.position[0], glm::vec3(0));  // the first Poisson point is the root, on the ground
  std::set<std::tuple<float, float, float>> seen;
  for (size_t i = 0; i < t.size(); ++i) {
    EXPECT_LT(t.parent[i], int32_t(i));
    EXPECT_EQ(t.parent[i] < 0, i == 0);
    if (i > 0) {
      EXPECT_GE(t.born[i], 1);
      EXPECT_GE(t.born[i], t.born[i - 1]);  // steps append in order
    }
    // Every node is a distinct graph vertex, so the union of paths has no repeated vertex.
    EXPECT_TRUE(seen.insert({t.position[i].x, t.position[i].y, t.position[i].z}).second);
  }
  EXPECT_TRUE(t.leaves.empty());  // the mesher places leaves
  // Pipe model: a tip has the tip radius; the root carries r_tip·(tips)^(1/n).
  size_t tips = 0;
  std::vector<int> children(t.size(), 0);
  for (size_t i = 1; i < t.size(); ++i) ++children[t.parent[i]];
  for (size_t i = 0; i < t.size(); ++i)
    if (children[i] == 0) {
      ++tips;
      EXPECT_NEAR(t.radius[i], p.tip_radius, 1e-6f);
    }
  EXPECT_NEAR(t.radius[0], p.tip_radius * std::pow(float(tips), 1 / p.pipe_exponent), 1e-4f);
}

TEST(GuidingVectors, StepsArePrefixes) {   // determinism per seed: generator_suite_test.cpp
  const guiding_vectors_params p = small_params();
  grow_options o;
  o.seed = 5;
  const tree_skeleton a = grow_guiding_vectors(p, o);
  // Growing 2 steps gives exactly the nodes born by step 2 of the longer growth.
  o.steps = 2;
  const tree_skeleton part = grow_guiding_vectors(p, o);
  size_t alive = 0;
  while (alive < a.size() && a.born[alive] <= 2) ++alive;
  ASSERT_EQ(part.size(), alive);
  EXPECT_EQ(part.steps, 2);
  for (size_t i = 0; i < alive; ++i) {
    EXPECT_EQ(part.position[i], a.position[i]);
    EXPECT_EQ(part.parent[i], a.parent[i]);
  }
}

TEST(GuidingVectors, EmptyVolumeGivesAClearMessage) {
  guiding_vectors_params p = small_params();
  p.volume_offset = {0, 40, 0};  // far above the 4 m domain
  grow_report rep;
  tree_skeleton t = grow_guiding_vectors(p, {}, &rep);
  EXPECT_TRUE(rep.error);
  EXPECT_NE(rep.message.find("volume contains no graph vertex"), std::string::npos) << rep.message;
  EXPECT_EQ(validate_skeleton(t), "");
}

TEST(GuidingVectors, EveryVolumeAndTurnRuleGrows) {
  for (int vol = 0; vol < 4; ++vol)
    for (int mode = 0; mode < 3; ++mode) {
      guiding_vectors_params p = small_params();
      p.volume = gv_volume(vol);
      p.volume_inner = 0.6f;
      p.t_mode = gv_t_mode(mode);
      p.radial_T = 0.5f;
      p.source_fraction = 0.5f;
      grow_report rep;
      growth_debug dbg;
      tree_skeleton t = grow_guiding_vectors(p, {}, &rep, &dbg);
      EXPECT_FALSE(rep.error) << rep.message;
      EXPECT_EQ(validate_skeleton(t), "");
      EXPECT_GT(t.size(), 10u);
      EXPECT_EQ(dbg.lines.size(), 2 * dbg.line_color.size());
      EXPECT_EQ(dbg.points.size(), dbg.point_value.size());
      EXPECT_FALSE(dbg.lines.empty());
    }
}

TEST(GuidingVectors, ParamsAreDeclaredOnceAndInRange) {
  guiding_vectors_params p;
  std::set<std::string> keys;
  visit_params(p, [&](auto&, const param_info& info) { EXPECT_TRUE(keys.insert(info.key).second) << info.key; });
  EXPECT_TRUE(clamp_all_params(p).empty());
  EXPECT_EQ(p, guiding_vectors_params{});
}

TEST(GuidingVectors, PresetsLoadCleanlyAndGrow) {
  for (const char* name : {"default", "seed002", "fig7_constant", "fig7_radial", "wide_annulus", "tall_narrow"}) {
    const std::string path = std::string(SYLVA_SOURCE_DIR) + "/presets/guiding_vectors_" + name + ".json";
    preset p;
    const load_result r = load_preset_file(path, p);
    ASSERT_TRUE(r.ok) << path << ": " << r.error;
    EXPECT_TRUE(r.warnings.empty()) << path << ": " << r.warnings.front();
    ASSERT_TRUE(std::holds_alternative<guiding_vectors_params>(p.spec.params)) << path;
    grow_report rep;
    const tree_skeleton t = grow(p.spec, {}, &rep);
    EXPECT_FALSE(rep.error) << path << ": " << rep.message;
    EXPECT_EQ(validate_skeleton(t), "") << path;
    EXPECT_GT(t.size(), 50u) << path;
  }
  // The seed's schedule, spelled out, is the built-in default.
  preset seed;
  ASSERT_TRUE(load_preset_file(std::string(SYLVA_SOURCE_DIR) + "/presets/guiding_vectors_seed002.json", seed).ok);
  EXPECT_EQ(std::get<guiding_vectors_params>(seed.spec.params).step_t, (std::vector<float>{-3, -3, 1, 1, 1}));
}

TEST(GuidingVectors, LaterEndpointsAreExactlyHHopsFromTheTree) {
  // Rebuild the generator's graph (same domain, first point, spacing and seed) and check that each
  // step-2 endpoint lies exactly h hops, by breadth-first search, from the tree of step 1.
  guiding_vectors_params p = small_params();
  p.steps = 2;
  p.clear_trunk = 0;
  growth_debug dbg;
  grow_options o;
  o.seed = 9;
  const tree_skeleton t = grow_guiding_vectors(p, o, nullptr, &dbg);
  const glm::vec3 s = p.domain_size;
  std::vector<glm::vec3> pts;
  ASSERT_TRUE(sample_poisson_disc({-s.x / 2, 0, -s.z / 2}, {s.x / 2, s.y, s.z / 2}, glm::vec3(0), p.spacing, p.candidates,
                                  o.seed, {}, pts));
  gv_graph g = make_gv_graph(pts, p.spacing);
  std::vector<int> hops(g.point.size(), -1);
  std::vector<int32_t> frontier;
  for (size_t i = 0; i < t.size(); ++i)
    if (t.born[i] <= 1)
      for (int32_t v = 0; v < int32_t(g.point.size()); ++v)
        if (g.point[v] == t.position[i]) {
          hops[v] = 0;
          frontier.push_back(v);
        }
  const int h = int(p.step_hops[1]);
  for (int d = 1; d <= h; ++d) {
    std::vector<int32_t> next;
    for (int32_t u : frontier) {
      const int32_t* e = yao8_edges(g, u);
      for (int o8 = 0; o8 < 8; ++o8)
        if (e[o8] >= 0 && hops[e[o8]] < 0) {
          hops[e[o8]] = d;
          next.push_back(e[o8]);
        }
    }
    frontier = std::move(next);
  }
  int checked = 0;
  for (size_t k = 0; k < dbg.points.size(); ++k) {
    if (dbg.point_value[k] != 2) continue;
    for (int32_t v = 0; v < int32_t(g.point.size()); ++v)
      if (g.point[v] == dbg.points[k]) {
        EXPECT_EQ(hops[v], h);
        ++checked;
      }
  }
  EXPECT_EQ(checked, int(p.step_endpoints[1]));
}

TEST(GuidingVectors, CancelReturnsWhatIsGrown) {   // bad input: generator_suite_test.cpp
  std::atomic<uint32_t> generation{1};
  grow_options o;
  o.cancel = &generation;  // cancel_value is 0, so this counts as cancelled from the start
  grow_report rep;
  tree_skeleton t = grow_guiding_vectors(small_params(), o, &rep);
  EXPECT_TRUE(rep.cancelled);
  EXPECT_EQ(validate_skeleton(t), "");
  EXPECT_GE(t.size(), 1u);
}
