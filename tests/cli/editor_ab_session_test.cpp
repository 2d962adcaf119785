// A/B comparison in the real editor: under Xvfb, a scripted session duplicates the tree
// into slot B and shows both side by side. Right after the duplicate the two halves of the view are
// the same picture; after an edit of B they differ, and A's document kept its value.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <stb/stb_image.h>
#include <unistd.h>

#include "render/io/preset.h"
#include "tests/scratch_dir.h"

namespace {

namespace fs = std::filesystem;

bool have_display() {
  const char* d = std::getenv("DISPLAY");
  return d && *d;
}

// Fraction of pixels in the view's left half that differ (by more than 30 in a channel) from the
// pixel at the same place in the right half. The view starts right of the 420 px panel, below the
// slot labels, and ends above the timeline and status bar (window 900x400, UI scale 1).
double halves_differ(const std::string& png, int* width = nullptr) {
  int w = 0, h = 0, ch = 0;
  stbi_uc* px = stbi_load(png.c_str(), &w, &h, &ch, 3);
  if (!px) return -1;
  if (width) *width = w;
  const int left = 420, view_w = w - left, half = view_w / 2;
  long differ = 0, total = 0;
  for (int y = 60; y < h - 80; ++y)
    for (int x = 6; x < half - 6; ++x) {
      const stbi_uc* a = px + 3 * (y * w + left + x);
      const stbi_uc* b = px + 3 * (y * w + left + half + x);
      ++total;
      if (std::abs(a[0] - b[0]) > 30 || std::abs(a[1] - b[1]) > 30 || std::abs(a[2] - b[2]) > 30) ++differ;
    }
  stbi_image_free(px);
  return total ? double(differ) / double(total) : -1;
}

}  // namespace

TEST(EditorABSession, SideBySideShowsBothSlotsAndEditsOnlyB) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const sylva_test::scratch_dir scratch("sylva_editor_ab");
  const fs::path& dir = scratch.dir;
  fs::create_directories(dir / "home");
  sylva::preset bush;
  ASSERT_TRUE(sylva::load_preset_file(std::string(SYLVA_SOURCE_DIR) + "/presets/self_organizing_seed001_bush.json", bush).ok);
  bush.mesh.leaves_enabled = false;   // llvmpipe: quick frames
  const std::string preset = (dir / "bush.json").string();
  ASSERT_EQ(sylva::save_preset_file(bush, preset), "");
  const double lambda = std::get<sylva::self_organizing_params>(bush.spec.params).lambda;
  const std::string same = (dir / "same.png").string(), differ = (dir / "differ.png").string();
  std::ofstream(dir / "script.txt") << "wait_tree\nab_duplicate\nab_mode side\nframes 2\nshot " << same
                                    << "\nframes 3\nset lambda=0.42\nwait_tree\nab_wait\nframes 2\nshot " << differ
                                    << "\nframes 3\nab_select a\nexpect_param lambda=" << lambda
                                    << "\nab_select b\nexpect_param lambda=0.42\n"
                                    // Quitting with A selected and clean still asks: B has unsaved changes
                                    // (and its own recovery file). Discard quits and removes both files.
                                    << "expect_recovery_b 1\nab_select a\nexpect_modified 0\nexpect_recovery 0\nquit\n"
                                       "expect_prompt Unsaved changes\nanswer Discard\nnot reached: Discard quits\n";
  const std::string log = (dir / "log.txt").string();
  const std::string cmd = "SYLVA_HOME='" + (dir / "home").string() + "' SYLVA_SCRIPT='" + (dir / "script.txt").string() +
                          "' SYLVA_WINDOW=900x400 SYLVA_UI_SCALE=1 '" + std::string(SYLVA_BINARY) + "' '" + preset +
                          "' > '" + log + "' 2>&1";
  const int status = std::system(cmd.c_str());
  std::ifstream in(log);
  std::stringstream out;
  out << in.rdbuf();
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << out.str();
  EXPECT_NE(out.str().find("ok expect_prompt Unsaved changes"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("the editor closed before line 24"), std::string::npos) << out.str();
  EXPECT_FALSE(fs::exists(dir / "home" / ".recovery_b.json"));
  int w = 0;
  const double d_same = halves_differ(same, &w), d_differ = halves_differ(differ);
  ASSERT_EQ(w, 900) << out.str();
  EXPECT_GE(d_same, 0);
  EXPECT_LT(d_same, 0.002) << "A and B are the same tree: the halves should match";
  EXPECT_GT(d_differ, 0.01) << "B was edited: the halves should differ";
}

// Slot B's unsaved work has its own recovery file, and comes back as slot B on the next start.
TEST(EditorABSession, SlotBsUnsavedWorkIsRecoveredAsSlotB) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const sylva_test::scratch_dir scratch("sylva_editor_ab_recovery");
  const fs::path& dir = scratch.dir;
  fs::create_directories(dir / "home");
  const std::string preset = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";
  auto run = [&](const std::string& script) {
    std::ofstream(dir / "script.txt") << script;
    const std::string log = (dir / "log.txt").string();
    const std::string cmd = "SYLVA_HOME='" + (dir / "home").string() + "' SYLVA_SCRIPT='" + (dir / "script.txt").string() +
                            "' SYLVA_WINDOW=800x500 '" + std::string(SYLVA_BINARY) + "' '" + preset + "' > '" + log + "' 2>&1";
    const int status = std::system(cmd.c_str());
    std::ifstream in(log);
    std::stringstream out;
    out << in.rdbuf();
    return std::make_pair(WIFEXITED(status) ? WEXITSTATUS(status) : -1, out.str());
  };
  // First session: B edited, A untouched; it ends without asking (as a crash would).
  auto [code1, out1] = run("wait_tree\nab_duplicate\nset derivations=7\nwait_tree\nexpect_recovery_b 1\nexpect_recovery 0\n");
  ASSERT_EQ(code1, 0) << out1;
  ASSERT_TRUE(fs::exists(dir / "home" / ".recovery_b.json"));
  // Second: the prompt offers B's work; restored, B holds it (selected, to regrow) and A is as opened.
  auto [code2, out2] = run("expect_prompt Restore unsaved work?\nanswer Restore\nframes 2\nwait_tree\nframes 3\nwait_tree\n"
                           "expect_param derivations=7\nexpect_modified 1\nab_select a\nexpect_param derivations=10\n"
                           "expect_modified 0\n");
  EXPECT_EQ(code2, 0) << out2;
  EXPECT_EQ(out2.find("FAIL"), std::string::npos) << out2;
}
