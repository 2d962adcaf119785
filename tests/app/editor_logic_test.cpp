// Editor logic that needs no display: parameter relevance, per-step tables, overlay kinds.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/editor/editor_generators.h"
#include "generators/tree_spec.h"
#include "render/mesh/overlay_geometry.h"

namespace sylva {
namespace {

template <class P>
std::vector<std::string> hidden_keys(const P& p) {
  std::vector<std::string> out;
  visit_params(p, [&](const auto& value, const param_info& info) {
    if (!param_relevant(p, &value, info)) out.emplace_back(info.key);
  });
  return out;
}

TEST(EditorLogic, LsystemHondaModeHidesTextSettings) {
  lsystem_params p;
  p.mode = lsystem_mode::honda;
  // The growth history (seasons, self-pruning) acts on text L-systems' derivations only; a stub's
  // length shows only with self-pruning on (live crown under 1).
  EXPECT_EQ(hidden_keys(p), (std::vector<std::string>{"source", "turtle_leaf_size", "widths", "pipe_exponent",
                                                      "tip_radius", "pipe_taper", "season_variation", "live_crown",
                                                      "stub_length", "module_cap"}));
}

TEST(EditorLogic, LsystemTextModeHidesHondaSliders) {
  lsystem_params p;
  p.mode = lsystem_mode::text;
  // The eleven symbols of Honda's production A(s,w) : s >= min -> ... ; mode, derivations, scale,
  // width scale and node cap apply to both models.
  EXPECT_EQ(hidden_keys(p), (std::vector<std::string>{"s0", "w0", "min", "alpha1", "alpha2", "phi1", "phi2", "r1",
                                                      "r2", "q", "e", "stub_length"}));
  p.live_crown = 0.7f;   // self-pruning on: the stub length shows
  EXPECT_EQ(hidden_keys(p).back(), "e");
}

TEST(EditorLogic, OtherGeneratorsShowEverything) {
  EXPECT_TRUE(hidden_keys(guiding_vectors_params{}).empty());
}

// The open side's azimuth shows only once the tree leans towards it (Loehle 1986's phototropism).
TEST(EditorLogic, OpenSideShowsOnlyWithALean) {
  self_organizing_params so;
  EXPECT_EQ(hidden_keys(so), (std::vector<std::string>{"open_side"}));
  so.sky_lean = 0.3f;
  EXPECT_TRUE(hidden_keys(so).empty());
  space_colonization_params sc;
  sc.sky_lean = 0.3f;
  EXPECT_EQ(hidden_keys(sc).back(), "stub_length");
}

// Space colonization shows an envelope's own settings only with that envelope.
TEST(EditorLogic, SpaceColonizationShowsOnlyTheEnvelopesOwnSettings) {
  // Without forks or leader damage the fork asymmetry, without self-pruning the stub length, and
  // without a lean the open side change nothing and hide too.
  space_colonization_params p;   // an ellipsoid without dents
  EXPECT_EQ(hidden_keys(p), (std::vector<std::string>{"slab_thickness", "envelope_mesh", "envelope_dent_depth", "fork_asymmetry",
                                                      "stub_length", "open_side"}));
  p.envelope = envelope_shape::slab;
  p.envelope_dents = 8;
  p.leader_damage = 0.05f;
  p.live_crown = 0.8f;
  p.sky_lean = 0.3f;
  EXPECT_EQ(hidden_keys(p), (std::vector<std::string>{"envelope_mesh"}));
  p.envelope = envelope_shape::mesh;
  EXPECT_EQ(hidden_keys(p), (std::vector<std::string>{"slab_thickness"}));
}

// The generator's own leaf rule shows only when the mesh places the generator's leaves: under
// the shoots model space colonization's spiral settings and the L-system's L size change nothing.
TEST(EditorLogic, OwnLeafSettingsShowOnlyWithTheGeneratorsLeaves) {
  auto hidden = [](const auto& p, bool generator_leaves) {
    std::vector<std::string> out;
    visit_params(p, [&](const auto& value, const param_info& info) {
      if (!editor_shows(p, &value, info, generator_leaves)) out.emplace_back(info.key);
    });
    return out;
  };
  const space_colonization_params sc;
  EXPECT_EQ(hidden(sc, true), hidden_keys(sc));
  EXPECT_EQ(hidden(sc, false), (std::vector<std::string>{"slab_thickness", "envelope_mesh", "envelope_dent_depth", "fork_asymmetry",
                                                         "stub_length", "open_side", "leaves_min",
                                                         "leaves_max", "leaf_size_min", "leaf_size_max", "spiral_a", "spiral_k",
                                                         "spiral_e", "spiral_rounds"}));
  lsystem_params ls;
  ls.mode = lsystem_mode::text;
  EXPECT_EQ(hidden(ls, true), hidden_keys(ls));
  std::vector<std::string> text_hidden = hidden_keys(ls);
  text_hidden.insert(text_hidden.begin() + 11, "turtle_leaf_size");
  EXPECT_EQ(hidden(ls, false), text_hidden);
  EXPECT_EQ(hidden(self_organizing_params{}, false), hidden_keys(self_organizing_params{}));   // no leaf rule of its own
}

TEST(EditorLogic, GuidingVectorScheduleIsOneTable) {
  guiding_vectors_params p;   // t = -3,-3,1,1,1; endpoints 3,16,40,90,160; hops 1,5,4,3,2
  std::vector<step_column> cols = collect_step_columns(p);
  ASSERT_EQ(cols.size(), 3u);
  EXPECT_STREQ(cols[0].info.key, "step_t");
  EXPECT_STREQ(cols[1].info.key, "step_endpoints");
  EXPECT_STREQ(cols[2].info.key, "step_hops");
  EXPECT_EQ(cols[0].values, &p.step_t);
  EXPECT_EQ(step_rows(cols), 5u);
  EXPECT_EQ(step_cell(cols[1], 2), 40.0f);

  add_step(cols);   // the new step repeats each column's last entry
  EXPECT_EQ(step_rows(cols), 6u);
  EXPECT_EQ(p.step_t.back(), 1.0f);
  EXPECT_EQ(p.step_endpoints.back(), 160.0f);
  EXPECT_EQ(p.step_hops.back(), 2.0f);

  remove_step(cols);
  remove_step(cols);
  EXPECT_EQ(step_rows(cols), 4u);
  EXPECT_EQ(p.step_endpoints, (std::vector<float>{3, 16, 40, 90}));
}

TEST(EditorLogic, ShortColumnsRepeatTheirLastEntry) {
  guiding_vectors_params p;
  p.step_t = {-3};
  p.step_endpoints = {3, 16, 40};
  p.step_hops = {};
  std::vector<step_column> cols = collect_step_columns(p);
  EXPECT_EQ(step_rows(cols), 3u);
  EXPECT_EQ(step_cell(cols[0], 2), -3.0f);                   // repeated
  EXPECT_EQ(step_cell(cols[2], 0), cols[2].info.min);         // empty: the minimum

  set_step_cell(cols[0], 2, 7);   // steps 1 and 2 keep the repeated -3
  EXPECT_EQ(p.step_t, (std::vector<float>{-3, -3, 7}));

  remove_step(cols);   // only the columns reaching step 3 lose it
  EXPECT_EQ(p.step_t, (std::vector<float>{-3, -3}));
  EXPECT_EQ(p.step_endpoints, (std::vector<float>{3, 16}));
  EXPECT_TRUE(p.step_hops.empty());

  p.step_t = {1};
  p.step_endpoints = {2};
  remove_step(cols);   // never below one step
  EXPECT_EQ(step_rows(cols), 1u);
}

TEST(EditorLogic, ParseErrorKeepsTheLastTree) {
  tree_spec spec;
  lsystem_params p;
  p.mode = lsystem_mode::text;
  p.source = "#axiom X\nX -> F(1+)X\n";   // an expression missing its operand
  spec.params = p;
  grow_result r;
  grow_options o;
  r.skeleton = std::make_shared<tree_skeleton>(grow(spec, o, &r.report));
  EXPECT_TRUE(keeps_last_tree(r));
  p.source = "#axiom X\nX -> F[+X]X\n";
  spec.params = p;
  r.report = {};
  grow(spec, o, &r.report);
  EXPECT_FALSE(keeps_last_tree(r));
}

TEST(EditorLogic, ColonizationPointsFollowTheTimeline) {
  growth_debug d;
  d.points = {{0, 1, 0}, {1, 1, 0}};
  d.point_value = {-1, 2};   // alive at the end; killed in step 2
  d.lines = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}};
  d.line_color = {{1.0f, 0.75f, 0.2f}, {0.35f, 0.6f, 1.0f}};   // influence link, envelope outline
  d.point_kind = {debug_kind::marker, debug_kind::marker};
  d.line_kind = {debug_kind::influence_link, debug_kind::envelope_edge};
  tree_skeleton t;
  t.add_node({0, 0, 0}, -1, 0.1f, 0, 0);
  t.steps = 4;
  const overlay_geometry g = build_overlays(d, &t);
  ASSERT_EQ(g.points.size(), 3u);
  EXPECT_EQ(g.points[0].kind, float(overlay_markers));
  EXPECT_EQ(g.points[0].died, overlay_forever);
  EXPECT_EQ(g.points[1].kind, float(overlay_markers));   // alive before step 2 ...
  EXPECT_EQ(g.points[1].born, 0.0f);
  EXPECT_EQ(g.points[1].died, 2.0f);
  EXPECT_EQ(g.points[2].kind, float(overlay_killed));    // ... and red in exactly step 2
  EXPECT_EQ(g.points[2].born, 2.0f);
  EXPECT_EQ(g.points[2].died, 3.0f);
  ASSERT_EQ(g.lines.size(), 4u);
  EXPECT_EQ(g.lines[0].kind, float(overlay_influence));
  EXPECT_EQ(g.lines[0].born, 4.0f);   // only the last iteration's links exist
  EXPECT_EQ(g.lines[2].kind, float(overlay_envelope));
  EXPECT_EQ(g.lines[2].born, 0.0f);
}

