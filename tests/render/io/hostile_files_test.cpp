// Hostile files: outputs onto FIFOs, devices, symlinks, folders, read-only folders, a full disk and
// 255-byte names; inputs from folders, /dev/zero, FIFOs and a 60 MB preset. Each failing case
// gives a clear message and a non-zero exit, stays within bounded memory, and leaves every file the
// user had byte for byte as it was. Also: malformed user textures fall back, sweeps with keyframes
// are checked whole before anything is written.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <climits>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include "render/io/export.h"
#include "render/files.h"
#include "render/io/preset.h"
#include "render/assets/textures.h"
#include "tests/run_sylva.h"
#include "tests/scratch_dir.h"

using namespace sylva;
namespace fs = std::filesystem;

namespace {

struct scratch : sylva_test::scratch_dir {
  explicit scratch(const std::string& name) : scratch_dir("sylva_hostile_" + name) {}
};

void write_text(const fs::path& p, const std::string& s) { std::ofstream(p, std::ios::binary) << s; }

// Everything under `dir` as the user would see it: each entry's kind, and a regular file's bytes
// or a link's target; compared whole before and after a failing command.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> s;
  for (auto it = fs::recursive_directory_iterator(dir, fs::directory_options::skip_permission_denied);
       it != fs::recursive_directory_iterator(); ++it) {
    struct stat st {};
    if (::lstat(it->path().c_str(), &st) != 0) continue;
    std::string what = std::string(file_kind(st.st_mode)) + " mode " + std::to_string(st.st_mode & 07777) + ": ";
    if (S_ISREG(st.st_mode)) {
      std::ifstream f(it->path(), std::ios::binary);
      what += std::string(std::istreambuf_iterator<char>(f), {});
    } else if (S_ISLNK(st.st_mode)) {
      what += fs::read_symlink(it->path()).string();
    } else if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) {
      what += std::to_string(st.st_rdev);
    }
    s[it->path().lexically_relative(dir).string()] = what;
  }
  return s;
}

// The entries that differ, named with their kind (a failure message, not the files' bytes).
std::string differences(const std::map<std::string, std::string>& before, const std::map<std::string, std::string>& after) {
  std::string d;
  auto kind = [](const std::string& v) { return v.substr(0, v.find(':')); };
  for (const auto& [name, v] : before)
    if (auto it = after.find(name); it == after.end()) d += "  removed " + name + " (" + kind(v) + ")\n";
    else if (it->second != v) d += "  changed " + name + ": " + kind(v) + " -> " + kind(it->second) + "\n";
  for (const auto& [name, v] : after)
    if (!before.count(name)) d += "  added " + name + " (" + kind(v) + ")\n";
  return d;
}

std::string quoted(const std::string& s) {
  std::string r = "'";
  for (char c : s) r += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return r + "'";
}

const std::string honda = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";

// The largest resident set of any child waited for so far, in MB (each test runs in its own
// process under ctest, so these are this test's commands).
long children_peak_mb() {
  struct rusage u {};
  ::getrusage(RUSAGE_CHILDREN, &u);
  return u.ru_maxrss / 1024;
}

