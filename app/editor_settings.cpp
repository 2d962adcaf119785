#include "app/editor_settings.h"

#include <cstdio>
#include <filesystem>
#include <system_error>

#include "render/file_io.h"

namespace sylva {

namespace fs = std::filesystem;

editor_settings load_settings(const std::string& home) {
  editor_settings s;
  std::string text;
  if (!read_file((fs::path(home) / "settings.ini").string(), text).empty()) return s;
  size_t a = 0;
  while (a < text.size()) {
    size_t b = text.find('\n', a);
    if (b == std::string::npos) b = text.size();
    const std::string line = text.substr(a, b - a);
    a = b + 1;
    long long n = 0;
    int m = 0;
    if (std::sscanf(line.c_str(), "window %d %d %d %d %d", &s.x, &s.y, &s.width, &s.height, &m) >= 4) s.maximized = m != 0;
    else if (std::sscanf(line.c_str(), "node_budget %lld", &n) == 1) s.node_budget = n;
    else if (line.rfind("recent ", 0) == 0 && s.recent.size() < 10) s.recent.push_back(line.substr(7));
  }
  return s;
}

void save_settings(const std::string& home, const editor_settings& s) {
  std::string text;
  char b[128];
  if (s.width > 0) {
    std::snprintf(b, sizeof b, "window %d %d %d %d %d\n", s.x, s.y, s.width, s.height, int(s.maximized));
    text += b;
  }
  if (s.node_budget > 0) text += "node_budget " + std::to_string(s.node_budget) + "\n";
  for (const std::string& r : s.recent) text += "recent " + r + "\n";
  std::error_code ec;
  fs::create_directories(home, ec);
  (void)write_file_atomic((fs::path(home) / "settings.ini").string(), text);
}

}  // namespace sylva
