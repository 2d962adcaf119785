// Files as the whole project writes and reads them: atomic writes (one file, or several staged
// and committed together) and bounded reads (docs/DESIGN-NOTES.md, "Input limits").
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace sylva {

// The largest texture, mesh or other asset file read whole (a preset has its own, smaller limit).
inline constexpr uint64_t max_asset_bytes = 256ull << 20;

// Writes `bytes` to `path` atomically (a short temporary name in the same folder, then rename).
// A symlink is written through: its target is replaced and the link stays. An existing file keeps
// its permission bits (and its owner, where allowed). A target that exists and is not a regular
// file (a folder, FIFO, device or socket, also at the end of a symlink) is refused, never replaced.
// Returns "" or a message naming the path and the reason.
std::string write_file_atomic(const std::string& path, std::string_view bytes);
// write_file_atomic in two halves, for writes that span several files (an OBJ with its MTL and PNGs):
// stage every file (written and synced under a temporary name beside its target, through symlinks,
// keeping permissions), and only when all are staged commit them (rename); on a failure discard the
// staged ones, so the previous files stay whole.
struct staged_write {
  std::string path;     // as asked for
  std::string target;   // where it lands (symlinks followed)
  std::string temp;     // the temporary beside it
};
std::string stage_file(const std::string& path, std::string_view bytes, staged_write& out);
std::string commit_staged(const staged_write& s);
void discard_staged(const staged_write& s);
// Tests: the n-th stage_file call from now (0: the next) fails as a full disk would; -1 never.
void inject_write_failure_for_tests(int n);
// "a FIFO (named pipe)", "a character device", ... for a stat st_mode, as messages name it.
const char* file_kind(unsigned mode);
// Reads a whole regular file of at most `max_bytes`. Devices, FIFOs, sockets and folders are refused
// at once, and so is a file over the limit (docs/DESIGN-NOTES.md, "Input limits").
std::string read_file(const std::string& path, std::string& out, uint64_t max_bytes = max_asset_bytes);

}  // namespace sylva
