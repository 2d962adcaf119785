// ~/Sylva/settings.ini and the recovery files as the editor reads them back at start: checked
// field by field, a bad line ignored with a message, and the editor starting whatever is there.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/editor/editor_settings.h"
#include "tests/scratch_dir.h"

using namespace sylva;
namespace fs = std::filesystem;

namespace {

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& l : v) s += l + "\n";
  return s;
}

// Parses `text`, expecting the defaults (nothing of the line used) and one message holding `why`.
void expect_ignored(const std::string& text, const std::string& why) {
  SCOPED_TRACE(text);
  std::vector<std::string> notes;
  const editor_settings s = parse_settings(text, &notes);
  EXPECT_EQ(s, editor_settings{});
  ASSERT_EQ(notes.size(), 1u) << joined(notes);
  EXPECT_NE(notes[0].find("line 1: "), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find(why), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("; ignored"), std::string::npos) << notes[0];
}

}  // namespace

TEST(EditorSettings, BadWindowLinesAreIgnoredWholeWithAMessage) {
  expect_ignored("window 10 10 800 0\n", "window height 0 is outside 200..32768");
  expect_ignored("window 10 10 800 -5\n", "window height -5 is outside");
  expect_ignored("window 10 10 800\n", "window expects X Y WIDTH HEIGHT");       // no half-read fields
  expect_ignored("window 10 10 800 600 1 7\n", "window expects");
  expect_ignored("window 10 10 3000000000 600\n", "window width \"3000000000\" is not a whole number");
  expect_ignored("window 10 x 800 600\n", "window y \"x\" is not a whole number");
  expect_ignored("window 10 10 800.5 600\n", "is not a whole number");
  expect_ignored("window 10 10 800 600 2\n", "window maximized 2 is outside 0..1");
  expect_ignored("window 99999999 10 800 600\n", "window x 99999999 is outside");
  // A good line after a bad one is used; the old file's five-field form still reads.
  std::vector<std::string> notes;
  editor_settings s = parse_settings("window 10 10 800 0\nwindow 5 6 800 600\n", &notes);
  EXPECT_EQ(notes.size(), 1u) << joined(notes);
  notes.clear();
  s = parse_settings("window -20 30 1024 700 1\r\n", &notes);
  EXPECT_TRUE(notes.empty()) << joined(notes);
  EXPECT_EQ(s.x, -20);
  EXPECT_EQ(s.y, 30);
  EXPECT_EQ(s.width, 1024);
  EXPECT_EQ(s.height, 700);
  EXPECT_TRUE(s.maximized);
}

TEST(EditorSettings, BudgetRecentFilesAndUnknownKeys) {
  expect_ignored("node_budget 5\n", "node_budget 5 is outside 1000..50000000");
  expect_ignored("node_budget 99999999999999999999999\n", "is not a whole number");
  expect_ignored("node_budget 2000 3\n", "node_budget expects one number");
  expect_ignored("recent \n", "recent file: the path is empty");
  expect_ignored("recent /tmp/a\xFF.json\n", "not valid UTF-8");
  expect_ignored("recent /tmp/a\x01.json\n", "control character");
  expect_ignored("recent /" + std::string(5000, 'a') + "\n", "over 4096");
  expect_ignored("colour blue\n", "unknown setting \"colour\"");
  std::string many;
  for (int i = 0; i < 12; ++i) many += "recent /tmp/r" + std::to_string(i) + ".json\n";
  many += "recent /tmp/r0.json\n# a comment\n\nnode_budget 20000\n";
  std::vector<std::string> notes;
  const editor_settings s = parse_settings(many, &notes);
  ASSERT_EQ(s.recent.size(), 10u);
  EXPECT_EQ(s.recent[0], "/tmp/r0.json");
  EXPECT_EQ(s.recent[9], "/tmp/r9.json");
  EXPECT_EQ(s.node_budget, 20000);
  ASSERT_EQ(notes.size(), 3u) << joined(notes);   // r10, r11, and r0 again
  EXPECT_NE(notes[0].find("line 11: recent file: more than 10 entries"), std::string::npos) << notes[0];
  EXPECT_NE(notes[2].find("line 13: recent file: listed twice"), std::string::npos) << notes[2];
  // Paths with spaces keep them.
  EXPECT_EQ(parse_settings("recent /tmp/my trees/oak 2.json\n").recent[0], "/tmp/my trees/oak 2.json");
  // A file of a million bad lines: 20 messages and a count, not a million.
  std::string junk;
  for (int i = 0; i < 100000; ++i) junk += "window 1\n";
  notes.clear();
  parse_settings(junk, &notes);
  ASSERT_EQ(notes.size(), 21u);
  EXPECT_EQ(notes.back(), "99980 more lines ignored");
}

