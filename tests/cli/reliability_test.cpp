// Hostile input: UTF-8 at the entrances, bounded reads, preset caps, whole-sweep
// validation, writes through symlinks, and CLI behaviour on bad file names.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "render/io/preset.h"
#include "tests/run_sylva.h"
#include "tests/scratch_dir.h"

using namespace sylva;
namespace fs = std::filesystem;

namespace {

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

// ---------------------------------------------------------------- item 2: UTF-8

TEST(Utf8, ValidatorFollowsRfc3629) {
  EXPECT_TRUE(valid_utf8(""));
  EXPECT_TRUE(valid_utf8("plain ASCII"));
  EXPECT_TRUE(valid_utf8("λ σ — 木 \xF0\x9F\x8C\xB3"));  // 2-, 3- and 4-byte forms
  EXPECT_FALSE(valid_utf8("\xFF"));
  EXPECT_FALSE(valid_utf8("\xC0\xAF"));          // overlong '/'
  EXPECT_FALSE(valid_utf8("\xE0\x80\xAF"));      // overlong, 3 bytes
  EXPECT_FALSE(valid_utf8("\xED\xA0\x80"));      // a UTF-16 surrogate
  EXPECT_FALSE(valid_utf8("\xF4\x90\x80\x80"));  // above U+10FFFF
  EXPECT_FALSE(valid_utf8("\xE6\x9C"));          // truncated
  EXPECT_FALSE(valid_utf8("a\x80z"));            // a lone continuation byte
}

TEST(Utf8, SetRefusesBadBytesAndSaveNeverThrows) {
  preset p = default_preset();
  const preset before = p;
  const std::string e = set_preset_param(p, std::string("source=F\xFF"));
  EXPECT_NE(e.find("UTF-8"), std::string::npos) << e;
  EXPECT_EQ(p, before);

  // A document holding bad bytes anyway (the editor's text fields) still saves, and loads back.
  std::get<lsystem_params>(p.spec.params).source = "F\xFF";
  p.name = "bad \xC3";
  p.tags = {"\xFE"};
  std::string text;
  EXPECT_NO_THROW(text = save_preset_json(p));
  preset q;
  const load_result r = load_preset_json(text, q);
  EXPECT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(valid_utf8(q.name));
  EXPECT_EQ(q.name, "bad \xEF\xBF\xBD");
  const sylva_test::scratch_dir scratch("sylva_reliability_utf8");
  const fs::path& dir = scratch.dir;
  EXPECT_EQ(save_preset_file(p, (dir / "p.json").string()), "");
}

TEST(Utf8, LoaderRejectsBadBytesWithAClearError) {
  preset p;
  const load_result r = load_preset_json(std::string("{\"sylva_preset\": 1, \"name\": \"a\xFF\"}"), p);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("UTF-8"), std::string::npos) << r.error;
}

// ---------------------------------------------------------------- item 4: bounded reads

TEST(InputFiles, DevicesAndFifosAreRefusedAtOnce) {
  std::string text = "kept";
  const auto t0 = std::chrono::steady_clock::now();
  std::string e = read_file("/dev/zero", text);
  EXPECT_NE(e.find("not a regular file"), std::string::npos) << e;
  const sylva_test::scratch_dir scratch("sylva_reliability_fifo");
  const fs::path& dir = scratch.dir;
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
}

