// ~/Sylva/settings.ini and the recovery files, checked field by field (app/editor/editor_settings.h).
#include "app/editor/editor_settings.h"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "render/files.h"

namespace sylva {

namespace fs = std::filesystem;

namespace {

std::vector<std::string_view> words(std::string_view s) {
  std::vector<std::string_view> w;
  size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
    const size_t start = i;
    while (i < s.size() && s[i] != ' ' && s[i] != '\t') ++i;
    if (i > start) w.push_back(s.substr(start, i - start));
  }
  return w;
}

// A whole decimal integer in [lo, hi], or why not (named `what`).
template <class T>
std::string read_int(std::string_view text, T lo, T hi, const char* what, T& out) {
  T v{};
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size())
    return std::string(what) + " \"" + std::string(text.substr(0, 40)) + "\" is not a whole number";
  if (v < lo || v > hi)
    return std::string(what) + " " + std::to_string(v) + " is outside " + std::to_string(lo) + ".." + std::to_string(hi);
  out = v;
  return "";
}

std::string parse_window(const std::vector<std::string_view>& w, editor_settings& s) {
  if (w.size() != 5 && w.size() != 6) return "window expects X Y WIDTH HEIGHT [MAXIMIZED 0|1]";
  editor_settings t = s;
  int m = 0;
  std::string e;
  if (e.empty()) e = read_int(w[1], -settings_position_max, settings_position_max, "window x", t.x);
  if (e.empty()) e = read_int(w[2], -settings_position_max, settings_position_max, "window y", t.y);
  if (e.empty()) e = read_int(w[3], settings_window_min, settings_window_max, "window width", t.width);
  if (e.empty()) e = read_int(w[4], settings_window_min, settings_window_max, "window height", t.height);
  if (e.empty() && w.size() == 6) e = read_int(w[5], 0, 1, "window maximized", m);
  if (!e.empty()) return e;
  t.maximized = m != 0;
  s = t;
  return "";
}

}  // namespace

std::string check_saved_path(std::string_view path) {
  if (path.empty()) return "the path is empty";
  if (path.size() > settings_path_max)
    return "the path is " + std::to_string(path.size()) + " bytes, over " + std::to_string(settings_path_max);
  if (!valid_utf8(path)) return "the path is not valid UTF-8";
  for (unsigned char c : path)
    if (c < 0x20 || c == 0x7f) return "the path holds a control character";
  return "";
}

editor_settings parse_settings(std::string_view text, std::vector<std::string>* messages) {
  editor_settings s;
  bool window_seen = false, budget_seen = false;
  size_t ignored = 0;
  size_t a = 0;
  for (int number = 1; a < text.size(); ++number) {
    size_t b = text.find('\n', a);
    if (b == std::string_view::npos) b = text.size();
    std::string_view line = text.substr(a, b - a);
    a = b + 1;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const std::vector<std::string_view> w = words(line);
    if (w.empty() || w[0][0] == '#') continue;
    std::string why;
    if (w[0] == "window") {
      why = window_seen ? "a second window line" : parse_window(w, s);
      window_seen = why.empty();
    } else if (w[0] == "node_budget") {
      if (budget_seen) why = "a second node_budget line";
      else if (w.size() != 2) why = "node_budget expects one number";
      else why = read_int(w[1], settings_budget_min, settings_budget_max, "node_budget", s.node_budget);
      budget_seen = why.empty();
    } else if (w[0] == "recent") {
      // The path is the rest of the line after "recent ", spaces included.
      const size_t at = line.find("recent") + 6;
      const std::string_view path = at < line.size() ? line.substr(at + 1) : std::string_view();
      why = check_saved_path(path);
      if (why.empty() && std::find(s.recent.begin(), s.recent.end(), path) != s.recent.end()) why = "listed twice";
      if (why.empty() && s.recent.size() == settings_recent_max)
        why = "more than " + std::to_string(settings_recent_max) + " entries";
      if (why.empty()) s.recent.emplace_back(path);
      else why = "recent file: " + why;
    } else {
      std::string key(w[0].substr(0, 40));
      if (!valid_utf8(key)) key = "(not UTF-8)";
      why = "unknown setting \"" + key + "\"";
    }
    if (why.empty() || !messages) continue;
    if (++ignored <= 20) messages->push_back("line " + std::to_string(number) + ": " + why + "; ignored");
  }
  if (ignored > 20 && messages) messages->push_back(std::to_string(ignored - 20) + " more lines ignored");
  return s;
}

std::string settings_text(const editor_settings& s) {
  std::string text;
  const bool window_ok = s.width >= settings_window_min && s.width <= settings_window_max &&
                         s.height >= settings_window_min && s.height <= settings_window_max &&
                         s.x >= -settings_position_max && s.x <= settings_position_max && s.y >= -settings_position_max &&
                         s.y <= settings_position_max;
  if (window_ok)
    text += "window " + std::to_string(s.x) + " " + std::to_string(s.y) + " " + std::to_string(s.width) + " " +
            std::to_string(s.height) + " " + (s.maximized ? "1" : "0") + "\n";
  if (s.node_budget >= settings_budget_min && s.node_budget <= settings_budget_max)
    text += "node_budget " + std::to_string(s.node_budget) + "\n";
  size_t written = 0;
  for (size_t i = 0; i < s.recent.size() && written < settings_recent_max; ++i) {
    const std::string& r = s.recent[i];
    if (!check_saved_path(r).empty() || std::find(s.recent.begin(), s.recent.begin() + long(i), r) != s.recent.begin() + long(i))
      continue;
    text += "recent " + r + "\n";
    ++written;
  }
  return text;
}

editor_settings load_settings(const std::string& home, std::vector<std::string>* messages) {
  const std::string path = (fs::path(home) / "settings.ini").string();
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(path, ec))) return {};
  std::string text;
  if (std::string err = read_file(path, text, 1 << 20); !err.empty()) {
    if (messages) messages->push_back(err + "; using the default settings");
    return {};
  }
  std::vector<std::string> notes;
  editor_settings s = parse_settings(text, &notes);
  if (messages)
    for (const std::string& n : notes) messages->push_back(path + ": " + n);
  return s;
}

void save_settings(const std::string& home, const editor_settings& s) {
  std::error_code ec;
  fs::create_directories(home, ec);
  (void)write_file_atomic((fs::path(home) / "settings.ini").string(), settings_text(s));
}

std::string parse_recovery(std::string_view json, std::string_view source, preset& doc, std::string& path) {
  preset p;
  const load_result r = load_preset_json(json, p);
  if (!r.ok) return r.error;
  std::string_view src = source;
  if (!src.empty() && src.back() == '\n') src.remove_suffix(1);   // written without one; tolerated
  if (!src.empty())
    if (std::string why = check_saved_path(src); !why.empty()) return "its document's path: " + why;
  doc = std::move(p);
  path = std::string(src);
  return "";
}

}  // namespace sylva
