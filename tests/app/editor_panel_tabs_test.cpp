// The parameter panel's tabs and search: every shared group has a tab, the tabs come in a
// newcomer's order, and the search finds parameters by name, symbol, key and help.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "app/editor/editor_panel_tabs.h"
#include "generators/self_organizing.h"
#include "generators/wood.h"
#include "render/mesh/mesh.h"
#include "render/mesh/render_params.h"

using namespace sylva;

namespace {

// The groups a params struct declares (the section name for those before its first group).
template <class P>
std::set<std::string> groups_of(const char* section) {
  P p{};
  std::set<std::string> out;
  const char* current = section;
  visit_params(p, [&](auto&, const param_info& info) {
    if (info.group) current = info.group;
    out.insert(current);
  });
  return out;
}

}  // namespace

TEST(EditorPanelTabs, EverySharedGroupHasItsTab) {
  std::set<std::string> all;
  for (const auto& g : groups_of<mesh_params>("Mesh")) all.insert(g);
  for (const auto& g : groups_of<wood_params>("Wood")) all.insert(g);
  for (const auto& g : groups_of<render_params>("Render")) all.insert(g);
  ASSERT_GE(all.size(), 8u);
  for (const std::string& g : all) {
    bool known = false;
    tab_of_group(g.c_str(), &known);
    EXPECT_TRUE(known) << "group \"" << g << "\" has no tab in the parameter panel";
  }
  // Where a newcomer looks for them: season and wind in the Scene, leaves under Leaves.
  EXPECT_EQ(tab_of_group("Season"), panel_tab::scene);
  EXPECT_EQ(tab_of_group("Wind"), panel_tab::scene);
  EXPECT_EQ(tab_of_group("Leaves"), panel_tab::leaves);
  EXPECT_EQ(tab_of_group("Level of detail"), panel_tab::output);
  EXPECT_STREQ(panel_tab_label(panel_tab::tree), "Tree");
  EXPECT_LT(int(panel_tab::tree), int(panel_tab::leaves));
  EXPECT_LT(int(panel_tab::leaves), int(panel_tab::wood));
  EXPECT_LT(int(panel_tab::wood), int(panel_tab::scene));
  EXPECT_LT(int(panel_tab::scene), int(panel_tab::output));
}

TEST(EditorPanelTabs, SearchFindsByNameSymbolKeyAndHelp) {
  // The tropism weight's symbol is τ.
  self_organizing_params p{};
  std::set<std::string> by_tau, by_word, by_two;
  visit_params(p, [&](auto&, const param_info& info) {
    if (param_matches(info, nullptr, "τ")) by_tau.insert(info.key);
    if (param_matches(info, nullptr, "TROPISM")) by_word.insert(info.key);
    if (param_matches(info, nullptr, "tropism weight")) by_two.insert(info.key);
  });
  EXPECT_TRUE(by_tau.count("w_tropism"));
  EXPECT_TRUE(by_word.count("w_tropism"));
  EXPECT_EQ(by_two, std::set<std::string>{"w_tropism"});
  const param_info season{"season", "Season", "", 0, 3, "Spring: fresh light green"};
  EXPECT_TRUE(param_matches(season, "Season", ""));
  EXPECT_TRUE(param_matches(season, "Season", "spring"));   // the help
  EXPECT_TRUE(param_matches(season, "Season", "seas"));
  EXPECT_FALSE(param_matches(season, "Season", "wind"));
  EXPECT_FALSE(param_matches(season, "Season", "season wind"));   // every word must match
  // Words match where a word begins: "angle" is not in "triangles", but is in "angles" and keys.
  const param_info budget{"lod1_budget", "LOD1 budget", "", 0, 1, "Share of LOD0's triangles"};
  const param_info angle{"branch_angle", "Branching angle", "β", 0, 90, "Angle of a lateral from its parent"};
  EXPECT_FALSE(param_matches(budget, "Level of detail", "angle"));
  EXPECT_TRUE(param_matches(angle, nullptr, "angle"));
  EXPECT_TRUE(param_matches(angle, nullptr, "ANGLE of"));
  EXPECT_TRUE(param_matches(budget, nullptr, "triangles"));
  EXPECT_TRUE(param_matches(budget, nullptr, "budget"));   // the key's second word
}
