#include "core/io/atomic_file.hpp"

#include "core/errors.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <system_error>

namespace egg {
namespace fs = std::filesystem;

std::string temporarySuffix() {
  std::random_device rd;
  std::uniform_int_distribution<unsigned> digit(0, 35);
  std::string s;
  for (int i = 0; i < 8; ++i) {
    const unsigned d = digit(rd);
    s.push_back(static_cast<char>(d < 10 ? '0' + d : 'a' + d - 10));
  }
  return s;
}

std::string temporaryFilePrefix() { return ".egg-tmp-"; }

fs::path makePrivateTempFolder(const std::string& stem) {
  std::error_code error;
  const fs::path base = fs::temp_directory_path(error);
  if (error) throw WriteError("no temporary folder ($TMPDIR): " + error.message());
  std::string name = (base / (stem + "-XXXXXX")).string();
  if (::mkdtemp(name.data()) == nullptr)
    throw WriteError("cannot make a private folder in " + base.string() +
                     " ($TMPDIR): " + std::strerror(errno));
  return name;
}

pid_t leftoverPid(const std::string& name, const std::string& prefix) {
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return -1;
  size_t i = prefix.size();
  long long pid = 0;
  const size_t start = i;
  while (i < name.size() && name[i] >= '0' && name[i] <= '9' && i - start < 10)
    pid = pid * 10 + (name[i++] - '0');
  if (i == start || i >= name.size() || name[i] != '-' || pid <= 0 || pid > 0x7fffffff) return -1;
  return static_cast<pid_t>(pid);
}

bool processAlive(pid_t pid) {
  if (pid <= 0) return false;
  if (::kill(pid, 0) == 0) return true;
  return errno != ESRCH;  // EPERM: it exists, owned by someone else
}

LiveLock::LiveLock(const fs::path& path) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
  if (fd_ >= 0) held_ = ::flock(fd_, LOCK_EX | LOCK_NB) == 0;
}

LiveLock::~LiveLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

bool leftoverInUse(const fs::path& path, pid_t pid) {
  // O_NOFOLLOW: a link planted under a leftover's name is never opened (nor its target locked).
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK | O_NOFOLLOW);
  if (fd >= 0) {
    const int taken = ::flock(fd, LOCK_EX | LOCK_NB);
    const int error = errno;
    ::close(fd);                                          // releases it again when we got it
    if (taken != 0 && error == EWOULDBLOCK) return true;  // held: at work, in any PID namespace
  }
  // Unlocked (or no flock here): a process of that PID alive here may still be at work on it (an
  // egg that took no lock); a leftover is removed only when neither says so.
  return processAlive(pid);
}

int removeDeadLeftovers(const fs::path& folder, const std::string& prefix, bool folders) {
  int removed = 0;
  std::error_code ec;
  fs::directory_iterator it(folder, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const pid_t pid = leftoverPid(name, prefix);
    if (pid < 0 || pid == ::getpid()) continue;
    // The type first: only our kinds of leftover (files, folders) are ever opened to test a lock.
    std::error_code typeError;
    const fs::file_status status = it->symlink_status(typeError);
    if (typeError || !(fs::is_regular_file(status) || (folders && fs::is_directory(status))))
      continue;
    if (leftoverInUse(it->path(), pid)) continue;
    std::error_code removeError;
    if (folders && fs::is_directory(status)) {
      fs::remove_all(it->path(), removeError);
    } else if (fs::is_regular_file(status)) {
      fs::remove(it->path(), removeError);
    } else {
      continue;
    }
    if (!removeError) ++removed;
  }
  return removed;
}

fs::path checkedOutputTarget(const fs::path& path) {
  std::error_code ec;
  const fs::file_status link = fs::symlink_status(path, ec);
  if (ec || !fs::exists(link)) return path;  // a new file
  fs::path target = path;
  fs::file_status status = link;
  if (fs::is_symlink(link)) {
    status = fs::status(path, ec);
    if (ec || !fs::exists(status)) return path;  // a dangling link: rename replaces the link itself
    target = fs::canonical(path, ec);
    if (ec)
      throw WriteError(path.string() + ": cannot resolve the symbolic link: " + ec.message(),
                       path.string());
  }
  if (!fs::is_regular_file(status)) {
    const char* kind = fs::is_directory(status)        ? "a folder"
                       : fs::is_character_file(status) ? "a character device"
                       : fs::is_block_file(status)     ? "a block device"
                       : fs::is_fifo(status)           ? "a FIFO"
                       : fs::is_socket(status)         ? "a socket"
                                                       : "not a regular file";
    throw WriteError(path.string() + ": exists and is " + kind +
                         "; refusing to replace it with a file (choose another output path)",
                     path.string());
  }
  return target;
}

namespace {

// Writes all of `text` to a new file `temp` and syncs it; false (and errno kept in `error`) on any
// failure: short write, ENOSPC, EFBIG, EIO at fsync or close.
bool writeNewFile(const fs::path& temp, const std::string& text, int& error) {
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) {
    error = errno;
    return false;
  }
  // At work while written: another run's cleanup (removeDeadLeftovers) leaves it alone even when
  // it cannot see our PID. The caller's rename follows at once; a cleanup in that instant finds the
  // file gone or finished, and the rename reports it.
  ::flock(fd, LOCK_EX | LOCK_NB);
  const char* data = text.data();
  size_t left = text.size();
  bool ok = true;
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error = n < 0 ? errno : ENOSPC;
      ok = false;
      break;
    }
    data += n;
    left -= static_cast<size_t>(n);
  }
  // The data must be on disk before the rename, or a crash could leave an empty file under the
  // final name; NFS and quotas report errors only at fsync or close.
  if (ok && ::fsync(fd) != 0) error = errno, ok = false;
  if (::close(fd) != 0 && ok) error = errno, ok = false;
  return ok;
}

}  // namespace

