#include "pipeline/run_folder.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"

#include <sys/stat.h>
#include <unistd.h>
#include <algorithm>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <system_error>

namespace egg::pipeline {

using nlohmann::json;

namespace {

namespace fs = std::filesystem;

constexpr int kManifestVersion = 2;

long long mtimeNs(const fs::path& file) {
  struct stat st {};
  if (::lstat(file.c_str(), &st) != 0) return -1;
  return static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec;
}

// Every file of a run folder but the marker, relative paths with size and modification time.
json listRunFiles(const fs::path& folder) {
  json files = json::array();
  for (auto it = fs::recursive_directory_iterator(folder); it != fs::recursive_directory_iterator();
       ++it) {
    const fs::file_status status = it->symlink_status();
    if (fs::is_directory(status)) continue;
    const fs::path relative = it->path().lexically_relative(folder);
    if (relative == fs::path(kRunMarker)) continue;
    if (!fs::is_regular_file(status)) {
      files.push_back(
          {{"path", relative.string()}, {"bytes", -1}, {"mtime_ns", -1}});  // never matches
      continue;
    }
    files.push_back({{"path", relative.string()},
                     {"bytes", static_cast<long long>(fs::file_size(it->path()))},
                     {"mtime_ns", mtimeNs(it->path())}});
  }
  return files;
}

// Every folder of a run folder, relative paths (the marker lists them, so that an empty folder
// someone made in the run folder afterwards is theirs, not the run's).
json listRunFolders(const fs::path& folder) {
  json folders = json::array();
  for (auto it = fs::recursive_directory_iterator(folder); it != fs::recursive_directory_iterator();
       ++it)
    if (fs::is_directory(it->symlink_status()))
      folders.push_back(it->path().lexically_relative(folder).string());
  return folders;
}

std::string markerText(const json& files, const json& folders) {
  json marker{{"eggshell_run", kManifestVersion},
              {"note",
               "eggshell run folder: replaced whole by the next egg run into it, if it holds only "
               "these files"},
              {"files", files},
              {"folders", folders}};
  return marker.dump(1) + "\n";
}

}  // namespace

std::string runFolderReplaceProblem(const fs::path& folder) {
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(folder, ec);
  if (ec || !fs::exists(status)) return "";
  if (fs::is_symlink(status))
    return "is a symbolic link (give the folder it points to, or another --out)";
  if (!fs::is_directory(status)) return "exists and is not a folder";
  const bool empty = fs::is_empty(folder, ec);
  if (ec) return "cannot be read: " + ec.message();
  if (empty) return "";
  const fs::path markerPath = folder / kRunMarker;
  if (!fs::is_regular_file(fs::symlink_status(markerPath, ec)))
    return std::string("exists and is not an eggshell run folder (no ") + kRunMarker + ")";
  json marker;
  try {
    marker = json::parse(readRegularFile(markerPath, 64 << 20, "run marker"));
  } catch (const std::exception&) {
    marker = nullptr;
  }
  if (!marker.is_object() || marker.value("eggshell_run", 0) != kManifestVersion ||
      !marker.contains("files") || !marker["files"].is_array()) {
    return std::string("holds an eggshell marker (") + kRunMarker +
           ") without the list of the files the run wrote (an interrupted or older run); "
           "move what you want to keep and remove the folder yourself";
  }
  std::map<std::string, std::pair<long long, long long>> written;
  for (const auto& f : marker["files"]) {
    if (!f.is_object() || !f.contains("path") || !f["path"].is_string()) continue;
    written[f["path"].get<std::string>()] = {f.value("bytes", -2LL), f.value("mtime_ns", -2LL)};
  }
  json present;
  try {
    present = listRunFiles(folder);
  } catch (const std::exception& e) {
    return std::string("cannot be listed: ") + e.what();
  }
  // Folders: the run's own are in the marker (or, in a marker from before folders were listed,
  // hold a file the run wrote); any other is someone's (an empty folder made afterwards, issue 40).
  std::set<std::string> madeFolders;
  if (marker.contains("folders") && marker["folders"].is_array())
    for (const auto& f : marker["folders"])
      if (f.is_string()) madeFolders.insert(f.get<std::string>());
  json folders;
  try {
    folders = listRunFolders(folder);
  } catch (const std::exception& e) {
    return std::string("cannot be listed: ") + e.what();
  }
  for (const auto& f : folders) {
    const std::string path = f.get<std::string>();
    if (madeFolders.count(path)) continue;
    const auto below = written.lower_bound(path + "/");
    if (below != written.end() && below->first.compare(0, path.size() + 1, path + "/") == 0)
      continue;
    return "holds the folder " + abbreviate(path) +
           ", which the earlier run did not make; move it out or choose another --out";
  }
  for (const auto& f : present) {
    const std::string path = f["path"].get<std::string>();
    const auto it = written.find(path);
    if (it == written.end())
      return "holds " + abbreviate(path) +
             ", which the earlier run did not write; move it out or choose another --out";
    if (it->second.first != f["bytes"].get<long long>() ||
        it->second.second != f["mtime_ns"].get<long long>())
      return "holds " + abbreviate(path) +
             ", changed since the earlier run wrote it; move it out or choose another --out";
  }
  return "";
}

StagedDirectory::StagedDirectory(std::filesystem::path target) : target_(std::move(target)) {
  if (target_.empty()) throw InvalidInput("output folder: empty path");
  if (target_.native().find('\0') != std::string::npos)
    throw InvalidInput("output folder " + abbreviate(target_.string()) +
                       ": the path contains a NUL character");
  target_ = fs::absolute(target_).lexically_normal();
  if (target_.filename().empty()) target_ = target_.parent_path();
  const std::string name = target_.filename().string();
  if (name.empty() || target_ == target_.root_path())
    throw InvalidInput("output folder: cannot be the root folder");
  if (const std::string problem = portableNameProblem(name, kMaxRunFolderName); !problem.empty())
    throw InvalidInput("output folder " + abbreviate(target_.string()) + ": the name " + problem);
  const fs::path parent = target_.parent_path();
  std::error_code ec;
  fs::create_directories(parent, ec);
  // A file where the path needs a folder is the user's path, not the machine: bad input (exit 2).
  if (ec == std::errc::not_a_directory || ec == std::errc::file_exists)
    throw InvalidInput("output folder " + abbreviate(target_.string()) + ": " +
                       abbreviate(parent.string()) +
                       " is not a folder (a file stands where the path needs one)");
  if (ec) throw WriteError(parent.string() + ": cannot create folder: " + ec.message());
  recoverInterruptedRuns();
  if (const std::string problem = runFolderReplaceProblem(target_); !problem.empty())
    throw InvalidInput(target_.string() + ": " + problem + "; refusing to replace it");
  staging_ =
      parent / ("." + name + ".staging-" + std::to_string(::getpid()) + "-" + temporarySuffix());
  fs::create_directory(staging_, ec);
  if (ec) throw WriteError(staging_.string() + ": cannot create staging folder: " + ec.message());
  // Held until the run ends: a run into the same --out from another container or host sees the
  // folder at work, which our PID could not tell it (issue 40).
  lock_ = std::make_unique<LiveLock>(staging_);
  try {
    // The marker from the start (an interrupted run's staging folder is recognised by it); the
    // file list is added at commit.
    writeFileAtomically(staging_ / kRunMarker, "eggshell run in progress (staging folder)\n");
  } catch (...) {
    // The destructor does not run for a throwing constructor: remove the staging folder here.
    std::error_code ignored;
    fs::remove_all(staging_, ignored);
    throw;
  }
}

void StagedDirectory::recoverInterruptedRuns() {
  const fs::path parent = target_.parent_path();
  const std::string name = target_.filename().string();
  const std::string stagingPrefix = "." + name + ".staging-";
  const std::string previousPrefix = "." + name + ".previous-";
  std::vector<fs::path> previous, staging;
  std::error_code ec;
  for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string entry = it->path().filename().string();
    std::error_code typeError;
    if (!fs::is_directory(it->symlink_status(typeError)) || typeError) continue;
    for (auto [prefix, list] :
         {std::pair{&previousPrefix, &previous}, std::pair{&stagingPrefix, &staging}}) {
      const pid_t pid = leftoverPid(entry, *prefix);
      if (pid > 0 && pid != ::getpid() && !leftoverInUse(it->path(), pid))
        list->push_back(it->path());
    }
  }
  auto note = [&](const std::string& text) {
    notes_.push_back(text);
    std::cerr << "egg: " << text << "\n";
  };
  auto isOurs = [](const fs::path& folder) {
    std::error_code e;
    return fs::is_regular_file(fs::symlink_status(folder / kRunMarker, e)) ||
           fs::is_empty(folder, e);
  };
  // A kill between the two renames of commit(): the earlier run is only in .NAME.previous-*.
  std::sort(previous.begin(), previous.end(),
            [](const fs::path& a, const fs::path& b) { return mtimeNs(a) > mtimeNs(b); });
  for (const fs::path& p : previous) {
    std::error_code e;
    if (!fs::exists(fs::symlink_status(target_, e))) {
      fs::rename(p, target_, e);
      if (!e)
        note("recovered the earlier run " + target_.string() + " from an interrupted commit (" +
             p.filename().string() + ")");
    } else if (isOurs(p)) {
      fs::remove_all(p, e);
      if (!e)
        note("removed " + p.string() +
             ", an earlier run an interrupted commit had already replaced");
    }
  }
  for (const fs::path& s : staging) {
    std::error_code e;
    if (!isOurs(s)) continue;
    fs::remove_all(s, e);
    if (!e) note("removed " + s.string() + ", the staging folder of an interrupted run");
  }
}

