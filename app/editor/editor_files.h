// The editor's in-app file browser: folders, an extension filter, recent files and an
// overwrite confirmation, for Open, Save as and Screenshot.
#pragma once

#include <string>
#include <vector>

namespace sylva {

struct file_entry {
  std::string name;
  bool folder = false;
};

struct file_browser {
  std::string title;                    // the dialog's title and id
  bool saving = false;                  // Save (a new name, overwrite asks) or Open (an existing file)
  std::vector<std::string> extensions;  // ".json"; the filter can also show every file
  bool all_files = false;
  std::string folder, name;             // the folder shown and the file name typed or picked
  std::vector<file_entry> entries;      // of `folder`, folders first, filtered
  std::vector<std::pair<std::string, std::string>> places;   // label, folder: the user's folder, presets, home
  std::string forbidden_folder_note;    // saving there is refused with this note ("" none)
  std::vector<std::string> forbidden_folders;
  bool confirm_overwrite = false;
  bool request_open = false;            // OpenPopup on the next draw
  std::string error;
};

// Folders first, then files whose extension is in `extensions` (all files when `all`), each sorted.
// Hidden entries (a leading '.') are left out. Returns "" or why the folder cannot be read.
std::string list_folder(const std::string& folder, const std::vector<std::string>& extensions, bool all,
                        std::vector<file_entry>& out);

// Shows the browser on `folder` (created if missing) with `name` proposed.
void open_file_browser(file_browser& b, const std::string& title, bool saving, const std::string& folder,
                       const std::string& name, const std::vector<std::string>& extensions);

// Draws the browser while open; returns the chosen path once (after the overwrite question when
// saving onto an existing file), else "". `recent` is listed for a quick pick. `answer` is a
// scripted button press (the editor test), cleared when used.
std::string draw_file_browser(file_browser& b, const std::vector<std::string>& recent, std::string& answer);

// Adds `path` to the front of the recent list (at most 10, no duplicates).
void note_recent(std::vector<std::string>& recent, const std::string& path);
// The presets among the recent files (newest first) that still exist: File > Open recent.
std::vector<std::string> recent_presets(const std::vector<std::string>& recent);

}  // namespace sylva
