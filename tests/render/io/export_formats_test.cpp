// The export format table (render/io/export.h): one row per format, read by export_tree's callers,
// the CLI's checks and messages and the editor's export dialog.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <string>

#include "generators/lsystem.h"
#include "render/io/export.h"
#include "tests/fixtures.h"
#include "tests/run_sylva.h"
#include "tests/scratch_dir.h"

using namespace sylva;
namespace fs = std::filesystem;

TEST(ExportFormats, TheTableFindsEachRowInAnyCaseAndNothingElse) {
  ASSERT_EQ(export_format_count, 6);   // a new row: add it to the lists below
  for (const export_format& f : export_format_table) {
    EXPECT_EQ(find_export_format(f.ext), &f) << f.ext;
    std::string upper = f.ext;
    for (char& c : upper) c = char(std::toupper(static_cast<unsigned char>(c)));
    EXPECT_EQ(find_export_format(upper), &f) << upper;
  }
  EXPECT_EQ(find_export_format(".stl"), nullptr);
  EXPECT_EQ(find_export_format(""), nullptr);
  EXPECT_EQ(export_format_list(), ".glb, .gltf, .obj, .json, .png, .fbx");
  EXPECT_EQ(export_format_list(&export_format::lods), ".glb, .gltf, .obj, .fbx");
  EXPECT_EQ(export_format_list(&export_format::render, " "), ".png");
}

// Every format that is not a render is written by export_tree itself (a render needs GL).
TEST(ExportFormats, EveryFileFormatInTheTableIsWritten) {
  const sylva_test::scratch_dir scratch("sylva_formats_test");
  const fs::path& dir = scratch.dir;
  const sylva_test::honda_export h = sylva_test::honda_for_export(4, 64);
  const tree_skeleton& t = h.t;
  const tree_mesh& m = h.m;
  const export_options& o = h.o;
  for (const export_format& f : export_format_table) {
    if (f.render) continue;
    const std::string path = (dir / (std::string("tree") + f.ext)).string();
    const export_result r = export_tree(t, m, export_info{"lsystem", 1}, path, o);
    EXPECT_EQ(r.error, "") << f.ext;
    EXPECT_TRUE(fs::is_regular_file(path)) << f.ext;
    EXPECT_GT(r.bytes, 0u) << f.ext;
  }
}

// The CLI's messages come from the table, so a new row shows in them.
TEST(ExportFormats, TheCliNamesTheTablesFormats) {
  const std::string preset = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_f.json";
  sylva_run r = run_sylva("", "export " + preset + " -o /tmp/sylva_formats_test.stl");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("use " + export_format_list()), std::string::npos) << r.err;
  r = run_sylva("", "export " + preset + " --lods -o /tmp/sylva_formats_test.json");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--lods writes " + export_format_list(&export_format::lods)), std::string::npos) << r.err;
}
