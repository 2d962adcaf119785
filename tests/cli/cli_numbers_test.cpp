// Every float option of every command refuses NaN and infinity by name, before anything is written
// (add_float_option, app/cli/cli_options.h); the batch limit is named when --seeds is too long.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "tests/run_sylva.h"

namespace fs = std::filesystem;

namespace {

sylva_run sylva(const std::string& args) { return run_sylva("env -u DISPLAY -u WAYLAND_DISPLAY", args); }

std::string honda_a() { return (fs::path(SYLVA_SOURCE_DIR) / "presets" / "lsystem_honda_a.json").string(); }

// The options a command's --help lists as FLOAT.
std::vector<std::string> float_options(const std::string& command) {
  const sylva_run r = sylva(command + " --help");
  EXPECT_EQ(r.code, 0) << r.err;
  std::vector<std::string> names;
  const std::regex option(R"((--[a-z][a-z-]*) FLOAT)");
  for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), option); it != std::sregex_iterator(); ++it)
    names.push_back((*it)[1]);
  return names;
}

}  // namespace

TEST(CliNumbers, EveryFloatOptionRefusesNanAndInfinityByName) {
  const fs::path dir = fs::temp_directory_path() / ("sylva_cli_numbers_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path out = dir / "a.glb";
  std::set<std::string> seen;
  for (const std::string command : {"export", "bench", "textures"}) {
    for (const std::string& option : float_options(command)) {
      seen.insert(command + " " + option);
      // 1e39 is beyond a float: read as CLI11 reads it, it is infinite too.
      for (const char* value : {"nan", "NaN", "inf", "-inf", "infinity", "1e39"}) {
        SCOPED_TRACE(command + " " + option + " " + value);
        const std::string args = command == "export" ? "export " + honda_a() + " -o " + out.string() + " --animation " : command + " ";
        const sylva_run r = sylva(args + option + " " + value);
        EXPECT_EQ(r.code, 2) << r.err;
        EXPECT_NE(r.err.find(option + ": "), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("is not a finite number"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out));
      }
    }
  }
  // The walk found the float options there are; a new one joins it through its --help line.
  EXPECT_TRUE(seen.count("export --seconds-per-step")) << seen.size();
  EXPECT_TRUE(seen.count("export --wind")) << seen.size();
  // A finite value still passes, and one outside the range is refused by the range.
  EXPECT_EQ(sylva("export " + honda_a() + " -o " + out.string() + " --animation --seconds-per-step 0.25").code, 0);
  EXPECT_TRUE(fs::exists(out));
  const sylva_run r = sylva("export " + honda_a() + " -o " + out.string() + " --animation --seconds-per-step 100");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--seconds-per-step"), std::string::npos) << r.err;
  std::error_code ec;
  fs::remove_all(dir, ec);
}

TEST(CliNumbers, SeedsPastTheBatchLimitSayWhatTheLimitIs) {
  const fs::path out = fs::temp_directory_path() / ("sylva_cli_seeds_" + std::to_string(::getpid()) + ".json");
  sylva_run r = sylva("export " + honda_a() + " -o " + out.string() + " --seeds 1-1000000000");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("1000000000 seeds"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("at most 100000 files"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("A <= B"), std::string::npos) << r.err;   // the range is well formed
  EXPECT_FALSE(fs::exists(out));
  // The whole 64-bit range is counted without wrapping.
  r = sylva("export " + honda_a() + " -o " + out.string() + " --seeds 0-18446744073709551615");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("18446744073709551616 seeds"), std::string::npos) << r.err;
  // A reversed range is still told as such.
  r = sylva("export " + honda_a() + " -o " + out.string() + " --seeds 5-2");
  EXPECT_NE(r.err.find("A <= B"), std::string::npos) << r.err;
  // Seeds times a sweep past the limit: the count and the limit.
  r = sylva("export " + honda_a() + " -o " + out.string() + " --seeds 1-200 --set r1=0.5:0.9:1000");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("at most 100000 files"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}