// A failing export: non-zero exit, "sylva export: ..." naming `expect`, and nothing changed in `dir`.
void expect_refused(const scratch& s, const std::string& env, const std::string& args, const std::string& expect) {
  SCOPED_TRACE(args);
  const auto before = snapshot(s.dir);
  const sylva_run r = run_sylva(env, args);
  EXPECT_NE(r.code, 0) << r.err;
  EXPECT_EQ(r.err.rfind("sylva export: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
  const auto after = snapshot(s.dir);
  EXPECT_TRUE(after == before) << "files changed:\n" << differences(before, after);
}

}  // namespace

// ---------------------------------------------------------------- outputs

TEST(HostileOutput, SpecialFilesAreNeverReplaced) {
  scratch s("special");
  ASSERT_EQ(::mkfifo((s / "pipe.glb").c_str(), 0600), 0);
  std::string e = write_file_atomic(s / "pipe.glb", "bytes");
  EXPECT_NE(e.find("a FIFO (named pipe)"), std::string::npos) << e;
  fs::create_symlink("pipe.glb", s / "to_pipe.glb");
  e = write_file_atomic(s / "to_pipe.glb", "bytes");
  EXPECT_NE(e.find("FIFO"), std::string::npos) << e;
  EXPECT_NE(e.find("symbolic link leads to"), std::string::npos) << e;
  fs::create_directory(s / "folder.glb");
  EXPECT_NE(write_file_atomic(s / "folder.glb", "bytes").find("a folder"), std::string::npos);
  EXPECT_TRUE(fs::is_fifo(s / "pipe.glb"));
  EXPECT_TRUE(fs::is_symlink(s / "to_pipe.glb"));

  // Through a link to /dev/null: only staged (a broken check would then leave a temporary in /dev,
  // discarded here, rather than replace the device).
  fs::create_symlink("/dev/null", s / "to_null.obj");
  staged_write w;
  e = stage_file(s / "to_null.obj", "bytes", w);
  if (e.empty()) discard_staged(w);
  EXPECT_NE(e.find("a character device"), std::string::npos) << e;
  EXPECT_NE(e.find("/dev/null"), std::string::npos) << e;
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST(HostileOutput, CliRefusesFifosDevicesLinksAndFolders) {
  scratch s("cli_special");
  write_text(s / "keep.glb", "the user's own file");
  ASSERT_EQ(::mkfifo((s / "pipe.glb").c_str(), 0600), 0);
  fs::create_symlink("pipe.glb", s / "to_pipe.glb");
  fs::create_directory(s / "folder.glb");
  write_text(s / "folder.glb/inside.txt", "kept");
  const std::string exp = "export " + quoted(honda) + " -o ";
  expect_refused(s, "", exp + quoted(s / "pipe.glb"), "is a FIFO (named pipe), not a regular file");
  expect_refused(s, "", exp + quoted(s / "to_pipe.glb"), "FIFO");
  expect_refused(s, "", exp + quoted(s / "folder.glb"), "is a folder");
  // A character device of its own (root only: mknod), so that a broken check replaces nothing real.
  if (::mknod((s / "device.obj").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) {
    fs::create_symlink("device.obj", s / "to_device.obj");
    expect_refused(s, "", exp + quoted(s / "device.obj"), "a character device");
    expect_refused(s, "", exp + quoted(s / "to_device.obj"), "a character device");
  }
  // An OBJ writes several files: one refused target stages none of them.
  ASSERT_EQ(::mkfifo((s / "multi.mtl").c_str(), 0600), 0);
  expect_refused(s, "", exp + quoted(s / "multi.obj"), "multi.mtl: it is a FIFO");
  EXPECT_LT(children_peak_mb(), 1024);
}

TEST(HostileOutput, ReadOnlyFolderAndFullDiskChangeNothing) {
  scratch s("readonly");
  fs::create_directory(s / "ro");
  write_text(s / "ro/tree.glb", "old export");
  ASSERT_EQ(::chmod((s / "ro").c_str(), 0555), 0);
  const std::string exp = "export " + quoted(honda) + " -o ";
  // Root writes anywhere: the read-only case runs as nobody where setpriv can drop privileges.
  std::string as_user;
  if (::getuid() == 0)
    as_user = std::system("setpriv --reuid=65534 --regid=65534 --clear-groups true 2>/dev/null") == 0
                  ? "setpriv --reuid=65534 --regid=65534 --clear-groups"
                  : "skip";
  if (as_user != "skip") expect_refused(s, as_user, exp + quoted(s / "ro/tree.glb"), "Permission denied");
  ASSERT_EQ(::chmod((s / "ro").c_str(), 0755), 0);

  // A full disk: RLIMIT_FSIZE (the shell's ulimit -f, 512-byte blocks) makes write() fail with
  // EFBIG once the file reaches 1 KB, as ENOSPC would; SIGXFSZ is ignored so the write returns.
  write_text(s / "full.glb", "old export");
  write_text(s / "full.obj", "old obj");
  expect_refused(s, "trap '' XFSZ; ulimit -f 2;", exp + quoted(s / "full.glb"), "write failed: File too large");
  expect_refused(s, "trap '' XFSZ; ulimit -f 2;", exp + quoted(s / "full.obj"), "write failed: File too large");
  // A real full disk where a small tmpfs can be mounted (root, with the capability).
  fs::create_directory(s / "tmpfs");
  if (::getuid() == 0 &&
      std::system(("mount -t tmpfs -o size=64k sylva_test " + quoted(s / "tmpfs") + " 2>/dev/null").c_str()) == 0) {
    write_text(s / "tmpfs/tree.glb", "old export");
    expect_refused(s, "", exp + quoted(s / "tmpfs/tree.glb"), "No space left on device");
    EXPECT_EQ(std::system(("umount " + quoted(s / "tmpfs")).c_str()), 0);
  }
  EXPECT_LT(children_peak_mb(), 1024);
}

TEST(HostileOutput, LongNamesUseAShortTemporary) {
  scratch s("names");
  const std::string name255 = std::string(NAME_MAX - 4, 'n') + ".glb";   // the longest legal name
  ASSERT_EQ(name255.size(), 255u);
  ASSERT_EQ(write_file_atomic(s / name255, "first"), "");
  ASSERT_EQ(write_file_atomic(s / name255, "second"), "");
  std::ifstream f(s / name255, std::ios::binary);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(f), {}), "second");
  staged_write w;
  ASSERT_EQ(stage_file(s / name255, "x", w), "");
  EXPECT_EQ(fs::path(w.temp).parent_path(), s.dir);
  EXPECT_LT(fs::path(w.temp).filename().string().size(), 40u) << w.temp;
  discard_staged(w);

  const sylva_run r = run_sylva("", "export " + quoted(honda) + " -o " + quoted(s / ("t" + name255.substr(1))));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_GT(fs::file_size(s / ("t" + name255.substr(1))), 1000u);
  // 256 bytes is over the limit: refused by the system, said clearly, nothing left behind.
  expect_refused(s, "", "export " + quoted(honda) + " -o " + quoted(s / ("x" + name255)), "File name too long");
  EXPECT_EQ(std::distance(fs::directory_iterator(s.dir), fs::directory_iterator()), 2);   // the two 255-byte files
}

// ---------------------------------------------------------------- textures

// An 18-byte PGM whose header gives a width of 0: stb "decodes" it, so the check must come after.
TEST(HostileInput, EmptyPgmTextureFallsBackWithTheWarning) {
  scratch s("pgm");
  write_text(s / "zero.pgm", std::string("P5\n0 1\n255\n\0\0\0\0\0\0\0", 18));
  ASSERT_EQ(fs::file_size(s / "zero.pgm"), 18u);
  image img;
  EXPECT_NE(decode_user_texture(std::string("P5\n0 1\n255\n\0\0\0\0\0\0\0", 18), img), "");
  EXPECT_NE(decode_png(std::string("P5\n0 1\n255\n\0\0\0\0\0\0\0", 18), img), "");
  for (const char* key : {"leaf_texture", "bark_texture"}) {
    SCOPED_TRACE(key);
    const sylva_run r = run_sylva("", "export " + quoted(honda) + " -o " + quoted(s / "t.glb") + " --set " + key + "=" +
                                          quoted(s / "zero.pgm"));
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("warning: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(s / "zero.pgm"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("using the procedural"), std::string::npos) << r.err;
    EXPECT_GT(fs::file_size(s / "t.glb"), 1000u);
  }
}

// Found by fuzz_texture: Debian's stb read past the end of a 16-bit PGM cut short (a crash); such
// files are refused before stb sees them, 8-bit ones with all their pixels still load.
TEST(HostileInput, PnmFilesAreCheckedBeforeDecoding) {
  image img;
  EXPECT_NE(decode_user_texture("P5999\n589\n999P", img).find("malformed PNM header"), std::string::npos);
  EXPECT_NE(decode_user_texture("P5 2 2 999\n\x01\x02\x03", img).find("999 levels (only 8-bit PNM"), std::string::npos);
  EXPECT_NE(decode_user_texture("P5 4 4 255\n\x01\x02", img).find("cut short"), std::string::npos);
  EXPECT_NE(decode_user_texture("P6 4", img).find("malformed PNM header"), std::string::npos);
  EXPECT_EQ(decode_user_texture("P5\n# a comment\n2 1\n255\n\x10\x20", img), "");
  EXPECT_EQ(img.width, 2);
  EXPECT_EQ(img.pixels[4], 0x20);
}

// Found by fuzz_keys: a branch cut given a size (or a brush a reach) kept a value it never saves,
// so the preset did not load back equal. The unused field is now ignored with a warning.
TEST(HostileInput, CutFieldsOfTheOtherShapeAreIgnoredWithAWarning) {
  preset p;
  const load_result r = load_preset_json(R"({"sylva_preset": 1, "generator": "self_organizing", "cuts": [
      {"step": 2, "point": [0, 1, 0], "size": [2, 3, 2]},
      {"step": 3, "shape": "outside_box", "point": [0, 2, 0], "size": [1, 1, 1], "reach": 4}]})", p);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.warnings.size(), 2u);
  EXPECT_NE(r.warnings[0].find("cuts[0].size: a branch cut has a reach"), std::string::npos) << r.warnings[0];
  EXPECT_NE(r.warnings[1].find("cuts[1].reach: a brush has a size"), std::string::npos) << r.warnings[1];
  preset q;
  ASSERT_TRUE(load_preset_json(save_preset_json(p), q).ok);
  EXPECT_EQ(p, q);
}

