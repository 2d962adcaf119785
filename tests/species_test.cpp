// The species library (issue 12): the fifteen species exist, say which generator grows them and
// why, and keep or drop their leaves in winter as their kind does.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "render/preset.h"
#include "render/season.h"

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
