// Atomic writes and bounded reads (render/files.h).
#include "render/files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace sylva {

namespace {
std::atomic<int> write_fault{-1};   // stage_file calls left before one fails (tests); -1: never

// Why a new file could not be made in `dir`, in the user's words: open() says "No such file or
// directory" both for a missing folder and for a system folder (/proc, /sys) that takes no files.
std::string create_failure(const std::filesystem::path& dir, int err) {
  std::error_code ec;
  const std::string where = dir.string();
  const std::string why = std::string(" (") + std::strerror(err) + ")";
  switch (err) {
    case ENOENT:
      return std::filesystem::is_directory(dir, ec)
                 ? "the folder " + where + " does not take new files (a system folder such as /proc or /sys?)"
                 : "the folder " + where + " does not exist";
    case EACCES:
    case EPERM: return "no permission to create a file in " + where + why;
    case EROFS: return "the folder " + where + " is on a read-only file system" + why;
    case ENOSPC:
    case EDQUOT: return "the disk is full: no room for a new file in " + where + why;
    case ENOTDIR: return "part of " + where + " is a file, not a folder" + why;
    default: return "cannot create a file in " + where + ": " + std::strerror(err);
  }
}
}  // namespace

void inject_write_failure_for_tests(int n) { write_fault.store(n); }

const char* file_kind(unsigned mode) {
  switch (mode & S_IFMT) {
    case S_IFREG: return "a regular file";
    case S_IFDIR: return "a folder";
    case S_IFIFO: return "a FIFO (named pipe)";
    case S_IFCHR: return "a character device";
    case S_IFBLK: return "a block device";
    case S_IFSOCK: return "a socket";
    case S_IFLNK: return "a symbolic link";
    default: return "a special file";
  }
}

std::string stage_file(const std::string& path, std::string_view bytes, staged_write& out) {
  namespace fs = std::filesystem;
  out = {};
  if (path.empty()) return "cannot write: empty path";
  // Through symlinks (as editors do): renaming over the link itself would turn it into a copy.
  fs::path target(path);
  for (int hops = 0;; ++hops) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(target, ec)) || ec) break;
    if (hops == 40) return "cannot write " + path + ": too many levels of symbolic links";
    const fs::path link = fs::read_symlink(target, ec);
    if (ec) return "cannot write " + path + ": cannot read the symbolic link: " + ec.message();
    target = link.is_absolute() ? link : target.parent_path() / link;
  }
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  // An existing file keeps its permissions (a 0600 file must not come back 0644) and, where the
  // user may, its owner; a new file gets 0666 less the umask, as open() would give it.
  struct stat old_st {};
  const bool existed = ::lstat(target.c_str(), &old_st) == 0;
  // Only a regular file is ever replaced: renaming over a FIFO, a device (a link to /dev/null, run
  // as root) or a folder would change what kind of thing the user had there.
  if (existed && !S_ISREG(old_st.st_mode)) {
    const std::string via = target.string() == path ? "" : " (the symbolic link leads to " + target.string() + ")";
    return "cannot write " + path + ": it is " + file_kind(old_st.st_mode) + via +
           ", not a regular file; Sylva only replaces regular files";
  }
  // A short temporary name: a legal 255-byte output name leaves no room for a longer one beside it.
  static std::atomic<unsigned> counter{0};
  const fs::path temp = dir / (".sylva.tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1)));
  auto fail = [&](const char* what, int err) {
    return "cannot write " + path + ": " + what + ": " + std::strerror(err);
  };
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, existed ? 0600 : 0666);
  if (fd < 0) return "cannot write " + path + ": " + create_failure(dir, errno);
  if (existed) {
    if (::fchown(fd, old_st.st_uid, old_st.st_gid) != 0) {}  // only root may give a file away; not an error
    if (::fchmod(fd, old_st.st_mode & 07777) != 0) {
      const int err = errno;
      ::close(fd);
      ::unlink(temp.c_str());
      return fail("cannot keep the file's permissions", err);
    }
  }
  size_t done = 0;
  const bool injected = write_fault.load() >= 0 && write_fault.fetch_sub(1) == 0;
  while (done < bytes.size() || injected) {
    const ssize_t n = injected ? (errno = ENOSPC, -1) : ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : EIO;
      ::close(fd);
      ::unlink(temp.c_str());
      return fail("write failed", err);  // e.g. a full disk: the partial temp file is removed
    }
    done += size_t(n);
  }
  // fsync before rename: otherwise a crash can leave the new name pointing at an empty file.
  if (::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    ::unlink(temp.c_str());
    return fail("fsync failed", err);
  }
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(temp.c_str());
    return fail("close failed", err);
  }
  out.path = path;
  out.temp = temp.string();
  out.target = target.string();
  return "";
}

std::string commit_staged(const staged_write& s) {
  namespace fs = std::filesystem;
  // Checked again just before the rename: something may have been put there since stage_file.
  if (struct stat st {}; ::lstat(s.target.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    ::unlink(s.temp.c_str());
    return "cannot write " + s.path + ": it is now " + file_kind(st.st_mode) + ", not a regular file";
  }
  if (::rename(s.temp.c_str(), s.target.c_str()) != 0) {
    const int err = errno;
    ::unlink(s.temp.c_str());
    return "cannot write " + s.path + ": rename failed: " + std::strerror(err);
  }
  const fs::path target(s.target);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dfd >= 0) {
    ::fsync(dfd);  // makes the rename itself durable; failure here loses nothing already written
    ::close(dfd);
  }
  return "";
}

void discard_staged(const staged_write& s) {
  if (!s.temp.empty()) ::unlink(s.temp.c_str());
}

std::string write_file_atomic(const std::string& path, std::string_view bytes) {
  staged_write s;
  if (std::string err = stage_file(path, bytes, s); !err.empty()) return err;
  return commit_staged(s);
}

std::string read_file(const std::string& path, std::string& out, uint64_t max_bytes) {
  auto fail = [&](const std::string& why) { return "cannot read " + path + ": " + why; };
  // O_NONBLOCK: opening a FIFO with no writer must not hang before the type check below refuses it.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd < 0) return fail(std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    return fail(std::strerror(err));
  }
  // Only regular files: a device (/dev/zero), FIFO or socket may never end, and a folder has no bytes.
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    return fail(S_ISDIR(st.st_mode) ? "it is a folder" : "not a regular file (a device, FIFO or socket)");
  }
  auto too_big = [&] {
    return fail("larger than the " + std::to_string(max_bytes >> 20) + " MB limit for this kind of file");
  };
  if (uint64_t(st.st_size) > max_bytes) {
    ::close(fd);
    return too_big();
  }
  std::string text;
  text.resize(size_t(st.st_size));
  size_t got = 0;
  for (;;) {  // also reads past st_size if the file grows meanwhile, up to the limit
    if (got == text.size()) {
      if (got > max_bytes) {
        ::close(fd);
        return too_big();
      }
      text.resize(std::min<uint64_t>(max_bytes + 1, std::max<uint64_t>(got * 2, 4096)));
    }
    const ssize_t n = ::read(fd, text.data() + got, text.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      return fail(std::strerror(err));
    }
    if (n == 0) break;
    got += size_t(n);
  }
  ::close(fd);
  if (got > max_bytes) return too_big();
  text.resize(got);
  out = std::move(text);
  return "";
}

}  // namespace sylva
