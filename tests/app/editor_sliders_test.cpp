// The panel's sliders: a short drag moves a wide-range parameter a little, Shift less, ranges
// spanning decades are logarithmic, and values print with their unit and sensible digits.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "app/editor/editor_sliders.h"
#include "generators/space_colonization.h"

using namespace sylva;

namespace {

param_info info_of(const char* key) {
  space_colonization_params p{};
  param_info found{};
  visit_params(p, [&](auto&, const param_info& info) {
    if (std::string(info.key) == key) found = info;
  });
  return found;
}

}  // namespace

TEST(EditorSliders, AShortDragMovesAWideRangeALittle) {
  const param_info di = info_of("influence_radius");
  ASSERT_NE(di.key, nullptr);
  // A 40-pixel drag: a linear ImGui slider 200 px wide would jump a fifth of the range.
  const float drag = 40 * drag_speed(di, false), fine = 40 * drag_speed(di, true);
  EXPECT_LT(drag, 0.08f * (di.max - di.min));   // of the (log) scale
  EXPECT_NEAR(fine, drag / 10, 1e-6f);
  const param_info dk = info_of("kill_distance");   // 0..50: linear, 2.4 moves to at most 5.7 in 40 px
  EXPECT_FALSE(slider_is_log(dk));
  EXPECT_LT(40 * drag_speed(dk, false), 3.4f);
}

TEST(EditorSliders, DecadesAreLogarithmicAndFormatsCarryUnits) {
  const param_info tip{"min_width", "Tip radius", "W", 0.0001f, 1, "Radius of a branch tip in metres"};
  EXPECT_TRUE(slider_is_log(tip));
  EXPECT_EQ(param_unit(tip), " m");
  const param_info angle{"fork_angle", "Fork angle", "", 0, 180, "Angle", param_degrees};
  EXPECT_FALSE(slider_is_log(angle));
  EXPECT_EQ(slider_format(angle), "%.1f°");
  const param_info share{"share", "Share", "", 0, 1, "A share"};
  EXPECT_FALSE(slider_is_log(share));
  char b[32];
  std::snprintf(b, sizeof b, slider_format(share).c_str(), 0.123456);
  EXPECT_STREQ(b, "0.123");
  const param_info length{"trunk_length", "Trunk length", "", 0, 50, "Trunk height (metres)"};
  std::snprintf(b, sizeof b, slider_format(length).c_str(), 16.946999);
  EXPECT_STREQ(b, "16.9 m");
  const param_info pct{"lod1_budget", "LOD1 budget", "", 1, 100, "Triangles of LOD1 in percent of LOD0"};
  std::snprintf(b, sizeof b, slider_format(pct).c_str(), 42.0);
  EXPECT_EQ(std::string(b).back(), '%');
}