// ---------------------------------------------------------------- sweeps

// Later variants (fewer steps) strand the keyframe past their last step: it is kept, inactive, and
// each such variant says so; a keyframe no variant can hold (past the steps' range) writes nothing.
TEST(HostileInput, SweepWithAKeyframeWritesNothingWhenAnyVariantRefusesIt) {
  scratch s("sweep_key");
  write_text(s / "t-1.json", "the user's own file");
  const std::string preset = std::string(SYLVA_SOURCE_DIR) + "/presets/self_organizing_seed001_bush.json";
  expect_refused(s, "", "export " + quoted(preset) + " -o " + quoted(s / "t.json") + " --set steps=20:2:3 --set lambda@201=0.5",
                 "lambda@201");
  const sylva_run ok = run_sylva("", "export " + quoted(preset) + " -o " + quoted(s / "k.json") +
                                         " --set steps=12:2:3 --set lambda@10=0.5");
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_TRUE(fs::exists(s / "k-1.json") && fs::exists(s / "k-2.json") && fs::exists(s / "k-3.json"));
  EXPECT_NE(ok.err.find("k-3.json: 1 keyframe or cut lies past the last step (2)"), std::string::npos) << ok.err;
  EXPECT_EQ(ok.err.find("k-1.json: 1 keyframe"), std::string::npos) << ok.err;
}

