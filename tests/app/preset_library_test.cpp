// The preset library: coverage of the shipped presets, their metadata, search, and thumbnail keys.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>

#include "app/editor/preset_library.h"
#include "render/io/preset.h"
#include "tests/scratch_dir.h"

namespace sylva {
namespace {

const std::string presets_dir = std::string(SYLVA_SOURCE_DIR) + "/presets";

TEST(PresetLibrary, ShipsAtLeast24PresetsOverAllFourGenerators) {
  const std::vector<preset_entry> entries = scan_preset_folder(presets_dir, 128);
  EXPECT_GE(entries.size(), 24u);
  std::set<std::string> generators;
  for (const preset_entry& e : entries) generators.insert(e.generator);
  for (const char* g : {"self_organizing", "space_colonization", "guiding_vectors", "lsystem"})
    EXPECT_TRUE(generators.count(g)) << "no preset uses " << g;
}

TEST(PresetLibrary, EveryPresetLoadsWithNameDescriptionAndTags) {
  for (const preset_entry& e : scan_preset_folder(presets_dir, 128)) {
    SCOPED_TRACE(e.path);
    EXPECT_TRUE(e.error.empty()) << e.error;
    EXPECT_FALSE(e.name.empty());
    EXPECT_NE(e.name, "Untitled");   // the loader's default: the file gave no name
    EXPECT_GE(e.description.size(), 20u) << "a description says what the tree is";
    EXPECT_FALSE(e.tags.empty());
    EXPECT_EQ(e.thumbnail_key.size(), 16u);
  }
}

TEST(PresetLibrary, SpeciesPresetsExistAndLoadWithoutWarnings) {
  std::set<std::string> generators;
  for (const char* species : {"oak", "pine", "birch", "willow", "bush", "palm", "forest"}) {
    const std::string path = presets_dir + "/species_" + species + ".json";
    SCOPED_TRACE(path);
    ASSERT_TRUE(std::filesystem::exists(path));
    preset p;
    load_result r = load_preset_file(path, p);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();   // every key is known and in range
    EXPECT_NE(std::find(p.tags.begin(), p.tags.end(), "species"), p.tags.end());
    EXPECT_NE(std::find(p.tags.begin(), p.tags.end(), species), p.tags.end());
    generators.insert(generator_name(p.spec));
  }
  // The species are spread over the generators rather than all made one way.
  EXPECT_GE(generators.size(), 3u);
}

TEST(PresetLibrary, ThumbnailKeyFollowsContentAndSize) {
  const std::string a = R"({"sylva_preset": 1, "name": "A", "generator": "lsystem"})";
  std::string b = a;
  b[b.find('A')] = 'B';   // one byte differs
  EXPECT_EQ(thumbnail_key(a, 128), thumbnail_key(a, 128));   // a pure function of its input
  EXPECT_NE(thumbnail_key(a, 128), thumbnail_key(b, 128));
  EXPECT_NE(thumbnail_key(a, 128), thumbnail_key(a, 256));
  EXPECT_NE(thumbnail_key(a, 128), thumbnail_key(a + " ", 128));   // whitespace is content too
  EXPECT_EQ(thumbnail_key("", 128).size(), 16u);
  const std::string k = thumbnail_key(a, 128);
  EXPECT_TRUE(std::all_of(k.begin(), k.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); }));
}

TEST(PresetLibrary, ThumbnailKeyChangesWhenAPresetFileIsEdited) {
  const sylva_test::scratch_dir scratch("sylva_preset_library_test");
  const std::filesystem::path& dir = scratch.dir;
  preset p = default_preset();
  p.name = "Edited";
  p.description = "A preset written by the test";
  p.tags = {"test"};
  ASSERT_EQ(save_preset_file(p, (dir / "t.json").string()), "");
  const std::string before = scan_preset_folder(dir.string(), 128).at(0).thumbnail_key;
  p.spec.seed = 7;
  ASSERT_EQ(save_preset_file(p, (dir / "t.json").string()), "");
  const std::vector<preset_entry> after = scan_preset_folder(dir.string(), 128);
  ASSERT_EQ(after.size(), 1u);
  EXPECT_NE(after[0].thumbnail_key, before);
  EXPECT_EQ(after[0].name, "Edited");
  EXPECT_EQ(after[0].generator, "lsystem");
}

