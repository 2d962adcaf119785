// Runs the real editor under a script (SYLVA_SCRIPT, app/editor_script.h) for the session tests.
#pragma once

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "../gl/gl_test_context.h"   // have_display
#include "../scratch_dir.h"

namespace sylva_test {

struct run_result {
  int code = -1;
  std::string output;
};

// The script ran to its end: exit 0 and no failed line (the output goes with a failure).
inline ::testing::AssertionResult script_passed(const run_result& r) {
  if (r.code == 0 && r.output.find("FAIL") == std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "exit " << r.code << "\n" << r.output;
}

// A path of this test process's own (tests/scratch_dir.h), so that parallel runs do not share files;
// it stays until the process exits, since a session test reads its log and files until it ends.
inline std::filesystem::path test_dir(const std::string& name) { return scratch_path("sylva_editor_" + name); }

// The editor in an 800x500 window with `preset`, its home in test_dir(name)/home, driven by
// `script`; `env` goes before the command ("XDG_CACHE_HOME='/tmp/x' ").
inline run_result run_script(const std::string& name, const std::string& script, const std::string& preset,
                             const std::string& env = "", const std::string& window = "800x500") {
  namespace fs = std::filesystem;
  const fs::path dir = test_dir(name);
  fs::remove_all(dir);
  fs::create_directories(dir / "home");
  std::ofstream(dir / "script.txt") << script;
  const std::string log = (dir / "log.txt").string();
  const std::string cmd = env + "SYLVA_HOME='" + (dir / "home").string() + "' SYLVA_SCRIPT='" + (dir / "script.txt").string() +
                          "' SYLVA_WINDOW=" + window + " '" + std::string(SYLVA_BINARY) + "' '" + preset + "' > '" + log + "' 2>&1";
  run_result r;
  const int status = std::system(cmd.c_str());
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  r.output = ss.str();
  return r;
}

}  // namespace sylva_test
