#pragma once
// A one-line progress bar on stderr for the long commands (issue 18): shown only when stderr is a
// terminal, so logs and pipes stay clean; redrawn in place with a carriage return.
#include <chrono>
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

}  // namespace egg::app
