// The headless commands of the `sylva` binary: params, export, bench (DESIGN §7).
#pragma once

#include <string>

#include "app/common/messages.h"   // fail, usage_error, warn

namespace sylva {

// True for the names of the headless commands ("params", "export", "bench").
bool is_cli_command(const char* arg);

// Parses argv (argv[0] is the program) and runs the command. Returns the exit code:
// 0 success, 1 failure (one-line reason on stderr), 2 usage error.
int run_cli(int argc, char** argv);

}  // namespace sylva