TEST(EditorLogic, GuidingVectorSourcesBelongToTheirStep) {
  growth_debug d;
  // As grow_guiding_vectors writes them: step 1's sources (0) then endpoints (1), step 2's ...
  d.points = {{0, 0, 0}, {0, 1, 0}, {0, 2, 0}, {0, 3, 0}};
  d.point_value = {0, 1, 0, 2};
  d.lines = {{0, 0, 0}, {1, 0, 0}, {0, 0, 0}, {0, 1, 0}};
  d.line_color = {glm::vec3(0.45f), {1.0f, 0.55f, 0.1f}};
  d.point_kind = {debug_kind::source, debug_kind::endpoint, debug_kind::source, debug_kind::endpoint};
  d.line_kind = {debug_kind::graph_edge, debug_kind::guide_arrow};
  const overlay_geometry g = build_overlays(d, nullptr);
  ASSERT_EQ(g.points.size(), 4u);
  const float born[] = {1, 1, 2, 2};
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(g.points[i].kind, float(overlay_endpoints));
    EXPECT_EQ(g.points[i].born, born[i]);
    EXPECT_EQ(g.points[i].died, born[i] + 1);
  }
  EXPECT_EQ(g.lines[0].kind, float(overlay_graph));
  EXPECT_EQ(g.lines[2].kind, float(overlay_guides));
}