TEST(InputFiles, SizeLimitsAreEnforced) {
  const sylva_test::scratch_dir scratch("sylva_reliability_size");
  const fs::path& dir = scratch.dir;
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

// ---------------------------------------------------------------- item 5: sweeps checked whole

TEST(Sweep, OutOfRangeValueRefusesTheWholeSweep) {
  preset p = default_preset();
  std::vector<std::string> out;
  const std::string e = expand_param_sweep(p, "derivations=0:30:4", out);
  EXPECT_NE(e.find("value 4 of the sweep"), std::string::npos) << e;
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(expand_param_sweep(p, "derivations=2:4:3", out), "");
  EXPECT_EQ(out.size(), 3u);
  out.clear();
  EXPECT_NE(expand_param_sweep(p, std::string("source=F\xFF"), out), "");  // plain values are checked too
  EXPECT_TRUE(out.empty());
}

TEST(Sweep, CliWritesNothingWhenAnyValueIsBad) {
  const sylva_test::scratch_dir scratch("sylva_reliability_sweep");
  const fs::path& dir = scratch.dir;
  const std::string preset_path = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";
  const sylva_run r = run_sylva("", "export '" + preset_path + "' -o '" + (dir / "t.json").string() +
                                        "' --set derivations=0:30:4");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("derivations"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir));
}

// ---------------------------------------------------------------- item 6: symlinks and permissions

