// The headless commands' shared messages (app/messages.h).
#include "app/common/messages.h"

#include <cstdio>

namespace sylva {

int fail(const std::string& command, const std::string& reason) {
  std::fprintf(stderr, "sylva %s: %s\n", command.c_str(), reason.c_str());
  return 1;
}
int usage_error(const std::string& command, const std::string& reason) {
  std::fprintf(stderr, "sylva %s: %s (see sylva %s --help)\n", command.c_str(), reason.c_str(), command.c_str());
  return 2;
}
void warn(const std::string& what, const std::string& message) {
  std::fprintf(stderr, "warning: %s: %s\n", what.c_str(), message.c_str());
}

}  // namespace sylva