TEST(EditorLogic, ShadowGridLayersFatesAndFlow) {
  growth_debug d;
  d.points = {{0, 0.5f, 0}, {0, 1.0f, 0}, {1, 1.0f, 0}, {0, 2.0f, 0}};
  d.point_value = {0.2f, 0.4f, 0.1f, 0.1f};
  d.point_kind.assign(4, debug_kind::shadow_sample);
  tree_skeleton t;
  t.add_node({0, 0, 0}, -1, 0.1f, 0, 0);
  t.add_node({0, 1, 0}, 0, 0.1f, 1, 0);
  t.add_node({0, 2, 0}, 1, 0.1f, 2, 0);
  t.died[2] = 3;   // shed in step 3
  t.steps = 5;
  d.node_fate = {0, 1, 2};
  d.node_flow = {0, 4, 1};   // the root carries no internode
  const overlay_geometry g = build_overlays(d, &t);
  EXPECT_FLOAT_EQ(g.shadow_layer, 0.5f);   // layers at y = 0.5, 1, 2: the closest pair is 0.5 apart
  EXPECT_FLOAT_EQ(g.shadow_min_y, 0.5f);
  EXPECT_FLOAT_EQ(g.shadow_max_y, 2.0f);
  ASSERT_EQ(g.points.size(), 4u + 3u + 2u);
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(g.points[i].kind, float(overlay_shadow_grid));
  EXPECT_EQ(g.points[4].kind, float(overlay_fates));
  EXPECT_EQ(g.points[4].born, 5.0f);   // fates are the last step's
  EXPECT_EQ(g.points[6].born, 3.0f);   // a shed node shows from its shedding on
  EXPECT_NE(g.points[4].color, g.points[5].color);
  // Flow: node 1 carries the most (diameter 2 + 14), node 2 a quarter of it (√¼ = ½: 2 + 7).
  EXPECT_EQ(g.points[7].kind, float(overlay_flow));
  EXPECT_FLOAT_EQ(g.points[7].size, 16.0f);
  EXPECT_FLOAT_EQ(g.points[8].size, 9.0f);
  EXPECT_EQ(g.points[7].position, glm::vec3(0, 0.5f, 0));   // internode midpoint
}

}  // namespace
}  // namespace sylva

TEST(EditorLogic, OverlaysShowOneLayerOfTheGeneratorFirstAndKnowWhatIsPresent) {
  using namespace sylva;
  overlay_view v;
  EXPECT_EQ(v.kinds, 1u << overlay_shadow_grid);   // one layer by default
  EXPECT_FALSE(v.combine);
  EXPECT_TRUE(v.shadow_slice);                    // a slice, not the whole cloud
  growth_debug d;
  d.points = {{0, 0, 0}, {0, 1, 0}};
  d.point_value = {-1, 0.5f};   // space colonization: one alive, one killed at step 0
  d.point_kind.assign(2, debug_kind::marker);
  const overlay_geometry g = build_overlays(d, nullptr);
  EXPECT_EQ(g.present, (1u << overlay_markers) | (1u << overlay_killed));
  EXPECT_EQ(overlay_default_kind(1, g.present), int(overlay_markers));
  EXPECT_EQ(overlay_default_kind(0, 1u << overlay_fates), int(overlay_fates));   // the first present one
  // The ramp never turns green, the ground's colour.
  for (float x = 0; x <= 1; x += 0.05f) {
    const glm::vec3 c = overlay_ramp(x);
    EXPECT_FALSE(c.y > c.x && c.y > c.z) << x;
  }
}
