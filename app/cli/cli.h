// The headless commands of the `sylva` binary: params, export, bench (DESIGN §7).
#pragma once

#include <string>

namespace sylva {

// The commands' shared messages (DESIGN §7): a failure is one line on stderr and exit 1, a usage
// error exit 2 with a pointer to --help; a warning does not change the exit code.
int fail(const std::string& command, const std::string& reason);
int usage_error(const std::string& command, const std::string& reason);
void warn(const std::string& what, const std::string& message);

// True for the names of the headless commands ("params", "export", "bench").
bool is_cli_command(const char* arg);

// Parses argv (argv[0] is the program) and runs the command. Returns the exit code:
// 0 success, 1 failure (one-line reason on stderr), 2 usage error.
int run_cli(int argc, char** argv);

}  // namespace sylva
