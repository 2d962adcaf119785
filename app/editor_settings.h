// The editor's own settings between sessions: ~/Sylva/settings.ini (window place, node budget,
// recent files).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sylva {

// ~/Sylva/settings.ini: one `key value...` per line.
struct editor_settings {
  int x = 0, y = 0, width = 0, height = 0;   // width 0: never saved
  bool maximized = false;
  int64_t node_budget = 0;
  std::vector<std::string> recent;           // newest first
};

// Reads HOME/settings.ini; a missing or unreadable file gives the defaults.
editor_settings load_settings(const std::string& home);
// Writes HOME/settings.ini atomically (best effort: a failure leaves the old file).
void save_settings(const std::string& home, const editor_settings& s);

}  // namespace sylva
