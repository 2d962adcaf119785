// The species library: the fifteen species exist, say which generator grows them and
// why, and keep or drop their leaves in winter as their kind does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "generators/tree_spec.h"
#include "render/mesh/mesh.h"
#include "render/io/preset.h"
#include "render/mesh/season.h"

using namespace sylva;

namespace {

struct species_case {
  const char* file;        // presets/species_<file>.json
  const char* tag;         // the tag that names it
  bool evergreen;          // keeps its leaves in winter
};

constexpr species_case library[] = {
    {"oak", "oak", false},       {"maple", "maple", false},    {"beech", "beech", false},
    {"birch", "birch", false},   {"ash", "ash", false},        {"poplar", "poplar", false},
    {"willow", "willow", false}, {"pine", "pine", true},       {"spruce", "spruce", true},
    {"fir", "fir", true},        {"cedar", "cedar", true},     {"cypress", "cypress", true},
    {"palm", "palm", true},
    {"sapling", "sapling", false}, {"bush", "bush", false},
};

}  // namespace

TEST(Species, FifteenSpeciesSayTheirGeneratorAndWhy) {
  for (const species_case& c : library) {
    SCOPED_TRACE(c.file);
    preset p;
    const load_result r = load_preset_file(std::string(SYLVA_SOURCE_DIR "/presets/species_") + c.file + ".json", p);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    EXPECT_NE(std::find(p.tags.begin(), p.tags.end(), "species"), p.tags.end());
    EXPECT_NE(std::find(p.tags.begin(), p.tags.end(), c.tag), p.tags.end());
    // The description names the generator that grows the form and gives the reason.
    const std::string gen = generator_name(p.spec);
    const char* said = gen == "space_colonization" ? "space colonization"
                       : gen == "self_organizing"  ? "elf-organizing"
                       : gen == "guiding_vectors"  ? "uiding vector"
                                                   : "L-system";
    EXPECT_NE(p.description.find(said), std::string::npos) << gen << ": " << p.description;
    EXPECT_NE(p.description.find("because"), std::string::npos) << p.description;
  }
}

TEST(Species, WinterStripsTheBroadleavesAndSparesTheConifersAndPalm) {
  for (const species_case& c : library) {
    SCOPED_TRACE(c.file);
    preset p;
    ASSERT_TRUE(load_preset_file(std::string(SYLVA_SOURCE_DIR "/presets/species_") + c.file + ".json", p).ok);
    p.render.season = leaf_season::winter;
    const season_look s = season_leaf_look(p.render);
    const bool deciduous = (s.deciduous_mask >> int(p.mesh.leaves.archetype)) & 1u;
    EXPECT_EQ(deciduous, !c.evergreen);
    // Autumn colours differ from the summer green for every broadleaf.
    if (!c.evergreen) { EXPECT_NE(p.render.autumn_color, p.render.leaf_color); }
  }
}

// ---- Conifer and palm forms: each reads as itself, measured on the grown tree.
namespace {

struct grown {
  tree_skeleton t;
  tree_mesh m;
};
grown grow_species(const char* name) {
  preset p;
  EXPECT_TRUE(load_preset_file(std::string(SYLVA_SOURCE_DIR "/presets/species_") + name + ".json", p).ok);
  grown g;
  g.t = grow(p.spec, grow_options{});
  g.m = mesh_tree(g.t, p.mesh, p.spec.seed);
  return g;
}
// The widest horizontal distance of a leaf from the trunk's axis (x = z = 0) in a height band.
float leaf_reach(const tree_mesh& m, float y0, float y1) {
  float r = 0;
  for (const leaf_instance& l : m.leaves)
    if (l.position.y >= y0 && l.position.y < y1) r = std::max(r, std::hypot(l.position.x, l.position.z));
  return r;
}
float top_of(const tree_mesh& m) {
  float top = 0;
  for (const leaf_instance& l : m.leaves) top = std::max(top, l.position.y);
  return top;
}

}  // namespace

TEST(Species, CypressIsAFlamePointedAtTheTopWithFoliageToTheGround) {
  const grown g = grow_species("cypress");
  const float h = top_of(g.m);
  ASSERT_GT(h, 8.0f);
  float lowest = h;
  for (const leaf_instance& l : g.m.leaves) lowest = std::min(lowest, l.position.y);
  EXPECT_LT(lowest, 0.3f) << "no bare trunk at the base";
  const float widest = leaf_reach(g.m, 0.2f * h, 0.45f * h);
  EXPECT_LT(widest, 1.5f) << "a narrow flame";
  EXPECT_LT(leaf_reach(g.m, 0.9f * h, h + 1), 0.45f * widest) << "pointed, not a blunt square top";
  EXPECT_LT(leaf_reach(g.m, 0.75f * h, 0.9f * h), 0.8f * widest) << "tapering in its upper quarter";
}

