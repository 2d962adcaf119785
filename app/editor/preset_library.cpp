// Preset library logic shared by the editor's browser and the tests: no GL, no ImGui.
#include "app/editor/preset_library.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>

#include "render/io/preset.h"

namespace sylva {

namespace fs = std::filesystem;

namespace {

uint64_t fnv1a(std::string_view bytes, uint64_t h = 0xcbf29ce484222325ull) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool contains(std::string_view haystack_lower, std::string_view needle_lower) {
  return haystack_lower.find(needle_lower) != std::string_view::npos;
}

}  // namespace

std::string thumbnail_key(std::string_view preset_text, int thumbnail_size) {
  // The size goes in too: a thumbnail rendered at another size is another file.
  const std::string salt = "sylva-thumb-2/" + std::to_string(thumbnail_size) + "/";
  const uint64_t h = fnv1a(preset_text, fnv1a(salt));
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::vector<preset_entry> scan_preset_folder(const std::string& dir, int thumbnail_size) {
  std::vector<preset_entry> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.path().extension() == ".json" && entry.is_regular_file(ec)) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& f : files) {
    preset_entry e;
    e.path = f.string();
    e.name = f.stem().string();
    std::string text;
    if (std::string err = read_file(e.path, text, max_preset_bytes); !err.empty()) {
      e.error = err;
    } else {
      e.thumbnail_key = thumbnail_key(text, thumbnail_size);
      preset p;
      load_result r = load_preset_json(text, p);
      if (!r.ok) {
        e.error = r.error;
      } else {
        e.name = p.name;
        e.description = p.description;
        e.tags = p.tags;
        e.generator = generator_name(p.spec);
      }
    }
    out.push_back(std::move(e));
  }
  return out;
}

std::vector<preset_entry> scan_preset_folders(const std::vector<std::string>& dirs, int thumbnail_size) {
  std::vector<preset_entry> out;
  std::set<std::string> seen, same_file;
  for (const std::string& d : dirs) {
    for (preset_entry& e : scan_preset_folder(d, thumbnail_size)) {
      std::error_code ec;
      const std::string canonical = fs::weakly_canonical(e.path, ec).string();
      if (!seen.insert(canonical).second) continue;
      std::string bytes;
      if (read_file(canonical, bytes, max_preset_bytes).empty() &&
          !same_file.insert(fs::path(canonical).filename().string() + '\n' + bytes).second)
        continue;
      e.path = canonical;
      out.push_back(std::move(e));
    }
  }
  return out;
}

bool preset_matches(const preset_entry& e, std::string_view query, const std::vector<std::string>& required_tags) {
  for (const std::string& t : required_tags)
    if (std::find(e.tags.begin(), e.tags.end(), t) == e.tags.end()) return false;
  // Appended piece by piece: `"\n" + std::string` here trips GCC 12's -Wrestrict false positive.
  std::string text = lower(e.name);
  for (const std::string* part : {&e.description, &e.generator}) {
    text += '\n';
    text += lower(*part);
  }
  for (const std::string& t : e.tags) {
    text += '\n';
    text += lower(t);
  }
  const std::string q = lower(query);
  size_t i = 0;
  while (i < q.size()) {
    while (i < q.size() && std::isspace(static_cast<unsigned char>(q[i]))) ++i;
    size_t j = i;
    while (j < q.size() && !std::isspace(static_cast<unsigned char>(q[j]))) ++j;
    if (j > i && !contains(text, std::string_view(q).substr(i, j - i))) return false;
    i = j;
  }
  return true;
}

std::vector<std::string> collect_tags(const std::vector<preset_entry>& entries) {
  std::map<std::string, int> count;
  for (const preset_entry& e : entries)
    for (const std::string& t : e.tags) ++count[t];
  std::vector<std::string> tags;
  for (const auto& [t, n] : count) tags.push_back(t);
  std::stable_sort(tags.begin(), tags.end(), [&](const std::string& a, const std::string& b) { return count[a] > count[b]; });
  return tags;
}

std::string thumbnail_cache_dir() {
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return (fs::path(x) / "sylva" / "thumbs").string();
  if (const char* h = std::getenv("HOME"); h && *h) return (fs::path(h) / ".cache" / "sylva" / "thumbs").string();
  std::error_code ec;
  return (fs::temp_directory_path(ec) / "sylva-thumbs").string();
}

}  // namespace sylva