TEST(PresetLibrary, BrokenFilesAreListedWithTheirError) {
  const sylva_test::scratch_dir scratch("sylva_preset_library_broken");
  const std::filesystem::path& dir = scratch.dir;
  ASSERT_EQ(write_file_atomic((dir / "bad.json").string(), "{ \"sylva_preset\": 1, "), "");
  ASSERT_EQ(write_file_atomic((dir / "notes.txt").string(), "not a preset"), "");
  const std::vector<preset_entry> entries = scan_preset_folder(dir.string(), 128);
  ASSERT_EQ(entries.size(), 1u);   // only *.json files
  EXPECT_FALSE(entries[0].error.empty());
  EXPECT_EQ(entries[0].name, "bad");   // the file stem stands in for the name
  EXPECT_TRUE(scan_preset_folder((dir / "missing").string(), 128).empty());
}

// The binary's tree and the working folder both ship presets/: a file with the same name and bytes
// is one card (from the first folder), a folder named twice is scanned once, and a file that
// differs (an edited copy) or has another name keeps its own card.
TEST(PresetLibrary, APresetShippedInTwoFoldersIsOneCard) {
  namespace fs = std::filesystem;
  const sylva_test::scratch_dir scratch("sylva_preset_library_twice");
  const fs::path& dir = scratch.dir;
  fs::create_directories(dir / "bin" / "presets");
  fs::create_directories(dir / "work" / "presets");
  preset p = default_preset();
  p.name = "Oak";
  ASSERT_EQ(save_preset_file(p, (dir / "bin" / "presets" / "oak.json").string()), "");
  ASSERT_EQ(save_preset_file(p, (dir / "work" / "presets" / "oak.json").string()), "");
  ASSERT_EQ(save_preset_file(p, (dir / "work" / "presets" / "oak_copy.json").string()), "");
  p.spec.seed = 9;
  ASSERT_EQ(save_preset_file(p, (dir / "work" / "presets" / "edited.json").string()), "");
  const std::string bin = (dir / "bin" / "presets").string(), work = (dir / "work" / "presets").string();
  const std::vector<preset_entry> entries = scan_preset_folders({bin, work, bin + "/../presets", work + "/"}, 128);
  std::vector<std::string> paths;
  for (const preset_entry& e : entries) paths.push_back(fs::relative(e.path, dir).string());
  EXPECT_EQ(paths, (std::vector<std::string>{"bin/presets/oak.json", "work/presets/edited.json", "work/presets/oak_copy.json"}));
}

TEST(PresetLibrary, SearchMatchesEveryWordCaseInsensitivelyAndRequiresEveryTag) {
  preset_entry e;
  e.name = "Oak";
  e.description = "A broad, spreading crown on a short trunk";
  e.generator = "self_organizing";
  e.tags = {"species", "deciduous"};
  EXPECT_TRUE(preset_matches(e, "", {}));
  EXPECT_TRUE(preset_matches(e, "OAK", {}));
  EXPECT_TRUE(preset_matches(e, "  spreading   trunk ", {}));   // words in any order, extra spaces
  EXPECT_TRUE(preset_matches(e, "decid", {}));                    // tags are searched
  EXPECT_TRUE(preset_matches(e, "organizing", {}));               // and the generator
  EXPECT_FALSE(preset_matches(e, "oak pine", {}));                // every word must match
  EXPECT_TRUE(preset_matches(e, "", {"species"}));
  EXPECT_TRUE(preset_matches(e, "oak", {"species", "deciduous"}));
  EXPECT_FALSE(preset_matches(e, "", {"species", "conifer"}));
  EXPECT_FALSE(preset_matches(e, "", {"Species"}));               // tag buttons match exactly
}

TEST(PresetLibrary, TagsAreCollectedOnceMostUsedFirst) {
  std::vector<preset_entry> entries(3);
  entries[0].tags = {"b", "a"};
  entries[1].tags = {"a"};
  entries[2].tags = {"c", "a", "b"};
  // a: 3, b: 2, c: 1.
  EXPECT_EQ(collect_tags(entries), (std::vector<std::string>{"a", "b", "c"}));
  entries[2].tags = {"c"};
  // a: 2, b: 1, c: 1; ties keep alphabetical order.
  EXPECT_EQ(collect_tags(entries), (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_TRUE(collect_tags({}).empty());
}

}  // namespace
}  // namespace sylva