StagedDirectory::~StagedDirectory() {
  if (!committed_) {
    std::error_code ignored;
    std::filesystem::remove_all(staging_, ignored);
  }
}

void StagedDirectory::commit() {
  std::error_code ec;
  // The run took a while: the target is checked again (a file added meanwhile is never lost).
  if (const std::string problem = runFolderReplaceProblem(target_); !problem.empty())
    throw InvalidInput(target_.string() + ": " + problem +
                       "; refusing to replace it (the results are not written)");
  try {
    writeFileAtomically(staging_ / kRunMarker,
                        markerText(listRunFiles(staging_), listRunFolders(staging_)));
  } catch (const WriteError&) {
    throw;
  } catch (const std::exception& e) {
    throw WriteError(staging_.string() + ": cannot list the results: " + e.what());
  }
  fs::path previous;
  const fs::file_status targetStatus = fs::symlink_status(target_, ec);
  if (ec && targetStatus.type() != fs::file_type::not_found)
    throw WriteError(target_.string() + ": cannot inspect the output folder: " + ec.message());
  const bool exists = fs::exists(targetStatus);
  // The earlier results are at work while they are .NAME.previous-*: a run elsewhere must not put
  // them back or remove them between our two renames.
  std::unique_ptr<LiveLock> previousLock;
  if (exists) previousLock = std::make_unique<LiveLock>(target_);
  if (exists) {
    previous = target_.parent_path() / ("." + target_.filename().string() + ".previous-" +
                                        std::to_string(::getpid()) + "-" + temporarySuffix());
    fs::rename(target_, previous, ec);
    if (ec)
      throw WriteError(target_.string() + ": cannot replace the earlier results: " + ec.message());
  }
  fs::rename(staging_, target_, ec);
  if (ec) {
    std::string message =
        target_.string() + ": cannot move the results into place: " + ec.message();
    if (!previous.empty()) {
      std::error_code restore;
      fs::rename(previous, target_, restore);  // put the old results back
      if (restore) {
        message += "; the earlier results could not be put back either (" + restore.message() +
                   ") and are in " + previous.string() + " (the next run puts them back)";
      }
    }
    throw WriteError(message);
  }
  committed_ = true;
  if (!previous.empty()) fs::remove_all(previous, ec);
}

}  // namespace egg::pipeline
