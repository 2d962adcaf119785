// `sylva bench --set KEY=VALUE` (to time the wind's cost): export's assignments, applied
// to every preset benched; a bad key, a sweep or a malformed assignment is refused with a message.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/run_sylva.h"

namespace {

sylva_run sylva(const std::string& args) { return run_sylva("", args); }

const std::string honda = "'" + std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json'";

size_t triangles(const sylva_run& r) {
  return nlohmann::json::parse(r.out.substr(0, r.out.find('\n')))["triangles"].get<size_t>();
}

}  // namespace

TEST(BenchSet, AppliesToEveryPresetBenched) {
  const sylva_run plain = sylva("bench --json --repeat 1 " + honda);
  ASSERT_EQ(plain.code, 0) << plain.err;
  // Two --set, then the presets: each --set takes one value, the paths stay positional.
  const sylva_run set = sylva("bench --json --repeat 1 --set mesh.radial_segments=4 --set render.wind=true " + honda + " " + honda);
  ASSERT_EQ(set.code, 0) << set.err;
  EXPECT_NE(set.err.find("every preset with mesh.radial_segments=4, render.wind=true"), std::string::npos) << set.err;
  EXPECT_LT(triangles(set), triangles(plain));   // 4 sides per ring instead of the preset's 8
  const std::string second = set.out.substr(set.out.find('\n') + 1);
  EXPECT_EQ(nlohmann::json::parse(second.substr(0, second.find('\n')))["triangles"], triangles(set));
}

TEST(BenchSet, BadAssignmentsAreRefusedWithAMessage) {
  const sylva_run unknown = sylva("bench --repeat 1 --set nonsense=3 " + honda);
  EXPECT_EQ(unknown.code, 1);
  EXPECT_NE(unknown.err.find("unknown parameter \"nonsense\""), std::string::npos) << unknown.err;
  const sylva_run range = sylva("bench --repeat 1 --set mesh.radial_segments=999 " + honda);
  EXPECT_EQ(range.code, 1);
  EXPECT_NE(range.err.find("radial_segments"), std::string::npos) << range.err;
  const sylva_run sweep = sylva("bench --repeat 1 --set render.wind_strength=0:1:3 " + honda);
  EXPECT_EQ(sweep.code, 1);
  EXPECT_NE(sweep.err.find("one value per key"), std::string::npos) << sweep.err;
  const sylva_run malformed = sylva("bench --set oops " + honda);
  EXPECT_EQ(malformed.code, 2);
  EXPECT_NE(malformed.err.find("key=value"), std::string::npos) << malformed.err;
  const sylva_run twice = sylva("bench --set s0@2=10 --set s0@2=20 " + honda);
  EXPECT_EQ(twice.code, 2);
  EXPECT_NE(twice.err.find("given twice"), std::string::npos) << twice.err;
}
