#pragma once
// The run folder of `egg run`: written whole or not at all, and never over anything the tool did
// not write itself.
#include "core/io/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace egg::pipeline {

// An output folder that appears whole or not at all: files are written into a hidden sibling
// staging folder, and commit() swaps it in place of the target (replacing an earlier run).
// If commit() is never called (an exception), the staging folder is removed.
//
// The one output-safety layer of `egg run` (issue 17):
// - The target's name must be a portable file name (no NUL or control character, at most
//   kMaxRunFolderName bytes, so that the hidden sibling names fit NAME_MAX), and the target must
//   not be a symbolic link, a file or the root.
// - An existing target is replaced only if it is empty, or a complete earlier run folder of this
//   tool holding nothing but what the tool wrote: its marker file kRunMarker lists every file of
//   the run with its size and modification time (written at commit). A folder without the marker,
//   with an older marker without the list, or with any file not on the list (the user's scene,
//   notes, an edited report) is refused with a message, at construction and again at commit.
// - Only these paths are ever removed: our own staging folder, the earlier run folder after it
//   was renamed aside, and leftovers of interrupted runs of the same target
//   (`.NAME.staging-PID-*`, `.NAME.previous-PID-*`) whose process is dead. A kill between the two
//   renames of commit() leaves the earlier run as `.NAME.previous-PID-*` and no target: the next
//   run puts it back before anything else.
constexpr const char* kRunMarker = ".eggshell-run";
constexpr std::size_t kMaxRunFolderName = 200;

class StagedDirectory {
 public:
  explicit StagedDirectory(std::filesystem::path target);
  ~StagedDirectory();
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;

  // Where to write files now (the staging folder).
  const std::filesystem::path& staging() const { return staging_; }
  void commit();
  // What the constructor did about leftovers of interrupted runs (also printed on stderr).
  const std::vector<std::string>& recoveryNotes() const { return notes_; }

 private:
  void recoverInterruptedRuns();

  std::filesystem::path target_;
  std::filesystem::path staging_;
  std::unique_ptr<LiveLock>
      lock_;  // on staging_, for the run's life (the folder keeps it on commit)
  bool committed_ = false;
  std::vector<std::string> notes_;
};

// Why `folder` may not be replaced by a run (empty string when it may): not a folder, no marker,
// a marker without the file list, or a file the tool did not write. Exposed for tests.
std::string runFolderReplaceProblem(const std::filesystem::path& folder);

}  // namespace egg::pipeline
