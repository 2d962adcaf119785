// Runs the built sylva binary from a test and captures its exit code, stdout and stderr.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

struct sylva_run {
  int code = -1;
  std::string out, err;
};

// `env` prefixes the command (e.g. "env -u DISPLAY -u WAYLAND_DISPLAY"); `args` is shell text.
inline sylva_run run_sylva(const std::string& env, const std::string& args) {
  static int counter = 0;
  const std::filesystem::path err = std::filesystem::temp_directory_path() /
                                    ("sylva_test_stderr_" + std::to_string(::getpid()) + "_" +
                                     std::to_string(counter++) + ".txt");
  const std::string cmd = env + " '" + std::string(SYLVA_BINARY) + "' " + args + " 2>'" + err.string() + "'";
  sylva_run r;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) return r;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) r.out.append(buf, n);
  const int status = ::pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream f(err, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  r.err = s.str();
  std::error_code ec;
  std::filesystem::remove(err, ec);
  return r;
}