// ---------------------------------------------------------------- inputs

TEST(HostileInput, FoldersDevicesFifosAndHugePresetsAreRefused) {
  scratch s("inputs");
  ASSERT_EQ(::mkfifo((s / "pipe.json").c_str(), 0600), 0);
  fs::create_directory(s / "folder.json");
  {  // 60 MB, under the 64 MB preset limit: read, then refused by the 1 MB text limit
    std::ofstream f(s / "big.json", std::ios::binary);
    f << "{\"sylva_preset\": 1, \"generator\": \"lsystem\", \"name\": \"";
    const std::string block(1 << 20, 'x');
    for (int i = 0; i < 60; ++i) f << block;
    f << "\"}";
  }
  const std::string out = " -o " + quoted(s / "out.glb");
  expect_refused(s, "", "export " + quoted(s / "folder.json") + out, "it is a folder");
  expect_refused(s, "", "export /dev/zero" + out, "not a regular file");
  expect_refused(s, "", "export " + quoted(s / "pipe.json") + out, "not a regular file");   // must not hang
  expect_refused(s, "", "export " + quoted(s / "big.json") + out, "1 MB limit");
  EXPECT_FALSE(fs::exists(s / "out.glb"));
  EXPECT_LT(children_peak_mb(), 1024);   // the 60 MB preset is read once, not copied over and over
}

// A user texture that is a folder, a device or a FIFO: a warning, and the export is written with
// the procedural texture (and a FIFO with no writer does not hang the export).
TEST(HostileInput, SpecialTextureFilesFallBack) {
  scratch s("texture_files");
  ASSERT_EQ(::mkfifo((s / "pipe.png").c_str(), 0600), 0);
  for (const std::string& tex : {s / "pipe.png", std::string("/dev/zero"), s.dir.string()}) {
    SCOPED_TRACE(tex);
    const sylva_run r = run_sylva("", "export " + quoted(honda) + " -o " + quoted(s / "t.glb") + " --set leaf_texture=" + quoted(tex));
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("leaf texture " + tex), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("using the procedural leaves"), std::string::npos) << r.err;
  }
}

// A folder that takes no new files (/proc) and one that does not exist are told apart: open() gives
// "No such file or directory" for both, which read as if /proc were missing.
TEST(HostileOutput, SystemFolderAndMissingFolderAreToldApart) {
  if (fs::is_directory("/proc")) {
    const std::string err = write_file_atomic("/proc/sylva_test_x.glb", "bytes");
    EXPECT_NE(err.find("/proc does not take new files"), std::string::npos) << err;
    EXPECT_EQ(err.find("No such file or directory"), std::string::npos) << err;
  }
  scratch s("missing_folder");
  const std::string missing = s / "not_there/tree.glb";
  const std::string err = write_file_atomic(missing, "bytes");
  EXPECT_NE(err.find("not_there does not exist"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(s / "not_there"));
}