TEST(Species, SpruceHangsCurtainsOfBranchletsWhereTheFirHoldsLevelTiers) {
  // Share of the wood in the laterals' side shoots (order >= 2) that points steeply down.
  auto hanging = [](const tree_skeleton& t) {
    double down = 0, all = 0;
    for (size_t i = 0; i < t.size(); ++i) {
      if (t.parent[i] < 0 || t.order[i] < 2) continue;
      const glm::vec3 d = t.position[i] - t.position[size_t(t.parent[i])];
      const float len = glm::length(d);
      if (!(len > 0)) continue;
      all += len;
      if (d.y < -0.7f * len) down += len;
    }
    return all > 0 ? down / all : 0.0;
  };
  const double spruce = hanging(grow_species("spruce").t), fir = hanging(grow_species("fir").t);
  EXPECT_GT(spruce, 0.25) << "pendulous branchlets under the laterals";
  EXPECT_LT(fir, 0.05) << "level, upturned tiers";
}

TEST(Species, CedarOfLebanonIsBroaderThanTallInFlatTiers) {
  const grown g = grow_species("cedar");
  const float h = top_of(g.m);
  EXPECT_GT(2 * leaf_reach(g.m, 0, h + 1), h) << "broad spreading tiers";
  // Flat layers: leaves bunch at a few heights, with thin foliage between them. Histogram of leaf
  // heights in 0.25 m bins over the crown: the fullest bins hold far more than the emptiest.
  std::vector<int> bins(size_t(h / 0.25f) + 1, 0);
  for (const leaf_instance& l : g.m.leaves)
    if (l.position.y > 2.0f) ++bins[size_t(std::max(l.position.y, 0.0f) / 0.25f)];
  std::vector<int> crown(bins.begin() + 9, bins.end() - 2);
  std::sort(crown.begin(), crown.end());
  ASSERT_GT(crown.size(), 8u);
  EXPECT_GT(crown[crown.size() * 9 / 10], 4 * std::max(crown[crown.size() / 5], 1)) << "tiers with gaps";
}

TEST(Species, PalmFrondsArchEvenlyAllRoundOnAStemThatTapers) {
  const grown g = grow_species("palm");
  ASSERT_GT(g.m.leaves.size(), 200u);
  // The leaflets' centroid sits over the crown's centre (the stem top), not off to one side.
  glm::vec3 c(0);
  float top = 0;
  glm::vec3 crown(0);
  for (size_t i = 0; i < g.t.size(); ++i)
    if (g.t.order[i] == 0 && g.t.position[i].y > top) top = g.t.position[i].y, crown = g.t.position[i];
  for (const leaf_instance& l : g.m.leaves) c += l.position;
  c /= float(g.m.leaves.size());
  const float reach = leaf_reach(g.m, -1, 100);
  EXPECT_LT(std::hypot(c.x - crown.x, c.z - crown.z), 0.2f * reach) << "fronds droop to one side";
  // Every quarter around the crown holds at least a sixth of the leaflets.
  int quarter[4] = {};
  for (const leaf_instance& l : g.m.leaves) {
    const float a = std::atan2(l.position.z - crown.z, l.position.x - crown.x);
    ++quarter[std::clamp(int((a + 3.14159265f) / (3.14159265f / 2)), 0, 3)];
  }
  for (int q : quarter) EXPECT_GT(q, int(g.m.leaves.size() / 6));
  // The stem is swollen at its base and tapers: its base radius is well over its radius below the crown.
  float base_r = 0, upper_r = 1e9f;
  for (size_t i = 0; i < g.t.size(); ++i) {
    if (g.t.order[i] != 0) continue;
    if (g.t.position[i].y < 0.3f) base_r = std::max(base_r, g.t.radius[i]);
    if (g.t.position[i].y > 0.6f * top && g.t.position[i].y < 0.85f * top) upper_r = std::min(upper_r, g.t.radius[i]);
  }
  EXPECT_GT(base_r, 1.4f * upper_r);
}
