// `sylva bench --render --ab PRESET_B`: the A/B view's frame timed against a single
// tree's, with the ratio printed. Only that the numbers are there and sane is checked here: the
// timings themselves are reported as medians, never asserted.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/run_sylva.h"

namespace {

bool have_display() {
  const char* d = std::getenv("DISPLAY");
  return d && *d;
}

std::string preset(const char* name) { return "'" + std::string(SYLVA_SOURCE_DIR) + "/presets/" + name + ".json'"; }

}  // namespace

TEST(BenchAB, RenderWithAB_PrintsBothFramesAndTheRatio) {
  if (!have_display()) GTEST_SKIP() << "no DISPLAY";
  const sylva_run r = run_sylva("", "bench --render --preset-light --json --repeat 1 --width 96 --height 64 --ab " +
                                        preset("lsystem_honda_f") + " " + preset("lsystem_honda_a"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out.substr(0, r.out.find('\n')));
  EXPECT_EQ(j["preset"], "lsystem_honda_a");
  EXPECT_EQ(j["preset_b"], "lsystem_honda_f");
  EXPECT_GT(j["triangles_a"].get<double>(), 0);
  EXPECT_GT(j["triangles_b"].get<double>(), 0);
  EXPECT_NE(j["triangles_a"], j["triangles_b"]);   // two different trees were drawn
  for (const char* k : {"single_a_ms", "single_b_ms", "side_by_side_ms", "split_ms", "side_by_side_ratio", "split_ratio",
                    "side_by_side_ratio_heavier", "split_ratio_heavier"})
    EXPECT_GT(j[k].get<double>(), 0) << k;
  EXPECT_NEAR(j["side_by_side_ratio"].get<double>(), j["side_by_side_ms"].get<double>() / j["single_a_ms"].get<double>(), 1e-6);
}

TEST(BenchAB, ABNeedsRenderAndAReadablePresetB) {
  sylva_run r = run_sylva("", "bench --ab " + preset("lsystem_honda_a"));
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--ab times frames"), std::string::npos) << r.err;
  if (!have_display()) return;
  r = run_sylva("", "bench --render --repeat 1 --width 32 --height 32 --ab /nonexistent/b.json " + preset("lsystem_honda_a"));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("/nonexistent/b.json"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
}
