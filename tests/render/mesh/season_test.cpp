// The season on the CPU: looks per season, fallen leaves with scrubbing intact, no regrow,
// out-of-range values clamped, and exports without winter's leaves. The viewport's pixels and the
// editor are tests/gl/season_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "render/io/export.h"
#include "render/io/preset.h"
#include "render/mesh/lod_cards.h"
#include "render/mesh/season.h"
#include "tests/scratch_dir.h"
#include "tests/season_cards.h"

using namespace sylva;
using sylva_test::card_grid;
using sylva_test::with_season;

TEST(Season, SummerIsTheLeafColourAndChangesNothing) {
  render_params rp;
  rp.leaf_color = glm::vec3(0.2f, 0.5f, 0.1f);
  const season_look s = season_leaf_look(rp);
  EXPECT_EQ(s.evergreen_color, rp.leaf_color);
  EXPECT_EQ(s.deciduous_color_a, rp.leaf_color);
  EXPECT_EQ(s.deciduous_color_b, rp.leaf_color);
  EXPECT_FALSE(season_changes_leaves(s));
  const tree_mesh m = card_grid(uint8_t(leaf_archetype::lobed));
  EXPECT_EQ(apply_season(m, s).leaves.size(), m.leaves.size());
}

TEST(Season, HabitFollowsTheArchetypeUnlessThePresetSaysOtherwise) {
  render_params rp;
  const season_look by_archetype = season_leaf_look(rp);
  for (int k = 0; k < leaf_archetype_count; ++k)
    EXPECT_EQ(bool((by_archetype.deciduous_mask >> k) & 1u),
              !archetype_is_evergreen(leaf_archetype(k)) && !archetype_is_fruit(leaf_archetype(k))) << k;
  EXPECT_FALSE((by_archetype.deciduous_mask >> int(leaf_archetype::needles)) & 1u);
  EXPECT_TRUE((by_archetype.deciduous_mask >> int(leaf_archetype::lobed)) & 1u);
  rp.habit = leaf_habit::evergreen;
  EXPECT_EQ(season_leaf_look(rp).deciduous_mask, 0u);
  rp.habit = leaf_habit::deciduous;
  // Every archetype but the cones' and fruit's (generators/fruits.h), which keep their colours.
  uint64_t leaves = 0;
  for (int k = 0; k < leaf_archetype_count; ++k)
    if (!archetype_is_fruit(leaf_archetype(k))) leaves |= uint64_t(1) << k;
  EXPECT_EQ(season_leaf_look(rp).deciduous_mask, leaves);
}

// Baked LOD cards take texture leaf_archetype_count + k, past bit 31 for the last of them: the
// mask is 64 bits wide, so each still follows the season of the leaves it was baked from.
TEST(Season, EveryBakedCardKeepsItsSeasonBitPastBit31) {
  render_params rp;
  rp.habit = leaf_habit::deciduous;
  const season_look s = season_leaf_look(rp);
  baked_card_textures cards;
  for (int k = 0; k < max_baked_cards; ++k)
    cards.source.push_back(uint8_t(k % 2 ? leaf_archetype::lobed : leaf_archetype::cone_hanging));
  cards.sets.resize(cards.source.size());
  ASSERT_GT(leaf_archetype_count + max_baked_cards, 32);
  const season_look with = with_card_seasons(s, &cards);
  for (int k = 0; k < max_baked_cards; ++k)
    EXPECT_EQ(season_deciduous(with, leaf_archetype_count + k), k % 2 == 1) << "card " << k;
  // apply_season drops the deciduous cards in winter, the ones past bit 31 too.
  tree_mesh m;
  m.steps = 0;
  m.leaf_end = {uint32_t(max_baked_cards)};
  for (int k = 0; k < max_baked_cards; ++k)
    m.leaves.push_back({{0, 1, 0}, {0, 0, 0, 1}, 0.1f, 0, never_died, 0, uint8_t(leaf_archetype_count + k)});
  m.cards = std::make_shared<baked_card_textures>(cards);
  season_look winter = s;
  winter.deciduous_keep = 0;
  EXPECT_EQ(apply_season(m, winter).leaves.size(), size_t(max_baked_cards / 2));
}