TEST(AtomicWrite, KeepsPermissionsAndWritesThroughSymlinks) {
  const sylva_test::scratch_dir scratch("sylva_reliability_links");
  const fs::path& dir = scratch.dir;
  const fs::path file = dir / "private.obj";
  write_text(file, "old");
  ASSERT_EQ(::chmod(file.c_str(), 0600), 0);
  ASSERT_EQ(write_file_atomic(file.string(), "new"), "");
  struct stat st {};
  ASSERT_EQ(::stat(file.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  EXPECT_EQ(read_text(file), "new");

  // A relative link in another folder, to a link, to the file: both links stay links.
  fs::create_directories(dir / "sub");
  fs::create_symlink("../private.obj", dir / "sub" / "near.obj");
  fs::create_symlink("sub/near.obj", dir / "far.obj");
  ASSERT_EQ(write_file_atomic((dir / "far.obj").string(), "through"), "");
  EXPECT_TRUE(fs::is_symlink(dir / "far.obj"));
  EXPECT_TRUE(fs::is_symlink(dir / "sub" / "near.obj"));
  EXPECT_EQ(read_text(file), "through");
  ASSERT_EQ(::stat(file.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);

  // A dangling link creates its target; a loop is an error, not a hang.
  fs::create_symlink("made.obj", dir / "dangling.obj");
  ASSERT_EQ(write_file_atomic((dir / "dangling.obj").string(), "made"), "");
  EXPECT_TRUE(fs::is_symlink(dir / "dangling.obj"));
  EXPECT_EQ(read_text(dir / "made.obj"), "made");
  fs::create_symlink("loop_b", dir / "loop_a");
  fs::create_symlink("loop_a", dir / "loop_b");
  EXPECT_NE(write_file_atomic((dir / "loop_a").string(), "x"), "");
  size_t temporaries = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    temporaries += e.path().filename().string().find(".tmp-") != std::string::npos;
  EXPECT_EQ(temporaries, 0u);
}

// ---------------------------------------------------------------- items 7, 8: versions and caps

TEST(PresetLimits, HugeVersionIsReportedAsItIs) {
  preset p;
  load_result r = load_preset_json(R"({"sylva_preset": 18446744073709551615, "generator": "lsystem"})", p);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings[0].find("18446744073709551615"), std::string::npos) << r.warnings[0];
  r = load_preset_json(R"({"sylva_preset": -1})", p);
  EXPECT_NE(r.error.find("-1 is not valid"), std::string::npos) << r.error;
}

TEST(PresetLimits, TagsListsAndTextAreCapped) {
  auto load = [](const nlohmann::json& doc) {
    preset p;
    return load_preset_json(doc.dump(), p);
  };
  nlohmann::json doc = {{"sylva_preset", 1}, {"generator", "self_organizing"}};
  doc["tags"] = std::vector<std::string>(max_preset_tags + 1, "t");
  load_result r = load(doc);
  EXPECT_NE(r.error.find("tags: 1001 tags"), std::string::npos) << r.error;
  doc["tags"] = std::vector<std::string>(max_preset_tags, "t");
  EXPECT_TRUE(load(doc).ok);

  doc["params"]["positions"] = std::vector<std::vector<float>>(max_preset_list + 1, {0.f, 0.f, 0.f});
  r = load(doc);
  EXPECT_NE(r.error.find("params.positions"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("limit"), std::string::npos) << r.error;
  doc["params"].erase("positions");

  doc["name"] = std::string(max_preset_text_bytes + 1, 'x');
  r = load(doc);
  EXPECT_NE(r.error.find("1 MB limit"), std::string::npos) << r.error;
  doc["name"] = "ok";

  // Many small values: refused before the document is built.
  std::string many = R"({"sylva_preset": 1, "x": [)";
  for (size_t i = 0; i <= max_preset_values; ++i) many += "0,";
  many += "0]}";
  preset p;
  r = load_preset_json(many, p);
  EXPECT_NE(r.error.find("more than 1000000 values"), std::string::npos) << r.error;
  r = load_preset_json(std::string(100, '[') + std::string(100, ']'), p);
  EXPECT_NE(r.error.find("nested deeper"), std::string::npos) << r.error;

  preset q = default_preset();
  EXPECT_NE(set_preset_param(q, "source=" + std::string(max_preset_text_bytes + 1, 'F')), "");
}

// ---------------------------------------------------------------- item 3: bench and bad names

TEST(BenchCli, NonUtf8FileNameIsReportedAndTheRunGoesOn) {
  const sylva_test::scratch_dir scratch("sylva_reliability_bench");
  const fs::path& dir = scratch.dir;
  const std::string source = read_text(fs::path(SYLVA_SOURCE_DIR) / "presets" / "lsystem_honda_a.json");
  const fs::path bad = dir / "tree_\xFF\xFE.json", good = dir / "tree_good.json";
  write_text(bad, source);
  write_text(good, source);
  const sylva_run r =
      run_sylva("", "bench --json --repeat 1 " + shell_quote(bad.string()) + " " + shell_quote(good.string()));
  EXPECT_EQ(r.code, 0) << r.err;
  std::vector<nlohmann::json> lines;
  std::istringstream in(r.out);
  for (std::string line; std::getline(in, line);) {
    ASSERT_TRUE(nlohmann::json::accept(line)) << line;
    lines.push_back(nlohmann::json::parse(line));
  }
  ASSERT_EQ(lines.size(), 2u) << r.out << r.err;
  EXPECT_EQ(lines[0]["preset"], "tree_\xEF\xBF\xBD\xEF\xBF\xBD");
  EXPECT_EQ(lines[1]["preset"], "tree_good");
  EXPECT_GT(lines[1]["nodes"].get<int>(), 0);
}

TEST(BenchCli, MissingFileMessageNamesTheProgram) {
  const sylva_run r = run_sylva("", "bench --json --repeat 1 /nonexistent-sylva/\xFF.json");
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err.rfind("sylva bench: ", 0), 0u) << r.err;
}

// An export whose file name is not UTF-8: the glTF's URIs are percent-encoded, the JSON never
// throws, and every file it names is there.
TEST(Utf8, GltfExportToANonUtf8NameWritesValidJson) {
  const sylva_test::scratch_dir scratch("sylva_reliability_gltf_name");
  const fs::path& dir = scratch.dir;
  const std::string preset_path = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";
  const std::string name = std::string("tr\xFF") + "e.gltf";
  const sylva_run r = run_sylva("", "export '" + preset_path + "' -o '" + (dir / name).string() + "'");
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream f(dir / name, std::ios::binary);
  const auto j = nlohmann::json::parse(f, nullptr, false);
  ASSERT_FALSE(j.is_discarded());
  ASSERT_TRUE(j.contains("buffers"));
  EXPECT_NE(j["buffers"][0]["uri"].get<std::string>().find("%FF"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / (std::string("tr\xFF") + "e.bin")));
}
