#pragma once
// Every file eggshell writes goes through here: the text is written to a temporary file in the
// target's folder and renamed into place, so a crash, a full disk or a reader racing the writer
// never sees a half-written file (DEVELOPERS.md: nothing lost or half-written).
// Every file eggshell reads by itself (scenes) goes through readRegularFile: a FIFO, a device or
// a folder given as an input is an error, never a hang.
#include <sys/types.h>

#include <cstddef>
#include <filesystem>
#include <string>

namespace egg {

// Writes `text` to `path` atomically. Throws WriteError naming the path when the file cannot be
// written (folder missing, disk full: nothing is left behind) and when `path` exists and is not a
// regular file (a device, a FIFO, a folder): such a target is refused, never replaced. A symbolic
// link to a regular file is written through (the file it points to is replaced).
void writeFileAtomically(const std::filesystem::path& path, const std::string& text);

// The check writeFileAtomically makes before writing, for writers that produce several files:
// returns the path to write (a symbolic link resolved) or throws WriteError.
std::filesystem::path checkedOutputTarget(const std::filesystem::path& path);

// A random suffix for temporary names (8 characters of [0-9a-z]).
std::string temporarySuffix();

// A new folder of this process's own in $TMPDIR (mkdtemp: created here, mode 0700, never an
// existing folder or a planted link), named `stem`-XXXXXX. Throws WriteError naming $TMPDIR when
// it cannot be made (missing, full, read-only). Benchmarks and the stress suite work in one, so
// that their cleanup removes nothing but what they made (issue 40).
std::filesystem::path makePrivateTempFolder(const std::string& stem);

// Temporary files of writeFileAtomically are named `.egg-tmp-PID-SUFFIX` in the target's folder.
// A kill leaves them behind; the next write into that folder removes those whose process is dead.
std::string temporaryFilePrefix();  // ".egg-tmp-"
// Parses the PID out of `name` when it is PREFIX + digits + "-" + anything; -1 otherwise.
pid_t leftoverPid(const std::string& name, const std::string& prefix);
// True when a process `pid` exists (kill(pid, 0) does not say ESRCH).
bool processAlive(pid_t pid);
// An exclusive flock held on a file or folder for the lock's lifetime: the mark that a run's
// staging folder or temporary file is at work. Unlike a PID it is seen from every PID namespace
// on the machine (containers) and, on NFS, through its lock manager (issue 40). A file system
// without flock leaves it unheld; leftoverInUse then falls back on the PID.
class LiveLock {
 public:
  explicit LiveLock(const std::filesystem::path& path);
  ~LiveLock();
  LiveLock(const LiveLock&) = delete;
  LiveLock& operator=(const LiveLock&) = delete;
  bool held() const { return held_; }

 private:
  int fd_ = -1;
  bool held_ = false;
};
// Whether the leftover `path`, named with `pid`, belongs to a process still at work: someone
// holds its LiveLock, or a process of that PID is alive here.
bool leftoverInUse(const std::filesystem::path& path, pid_t pid);
// Removes the leftovers `PREFIX<pid>-*` no process is at work on (leftoverInUse) directly in
// `folder` (regular files, or folders when `folders` is true). Never throws; returns how many were
// removed.
int removeDeadLeftovers(const std::filesystem::path& folder, const std::string& prefix,
                        bool folders);

// Reads a whole input file. Throws IoError naming the file (and `what` it is: "scene file") when it
// does not exist, is not a regular file (a folder, a FIFO, a device: opened without blocking and
// checked before any read), is larger than `maxBytes`, or cannot be read.
std::string readRegularFile(const std::filesystem::path& path, std::size_t maxBytes,
                            const std::string& what);

// The same checks without reading (for inputs another library opens by name, as assimp does).
void checkRegularInputFile(const std::filesystem::path& path, std::size_t maxBytes,
                           const std::string& what);

// Checks that `name` can be a file name on any common system: non-empty, at most `maxBytes` bytes,
// no NUL or other control character, no '/' or '\\', not "." or "..". Returns an empty string when
// it can, otherwise why not ("contains a control character (byte 0x00 at 1)").
std::string portableNameProblem(const std::string& name, std::size_t maxBytes);

// `text` shortened to at most `maxChars` characters for a message ("abc… (12345 characters)"),
// control characters shown as \xNN so that a message never carries a NUL or an escape sequence.
std::string abbreviate(const std::string& text, std::size_t maxChars = 200);

}  // namespace egg
