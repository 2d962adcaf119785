// Hostile input (issue 15): UTF-8 at the entrances, bounded reads, preset caps, whole-sweep
// validation, writes through symlinks, and CLI behaviour on bad file names.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "render/files.h"
#include "tests/run_sylva.h"

using namespace sylva;
namespace fs = std::filesystem;

namespace {

fs::path scratch_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("sylva_reliability_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

[[maybe_unused]] void write_text(const fs::path& p, const std::string& s) {
  std::ofstream f(p, std::ios::binary);
  f << s;
}

[[maybe_unused]] std::string read_text(const fs::path& p) {
  std::string s;
  EXPECT_EQ(read_file(p.string(), s), "");
  return s;
}

[[maybe_unused]] std::string shell_quote(const std::string& s) {
  std::string r = "'";
  for (char c : s) r += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return r + "'";
}

[[maybe_unused]] double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

// ---------------------------------------------------------------- item 4: bounded reads

TEST(InputFiles, DevicesAndFifosAreRefusedAtOnce) {
  std::string text = "kept";
  const auto t0 = std::chrono::steady_clock::now();
  std::string e = read_file("/dev/zero", text);
  EXPECT_NE(e.find("not a regular file"), std::string::npos) << e;
  const fs::path dir = scratch_dir("fifo");
  const fs::path fifo = dir / "pipe.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  e = read_file(fifo.string(), text);  // no writer: must neither block nor read
  EXPECT_NE(e.find("not a regular file"), std::string::npos) << e;
  preset p;
  load_result r = load_preset_file("/dev/zero", p);
  EXPECT_NE(r.error.find("not a regular file"), std::string::npos) << r.error;
  EXPECT_NE(read_file(dir.string(), text).find("folder"), std::string::npos);

  space_colonization_params sc;
  sc.envelope = envelope_shape::mesh;
  sc.points = 100;
  for (const std::string& path : {std::string("/dev/zero"), fifo.string(), dir.string()}) {
    sc.envelope_mesh = path;
    const envelope_sample s = sample_envelope(sc, 1);
    EXPECT_NE(s.error.find("not a regular file"), std::string::npos) << path << ": " << s.error;
  }
  EXPECT_LT(seconds_since(t0), 2.0);
  EXPECT_EQ(text, "kept");
  fs::remove_all(dir);
}

TEST(InputFiles, SizeLimitsAreEnforced) {
  const fs::path dir = scratch_dir("size");
  const fs::path big = dir / "big.json";
  {  // sparse: the size is there without writing the bytes
    std::ofstream f(big, std::ios::binary);
  }
  fs::resize_file(big, max_preset_bytes + 1);
  preset p;
  const load_result r = load_preset_file(big.string(), p);
  EXPECT_NE(r.error.find("64 MB limit"), std::string::npos) << r.error;
  std::string text;
  EXPECT_EQ(read_file(big.string(), text), "");  // within the 256 MB asset limit
  EXPECT_EQ(text.size(), max_preset_bytes + 1);
  text.clear();
  fs::resize_file(big, max_asset_bytes + 1);
  EXPECT_NE(read_file(big.string(), text).find("256 MB limit"), std::string::npos);
  EXPECT_TRUE(text.empty());

  space_colonization_params sc;
  sc.envelope = envelope_shape::mesh;
  sc.envelope_mesh = big.string();
  EXPECT_NE(sample_envelope(sc, 1).error.find("256 MB limit"), std::string::npos);
  fs::remove_all(dir);
}

TEST(InputFiles, EnvelopeObjParsesFromText) {
  const std::string tet = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  std::vector<bool> inside;
  EXPECT_EQ(check_envelope_obj(tet, {{-0.5f, -0.5f, -0.5f}, {0.9f, 0.9f, 0.9f}}, &inside), "");
  EXPECT_EQ(inside, (std::vector<bool>{true, false}));
  EXPECT_NE(check_envelope_obj("v 0 0 0\nf 1 2 3\n"), "");
  EXPECT_NE(check_envelope_obj("v -3e38 0 0\nv 3e38 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"),
            "");  // an extent beyond float's range is refused, not divided by
}

