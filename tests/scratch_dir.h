// The tests' one scratch-space helper, and a whole file read as bytes. Every scratch path is
// TMPDIR/NAME_PID, so parallel test processes never share files and none is left after the run:
// - scratch_dir: a folder for one test, emptied first and removed when the object goes;
// - scratch_path: a path (folder or file) kept until the test process exits, for tests that read
//   files written by a child process until they end (the editor sessions print their logs on a
//   failure).
#pragma once

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace sylva_test {

// TMPDIR/NAME_PID, emptied first and removed with everything in it when the test ends.
struct scratch_dir {
  std::filesystem::path dir;
  explicit scratch_dir(const std::string& name)
      : dir(std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()))) {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
    std::filesystem::create_directories(dir);
  }
  ~scratch_dir() {
    std::error_code ec;
    std::filesystem::permissions(dir, std::filesystem::perms::owner_all, ec);   // a test may have locked it
    std::filesystem::remove_all(dir, ec);
  }
  scratch_dir(const scratch_dir&) = delete;
  scratch_dir& operator=(const scratch_dir&) = delete;
  std::string operator/(const std::string& name) const { return (dir / name).string(); }
};

// The paths scratch_path has named, removed when the test process exits.
struct scratch_paths {
  std::vector<std::filesystem::path> named;
  ~scratch_paths() {
    for (const std::filesystem::path& d : named) {
      std::error_code ec;
      std::filesystem::remove_all(d, ec);
    }
  }
};

// TMPDIR/NAME_PID, not created (a test may write a file or a folder there), removed with
// everything in it when the test process exits.
inline std::filesystem::path scratch_path(const std::string& name) {
  static scratch_paths paths;
  std::filesystem::path d = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  if (std::find(paths.named.begin(), paths.named.end(), d) == paths.named.end()) paths.named.push_back(d);
  return d;
}

// The file's bytes ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace sylva_test
