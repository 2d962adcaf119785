// What the editor reads back from ~/Sylva at start: settings.ini (window place, node budget,
// recent files) and the recovery files' companion path. Display-free, so that tests and the fuzz
// harnesses reach it; every field is checked, and a bad line or entry is left out with a message
// (the editor always starts, with the defaults for whatever it could not use).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "render/io/preset.h"

namespace sylva {

// ~/Sylva/settings.ini: one `key value...` per line.
struct editor_settings {
  int x = 0, y = 0, width = 0, height = 0;   // width 0: never saved
  bool maximized = false;
  int64_t node_budget = 0;                   // 0: never saved
  std::vector<std::string> recent;           // newest first
  bool operator==(const editor_settings&) const = default;
};

// The ranges a setting must lie in to be used (the node budget is the Preferences slider's).
inline constexpr int settings_window_min = 200, settings_window_max = 32768;   // width, height
inline constexpr int settings_position_max = 1 << 20;                          // |x|, |y|
inline constexpr int64_t settings_budget_min = 1000, settings_budget_max = 50000000;
inline constexpr size_t settings_recent_max = 10, settings_path_max = 4096;

// Reads settings text: `window X Y W H [MAXIMIZED]`, `node_budget N`, `recent PATH`; blank lines
// and `#` comments are skipped. A line that is malformed or out of range is ignored whole, and
// `messages` gets "line N: why; ignored".
editor_settings parse_settings(std::string_view text, std::vector<std::string>* messages = nullptr);
// The text parse_settings reads back to `s` (entries parse_settings would refuse are left out).
std::string settings_text(const editor_settings& s);

// Reads HOME/settings.ini; a missing file gives the defaults, an unreadable one the defaults and
// a message; each message names the file.
editor_settings load_settings(const std::string& home, std::vector<std::string>* messages = nullptr);
// Writes HOME/settings.ini atomically (best effort: a failure leaves the old file).
void save_settings(const std::string& home, const editor_settings& s);

// A recent-file or recovery source path as read back: one line of valid UTF-8, no control
// characters, at most settings_path_max bytes. "" or why not.
std::string check_saved_path(std::string_view path);

// A recovery file's text and its companion `.source` text (the document's own path, "" for a new
// one): "" with `doc` and `path` filled, or why it cannot be offered back.
std::string parse_recovery(std::string_view json, std::string_view source, preset& doc, std::string& path);

}  // namespace sylva
