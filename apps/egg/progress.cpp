#include "apps/egg/progress.hpp"

#include <fmt/core.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <iostream>

namespace egg::app {

std::string progressText(double fraction, const std::string& what, double elapsedS, int width) {
  if (!std::isfinite(fraction)) fraction = 0.0;
  fraction = std::clamp(fraction, 0.0, 1.0);
  width = std::max(width, 1);
  const int filled = static_cast<int>(std::floor(fraction * width + 1e-9));
  return fmt::format("[{}{}] {:>3.0f}% {} ({:.1f} s)", std::string(filled, '#'),
                     std::string(width - filled, '.'), std::floor(100.0 * fraction + 1e-9), what,
                     elapsedS);
}

bool ProgressLine::stderrIsTerminal() { return isatty(STDERR_FILENO) != 0; }

ProgressLine::ProgressLine(bool enabled)
    : enabled_(enabled && stderrIsTerminal()), started_(std::chrono::steady_clock::now()) {}

ProgressLine::~ProgressLine() { finish(); }

void ProgressLine::update(double fraction, const std::string& what) {
  if (!enabled_) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  std::string line = progressText(fraction, what, elapsed);
  const size_t length = line.size();
  if (length < lastLength_)
    line += std::string(lastLength_ - length, ' ');  // wipe a longer previous line
  lastLength_ = length;
  std::cerr << '\r' << line << std::flush;
  drawn_ = true;
}

void ProgressLine::finish() {
  if (!drawn_) return;
  std::cerr << '\n' << std::flush;
  drawn_ = false;
  lastLength_ = 0;
}

StageLog::StageLog(std::ostream& out, double heartbeatS)
    : out_(out), heartbeatS_(heartbeatS), started_(std::chrono::steady_clock::now()) {}

void StageLog::update(double fraction, const std::string& what) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  const std::string stage = what.substr(0, what.find(':'));
  if (stage == stage_ && elapsed - lastLineS_ < heartbeatS_) return;
  const bool entered = stage != stage_;
  stage_ = stage;
  lastLineS_ = elapsed;
  const double percent = std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) * 100.0 : 0.0;
  out_ << fmt::format("egg: {:7.1f} s {:3.0f}% {}{}\n", elapsed, percent, what,
                      entered ? "" : " (still)")
       << std::flush;
}

void ProgressLine::clear() {
  if (!drawn_) return;
  std::cerr << '\r' << std::string(lastLength_, ' ') << '\r' << std::flush;
  drawn_ = false;
  lastLength_ = 0;
}

}  // namespace egg::app
