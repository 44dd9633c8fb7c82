#pragma once
// Typed exceptions of eggshell (docs/architecture.md "Conventions"). Libraries throw these and
// never call abort/exit; the `egg` command maps them to messages and exit codes (2 = bad input, 1 =
// failure).
#include <stdexcept>
#include <string>
#include <utility>

namespace egg {

// Base of every eggshell error, so callers can catch the family in one place.
// Where it is known, the file and the field (a scene key's dotted path, "lamella.width_m") at
// fault travel beside the message, for `egg --json`'s error object (issue 39).
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message, std::string file = {}, std::string field = {})
      : std::runtime_error(message), file_(std::move(file)), field_(std::move(field)) {}
  const std::string& file() const noexcept { return file_; }
  const std::string& field() const noexcept { return field_; }

 private:
  std::string file_, field_;
};

// The caller handed us something unusable: a bad option, a broken mesh, a malformed scene.
// The message names the file, field or element at fault.
class InvalidInput : public Error {
 public:
  using Error::Error;
};

// A file could not be read (missing, unreadable, unsupported format, no triangles) or an output was
// asked in an unsupported format: bad input (exit 2). Failures while writing are WriteError.
class IoError : public Error {
 public:
  using Error::Error;
};

// An output could not be written (folder missing or not writable, disk full, rename failed). The
// inputs were fine, so the run failed (exit 1), not the caller (exit 2); writers leave nothing
// half-written behind (core/io/atomic_file.hpp).
class WriteError : public IoError {
 public:
  using IoError::IoError;
};

// A numerical solve did not produce a usable answer (no convergence, singular system).
class SolverFailure : public Error {
 public:
  using Error::Error;
};

// A patch violates the EGG criteria (Section 2.4.1 / 3.4): no feasible alpha_bar, eta too large,
// crossing boundaries. The patching stage catches it and splits the patch.
class InfeasiblePatch : public Error {
 public:
  using Error::Error;
};

}  // namespace egg