void writeFileAtomically(const fs::path& path, const std::string& text) {
  if (path.empty()) throw WriteError("cannot write a file: empty path");
  if (path.native().find('\0') != std::string::npos)
    throw WriteError(abbreviate(path.string()) + ": the path contains a NUL character",
                     path.string());
  const fs::path target = checkedOutputTarget(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  removeDeadLeftovers(dir, temporaryFilePrefix(), false);
  // Same folder as the target: rename is atomic only within one file system. The name carries
  // our PID (so that a later run knows a leftover is dead) and not the target's name (so that
  // it fits NAME_MAX whatever the target's length).
  const fs::path temp =
      dir / (temporaryFilePrefix() + std::to_string(::getpid()) + "-" + temporarySuffix());
  int error = 0;
  if (!writeNewFile(temp, text, error)) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw WriteError(
        path.string() + ": write failed: " + std::strerror(error) +
            (error == ENOSPC || error == EFBIG || error == EDQUOT ? " (disk full or file too large)"
                                                                  : ""),
        path.string());
  }
  std::error_code ec;
  fs::rename(temp, target, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw WriteError(path.string() + ": cannot move finished file into place: " + ec.message(),
                     path.string());
  }
}

namespace {

// Opens `path` for reading without blocking (a FIFO without a writer would block open()) and
// checks it is a regular file of at most maxBytes. Returns the descriptor.
int openRegularInput(const fs::path& path, std::size_t maxBytes, const std::string& what,
                     off_t& size) {
  const std::string name = abbreviate(path.string());
  if (path.native().find('\0') != std::string::npos)
    throw IoError(name + ": the " + what + " path contains a NUL character", path.string());
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    const int error = errno;
    if (error == ENOENT)
      throw IoError(name + ": cannot open " + what + ": no such file", path.string());
    throw IoError(name + ": cannot open " + what + ": " + std::strerror(error), path.string());
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int error = errno;
    ::close(fd);
    throw IoError(name + ": cannot inspect " + what + ": " + std::strerror(error), path.string());
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    const char* kind = S_ISDIR(st.st_mode)    ? "a folder"
                       : S_ISFIFO(st.st_mode) ? "a FIFO"
                       : S_ISCHR(st.st_mode)  ? "a character device"
                       : S_ISBLK(st.st_mode)  ? "a block device"
                       : S_ISSOCK(st.st_mode) ? "a socket"
                                              : "not a regular file";
    throw IoError(name + ": the " + what + " is " + kind + ", not a regular file", path.string());
  }
  if (static_cast<unsigned long long>(st.st_size) > maxBytes) {
    ::close(fd);
    throw IoError(name + ": the " + what + " is too large (" + std::to_string(st.st_size) +
                      " bytes; at most " + std::to_string(maxBytes) + ")",
                  path.string());
  }
  // Regular files never block: back to ordinary reads.
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  size = st.st_size;
  return fd;
}

}  // namespace

std::string readRegularFile(const fs::path& path, std::size_t maxBytes, const std::string& what) {
  off_t size = 0;
  const int fd = openRegularInput(path, maxBytes, what, size);
  std::string text;
  text.reserve(static_cast<size_t>(size));
  char buffer[1 << 16];
  while (true) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int error = errno;
      ::close(fd);
      throw IoError(
          abbreviate(path.string()) + ": cannot read " + what + ": " + std::strerror(error),
          path.string());
    }
    if (n == 0) break;
    text.append(buffer, static_cast<size_t>(n));
    if (text.size() > maxBytes) {  // grew while we read
      ::close(fd);
      throw IoError(abbreviate(path.string()) + ": the " + what + " is too large (at most " +
                        std::to_string(maxBytes) + " bytes)",
                    path.string());
    }
  }
  ::close(fd);
  return text;
}

void checkRegularInputFile(const fs::path& path, std::size_t maxBytes, const std::string& what) {
  off_t size = 0;
  ::close(openRegularInput(path, maxBytes, what, size));
}

std::string portableNameProblem(const std::string& name, std::size_t maxBytes) {
  if (name.empty()) return "is empty";
  if (name == "." || name == "..") return "is \"" + name + "\"";
  if (name.size() > maxBytes)
    return "is too long (" + std::to_string(name.size()) + " bytes; at most " +
           std::to_string(maxBytes) + ")";
  for (size_t i = 0; i < name.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    if (c < 0x20 || c == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02x", c);
      return std::string("contains a control character (byte ") + hex + " at position " +
             std::to_string(i) + ")";
    }
    if (c == '/' || c == '\\') return std::string("contains '") + static_cast<char>(c) + "'";
  }
  return "";
}

std::string abbreviate(const std::string& text, std::size_t maxChars) {
  std::string out;
  size_t i = 0;
  for (; i < text.size() && out.size() < maxChars; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    } else {
      out.push_back(static_cast<char>(c));
    }
  }
  if (i < text.size()) {
    // Do not cut a UTF-8 sequence in half.
    while (!out.empty() && (static_cast<unsigned char>(out.back()) & 0xC0) == 0x80) out.pop_back();
    if (!out.empty() && (static_cast<unsigned char>(out.back()) & 0xC0) == 0xC0) out.pop_back();
    out += "... (" + std::to_string(text.size()) + " characters)";
  }
  return out;
}

}  // namespace egg
