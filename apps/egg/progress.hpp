#pragma once
// A one-line progress bar on stderr for the long commands (issue 18): shown only when stderr is a
// terminal, so logs and pipes stay clean; redrawn in place with a carriage return.
#include <chrono>
#include <ostream>
#include <string>

namespace egg::app {

// The bar's text: "[#####.....]  45% what (12.3 s)", `width` cells; fraction clamped to [0, 1].
std::string progressText(double fraction, const std::string& what, double elapsedS, int width = 30);

class ProgressLine {
 public:
  // `enabled` false (or stderr not a terminal) makes every call a no-op.
  explicit ProgressLine(bool enabled);
  ~ProgressLine();  // ends the line if one was drawn
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  void update(double fraction, const std::string& what);
  void finish();  // ends the line; later updates start a new one
  void clear();   // wipes the line (for output that takes its place); later updates draw it again
  bool shown() const { return enabled_; }

  static bool stderrIsTerminal();

 private:
  bool enabled_ = false, drawn_ = false;
  std::chrono::steady_clock::time_point started_;
  size_t lastLength_ = 0;
};

// Where stderr is not a terminal (a pipe, a CI log) the bar is not drawn; instead one line when
// the run enters a stage (the text before the first ':') and one every `heartbeatS` while a stage
// goes on, so that a log shows where a long run is (issue 39: 24 s of silence).
class StageLog {
 public:
  explicit StageLog(std::ostream& out, double heartbeatS = 15.0);
  void update(double fraction, const std::string& what);

 private:
  std::ostream& out_;
  double heartbeatS_;
  std::chrono::steady_clock::time_point started_;
  std::string stage_;
  double lastLineS_ = 0.0;
};

}  // namespace egg::app