TEST(Season, WinterDropsDeciduousLeavesAndKeepsConifersWithScrubbingIntact) {
  const season_look winter = season_leaf_look(with_season(leaf_season::winter));
  const tree_mesh oak = apply_season(card_grid(uint8_t(leaf_archetype::lobed)), winter);
  EXPECT_TRUE(oak.leaves.empty());
  EXPECT_EQ(oak.leaf_end, (std::vector<uint32_t>{0, 0, 0}));
  const tree_mesh pine = apply_season(card_grid(uint8_t(leaf_archetype::needles)), winter);
  EXPECT_EQ(pine.leaves.size(), 36u);

  // Autumn: about a quarter fall; leaf_end still counts the kept leaves born up to each step.
  const season_look autumn = season_leaf_look(with_season(leaf_season::autumn));
  const tree_mesh full = card_grid(uint8_t(leaf_archetype::palmate), 20);
  const tree_mesh fall = apply_season(full, autumn);
  EXPECT_LT(fall.leaves.size(), full.leaves.size() * 9 / 10);
  EXPECT_GT(fall.leaves.size(), full.leaves.size() / 2);
  EXPECT_EQ(fall.leaf_end.back(), fall.leaves.size());
  for (size_t s = 0; s < fall.leaf_end.size(); ++s)
    for (uint32_t i = 0; i < fall.leaf_end[s]; ++i) EXPECT_LE(int(fall.leaves[i].born), int(s));
  EXPECT_EQ(validate_mesh(fall), "");

  // Spring: smaller leaves.
  const tree_mesh spring = apply_season(full, season_leaf_look(with_season(leaf_season::spring)));
  ASSERT_FALSE(spring.leaves.empty());
  EXPECT_LT(spring.leaves[0].size, full.leaves[0].size);
}

TEST(Season, ChangingTheSeasonLeavesTheGrowthRequestAlone) {
  preset p;
  ASSERT_TRUE(load_preset_file(SYLVA_SOURCE_DIR "/presets/species_oak.json", p).ok);
  for (const char* s : {"season=autumn", "render.season=winter", "season=spring", "leaf_habit=evergreen",
                        "autumn_color=0.9,0.1,0.1"}) {
    preset q = p;
    ASSERT_EQ(set_preset_param(q, s), "") << s;
    EXPECT_EQ(q.spec, p.spec) << s;   // the worker's request is (spec, mesh): unchanged, so no regrow
    EXPECT_EQ(q.mesh, p.mesh) << s;
    EXPECT_NE(q.render, p.render) << s;
  }
  EXPECT_NE(set_preset_param(p, "season=monsoon"), "");
}

TEST(Season, OutOfRangeIsClampedWithAWarningAndRoundTrips) {
  preset p;
  load_result r = load_preset_json(R"({"sylva_preset": 1, "generator": "lsystem", "render": {"season": 7}})", p);
  ASSERT_TRUE(r.ok) << r.error;
  // The loader's rule for every enum (clamp_param): an index outside the options becomes the
  // first option, with the "clamped" warning.
  EXPECT_EQ(p.render.season, leaf_season::spring);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings[0].find("clamped"), std::string::npos) << r.warnings[0];
  r = load_preset_json(R"({"sylva_preset": 1, "generator": "lsystem", "render": {"season": "monsoon"}})", p);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(p.render.season, leaf_season::summer);
  EXPECT_FALSE(r.warnings.empty());
  // A corrupt in-memory value still gives a valid look.
  render_params rp;
  rp.season = leaf_season(42);
  EXPECT_EQ(season_leaf_look(rp), season_leaf_look(with_season(leaf_season::winter)));
  // Saved by name, loaded back equal.
  p.render.season = leaf_season::autumn;
  preset q;
  ASSERT_TRUE(load_preset_json(save_preset_json(p), q).ok);
  EXPECT_EQ(q.render.season, leaf_season::autumn);
  EXPECT_NE(save_preset_json(p).find("\"autumn\""), std::string::npos);
}

TEST(Season, ObjExportHasNoWinterLeavesAndAnAutumnMaterial) {
  const tree_mesh m = card_grid(uint8_t(leaf_archetype::lobed));
  tree_skeleton t;
  t.position = {glm::vec3(0)};
  t.parent = {-1};
  t.radius = {0.01f};
  t.born = {0};
  t.died = {never_died};
  t.order = {0};
  t.steps = 2;
  const sylva_test::scratch_dir scratch("sylva_season_test");
  auto leaf_faces = [&](leaf_season s, std::string* mtl) {
    export_options o;
    apply_render_params(o, with_season(s));
    const std::string path = scratch / "tree.obj";
    const export_result r = export_tree(t, m, export_info{}, path, o);
    EXPECT_EQ(r.error, "");
    std::ifstream in(path);
    std::string line;
    bool leaves = false;
    int faces = 0;
    while (std::getline(in, line)) {
      if (line.rfind("g ", 0) == 0) leaves = line.find("lea") != std::string::npos;
      if (leaves && line.rfind("f ", 0) == 0) ++faces;
    }
    if (mtl) {
      std::ifstream mi(path.substr(0, path.size() - 4) + ".mtl");
      std::stringstream ss;
      ss << mi.rdbuf();
      *mtl = ss.str();
    }
    return faces;
  };
  std::string summer_mtl, autumn_mtl;
  const int summer = leaf_faces(leaf_season::summer, &summer_mtl);
  EXPECT_GE(summer, 36);
  EXPECT_EQ(leaf_faces(leaf_season::winter, nullptr), 0);
  const int autumn = leaf_faces(leaf_season::autumn, &autumn_mtl);
  EXPECT_GT(autumn, 0);
  EXPECT_LT(autumn, summer);
}