TEST(EditorSettings, SavedTextReadsBackExactly) {
  editor_settings s;
  s.x = -1920, s.y = 0, s.width = 1600, s.height = 1000, s.maximized = true;
  s.node_budget = 4000000;
  s.recent = {"/home/u/Sylva/oak.json", "/tmp/with space.json", "/tmp/λ.json"};
  std::vector<std::string> notes;
  EXPECT_EQ(parse_settings(settings_text(s), &notes), s);
  EXPECT_TRUE(notes.empty()) << joined(notes);
  // What the reader would refuse is not written: a bad window, budget and path are left out.
  editor_settings bad = s;
  bad.height = -5;
  bad.node_budget = 1;
  bad.recent.push_back("/tmp/a\nwindow 0 0 1 1");
  const editor_settings back = parse_settings(settings_text(bad), &notes);
  EXPECT_TRUE(notes.empty()) << joined(notes);
  EXPECT_EQ(back.width, 0);
  EXPECT_EQ(back.node_budget, 0);
  EXPECT_EQ(back.recent, s.recent);
}

TEST(EditorSettings, UnreadableFilesGiveDefaultsAndSaySo) {
  const sylva_test::scratch_dir scratch("sylva_settings_load");
  const fs::path& home = scratch.dir;
  std::vector<std::string> notes;
  EXPECT_EQ(load_settings(home.string(), &notes), editor_settings{});   // none yet: no message
  EXPECT_TRUE(notes.empty());
  fs::create_directory(home / "settings.ini");
  EXPECT_EQ(load_settings(home.string(), &notes), editor_settings{});
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("it is a folder; using the default settings"), std::string::npos) << notes[0];
  fs::remove(home / "settings.ini");
  ASSERT_EQ(::mkfifo((home / "settings.ini").c_str(), 0600), 0);
  notes.clear();
  EXPECT_EQ(load_settings(home.string(), &notes), editor_settings{});   // no writer: no hang
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("not a regular file"), std::string::npos) << notes[0];
  fs::remove(home / "settings.ini");
  std::ofstream(home / "settings.ini") << "window 0 0 800 0\nnode_budget 3000\n";
  notes.clear();
  EXPECT_EQ(load_settings(home.string(), &notes).node_budget, 3000);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_EQ(notes[0].rfind((home / "settings.ini").string() + ": line 1: window height 0", 0), 0u) << notes[0];
}

TEST(EditorSettings, RecoveryFilesAreChecked) {
  preset doc;
  std::string path = "untouched";
  EXPECT_NE(parse_recovery("{\"sylva_preset\": 1, \"generator\": ", "", doc, path), "");
  EXPECT_NE(parse_recovery("", "", doc, path), "");
  const std::string good = save_preset_json(default_preset());
  EXPECT_NE(parse_recovery(good, "/tmp/a\xFF.json", doc, path).find("not valid UTF-8"), std::string::npos);
  EXPECT_NE(parse_recovery(good, "/tmp/a.json\nsecond line", doc, path).find("control character"), std::string::npos);
  EXPECT_NE(parse_recovery(good, std::string(5000, 'a'), doc, path).find("over 4096"), std::string::npos);
  EXPECT_EQ(path, "untouched");
  EXPECT_EQ(parse_recovery(good, "/home/u/Sylva/oak.json\n", doc, path), "");
  EXPECT_EQ(path, "/home/u/Sylva/oak.json");
  EXPECT_EQ(doc, default_preset());
  EXPECT_EQ(parse_recovery(good, "", doc, path), "");   // a new document: no path
  EXPECT_EQ(path, "");
}

// The editor itself, not scripted (a script ignores the saved window): with a window of height
// -5, a partial line, junk recent entries and a corrupt recovery file it starts and keeps running
// (stopped by timeout, exit 124) and says what it ignored. Before, it aborted in glfwCreateWindow.
TEST(EditorSettings, EditorStartsWhateverIsInItsFolder) {
  const char* d = std::getenv("DISPLAY");
  if (!d || !*d) GTEST_SKIP() << "no DISPLAY";
  const sylva_test::scratch_dir scratch("sylva_settings_editor");
  const fs::path& home = scratch.dir;
  std::ofstream(home / "settings.ini") << "window 10 10 800 -5 0\nwindow 10 10 800\nnode_budget -1\nrecent \x01\n";
  std::ofstream(home / ".recovery.json") << "{\"sylva_preset\": 1, \"generator\": [";
  const std::string log = (home.parent_path() / (home.filename().string() + ".log")).string();
  const std::string preset = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";
  const std::string cmd = "SYLVA_HOME='" + home.string() + "' timeout 8 '" + std::string(SYLVA_BINARY) + "' '" + preset +
                          "' >'" + log + "' 2>&1";
  const int status = std::system(cmd.c_str());
  std::ifstream in(log);
  std::stringstream out;
  out << in.rdbuf();
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 124) << out.str();
  EXPECT_NE(out.str().find("settings.ini: line 1: window height -5 is outside 200..32768; ignored"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("line 2: window expects"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("line 4: recent file: the path holds a control character"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find(".recovery.json cannot be offered back"), std::string::npos) << out.str();
  fs::remove(log);
}
