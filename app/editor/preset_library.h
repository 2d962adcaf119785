// The preset library without a display: folder scans, search and tag filters, thumbnail cache keys.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sylva {

struct preset_entry {
  std::string path;          // the file as found
  std::string name, description, generator;
  std::vector<std::string> tags;
  std::string thumbnail_key; // changes whenever the file's bytes change (see thumbnail_key)
  std::string error;         // non-empty: the file did not load; listed, but not openable
};

// The cache key for a preset's thumbnail: a 64-bit FNV-1a hash of the file's bytes and the
// thumbnail size, in hex. Hashing the content rather than the path or mtime means an edited
// preset gets a new thumbnail and a renamed or copied one reuses the old.
std::string thumbnail_key(std::string_view preset_text, int thumbnail_size);

// Every *.json in `dir` (not recursive), loaded tolerantly, sorted by file name. Files that fail
// to load are kept with `error` set so the browser can say why.
std::vector<preset_entry> scan_preset_folder(const std::string& dir, int thumbnail_size);

// scan_preset_folder over each folder in order, with each path made canonical. One card per
// preset: a folder reached twice (a link, "a/../a") is listed once, and a file with the same name
// and bytes as one listed from an earlier folder (the binary's tree and the working folder both
// shipping presets/) is left out.
std::vector<preset_entry> scan_preset_folders(const std::vector<std::string>& dirs, int thumbnail_size);

// Case-insensitive: every word of `query` must occur in the name, description, generator or a
// tag, and the entry must carry every tag in `required_tags`.
bool preset_matches(const preset_entry& e, std::string_view query, const std::vector<std::string>& required_tags);

// The tags of all entries, most used first (ties by name), each once.
std::vector<std::string> collect_tags(const std::vector<preset_entry>& entries);

// $XDG_CACHE_HOME/sylva/thumbs, else $HOME/.cache/sylva/thumbs, else a folder under the temp dir.
std::string thumbnail_cache_dir();

}  // namespace sylva
