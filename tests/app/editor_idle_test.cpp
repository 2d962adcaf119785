// An editor with nothing to do waits for events and draws nothing; wind and playback keep it
// drawing, and the status bar says so (docs/design/09-editor.md "An editor that idles"). Measured
// end to end under Xvfb (SYLVA_SCRIPT's `idle S MAX`: CPU time of every thread over S seconds).
// While the user drags, the view is drawn cheaper, and an unchanged view is not drawn again
// ("Responsive on software GL").
#include <gtest/gtest.h>

#include <cstdlib>
#include <regex>
#include <string>
#include <vector>

#include "editor_script_run.h"

namespace {

using sylva_test::have_display;
using sylva_test::run_result;
using sylva_test::run_script;
using sylva_test::script_passed;

struct idle_line {
  double seconds, cpu, share;
  long frames;
  std::string drawing_for;
};

// Every "idle" report of a script's output, in order.
std::vector<idle_line> idle_reports(const std::string& out) {
  std::vector<idle_line> lines;
  const std::regex re(R"(idle ([0-9.]+) s: CPU ([0-9.]+) s, ([0-9.]+) % of a core, ([0-9]+) frames drawn(; drawing for ([a-z ]+))?)");
  for (auto it = std::sregex_iterator(out.begin(), out.end(), re); it != std::sregex_iterator(); ++it)
    lines.push_back({std::atof((*it)[1].str().c_str()), std::atof((*it)[2].str().c_str()), std::atof((*it)[3].str().c_str()),
                     std::atol((*it)[4].str().c_str()), (*it)[6].str()});
  return lines;
}

}  // namespace

// The oak (the first view a newcomer meets), left alone: once its tree and levels of detail have
// arrived and three seconds passed, no frame is drawn and the process uses under 5 % of a core.
// With the wind on, every frame is drawn, and the status bar names the wind.
TEST(EditorIdle, AnIdleEditorDrawsNothingUntilTheWindBlows) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const std::string script = R"(wait_tree
wait_quiet
idle 3
idle 4 5
set render.wind=true
idle 2
set render.wind=false
idle 3
idle 2 5
)";
  const run_result r = run_script("idle", script, std::string(SYLVA_SOURCE_DIR) + "/presets/species_oak.json");
  ASSERT_TRUE(script_passed(r));
  const std::vector<idle_line> idle = idle_reports(r.output);
  ASSERT_EQ(idle.size(), 5u) << r.output;
  EXPECT_EQ(idle[1].frames, 0) << r.output;
  EXPECT_EQ(idle[1].drawing_for, "") << r.output;
  EXPECT_LT(idle[1].share, 5.0) << r.output;
  EXPECT_GE(idle[1].seconds, 4.0) << r.output;
  // The wind draws every frame (at llvmpipe's pace on a loaded machine, one a few seconds) and says why.
  EXPECT_GE(idle[2].frames, 1) << r.output;
  EXPECT_EQ(idle[2].drawing_for, "wind") << r.output;
  // Wind off: quiet again.
  EXPECT_EQ(idle[4].frames, 0) << r.output;
  EXPECT_LT(idle[4].share, 5.0) << r.output;
}

// While the user orbits, the view is drawn cheaper (half resolution, no shafts, the last shadow
// map) and the camera moves; frames in which nothing in the picture changed (the script stepping,
// a hover, a menu) show the last full picture again instead of drawing it.
TEST(EditorIdle, AnOrbitDrawsCheaperAndAnUnchangedViewIsShownAgain) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const std::string script = R"(wait_tree
wait_quiet
frame_median 5
expect_kept_frames_over 3
expect_cheap_frames 0
remember_camera
orbit 6
expect_camera moved
)";
  const run_result r = run_script("orbit", script, std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json");
  ASSERT_TRUE(script_passed(r));
  const std::regex re(R"(orbit: frame median [0-9.]+ ms over [0-9]+ frames, ([0-9]+) drawn cheaper)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.output, m, re)) << r.output;
  EXPECT_GE(std::atoi(m[1].str().c_str()), 6) << r.output;   // every frame of the drag
}
