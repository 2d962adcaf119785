// The headless commands' shared messages (docs/design/11-cli-and-bench.md), for the CLI (app/cli/)
// and the bench (app/bench/): a failure is one line on stderr and exit 1, a usage error exit 2 with
// a pointer to --help; a warning does not change the exit code.
#pragma once

#include <string>

namespace sylva {

int fail(const std::string& command, const std::string& reason);
int usage_error(const std::string& command, const std::string& reason);
void warn(const std::string& what, const std::string& message);

}  // namespace sylva
