#include "console.h"

#include <fmt/format.h>
#include <radiosity/error.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <iostream>
#include <memory>
#include <optional>
#include <ostream>

namespace rad::cli {

namespace {

std::atomic<bool> gInterrupted{false};

extern "C" void onInterrupt(int) {
  gInterrupted.store(true);
}

}  // namespace

void Console::warn(const std::string& message) {
  if (!speaksWarnings_) return;
  warnings_.push_back(message);
  if (quiet_) return;
  finishProgress();
  err_ << "radiosity: warning: " << message << "\n";
}

void Console::summarizeWarnings() {
  if (quiet_ || warnings_.empty()) return;
  finishProgress();
  err_ << fmt::format("radiosity: {} warning{}\n", warnings_.size(),
                      warnings_.size() == 1 ? "" : "s");
}

void Console::info(const std::string& message) {
  if (quiet_) return;
  finishProgress();
  err_ << message << "\n";
}

void Console::detail(const std::string& message) {
  if (verbose_) info(message);
}

std::string durationText(double seconds) {
  const long s = std::lround(std::max(seconds, 0.0));
  if (s < 60) return fmt::format("{} s", s);
  if (s < 3600) return fmt::format("{} min {:02} s", s / 60, s % 60);
  const long m = (s + 30) / 60;
  return fmt::format("{} h {:02} min", m / 60, m % 60);
}

double secondsLeft(double startFraction, double fraction, double seconds) {
  // Too little done (or too soon) for its rate to say anything yet.
  constexpr double kLeastFraction = 0.01, kLeastSeconds = 1.0;
  const double done = fraction - startFraction;
  if (done < kLeastFraction || seconds < kLeastSeconds) return -1.0;
  return seconds * (1.0 - fraction) / done;
}

ProgressCallback Console::progress(const std::string& label) {
  // A bar redrawn in place on a terminal; in a log (stderr to a file or a pipe: a batch job, CI)
  // a line every few seconds, so that a long run is never silent and a short one stays quiet.
  constexpr double kSecondsBetweenLines = 5.0;
  const bool toStderr = !quiet_ && &err_ == &std::cerr;
  const bool draw = toStderr && isatty(STDERR_FILENO), log = toStderr && !draw;
  // The time left is judged from the first report on, so that setup before it (voxelizing, a
  // first shot) does not count as the computation's own pace.
  struct Pace {
    Stopwatch sinceCreated, sinceLine;
    std::optional<Stopwatch> sinceFirst;
    double firstFraction = 0.0;
  };
  auto pace = std::make_shared<Pace>();
  return [this, draw, log, label, pace](double fraction) {
    if (!pace->sinceFirst) {
      pace->sinceFirst.emplace();
      pace->firstFraction = fraction;
    }
    const double left = secondsLeft(pace->firstFraction, fraction, pace->sinceFirst->seconds());
    const std::string times = durationText(pace->sinceCreated.seconds()) +
                              (left >= 0.0 ? ", about " + durationText(left) + " left" : "");
    if (draw) {
      constexpr int kWidth = 40;
      const int filled = int(fraction * kWidth + 0.5);
      err_ << fmt::format("\r{} [{}{}] {:5.1f}% {:>10}\x1b[K", label, std::string(filled, '='),
                          std::string(kWidth - filled, ' '), 100.0 * fraction, times)
           << std::flush;
      barDrawn_ = true;
    } else if (log && pace->sinceLine.seconds() >= kSecondsBetweenLines) {
      err_ << fmt::format("{}: {:.1f}% done, {}\n", label, 100.0 * fraction, times) << std::flush;
      pace->sinceLine = Stopwatch();
    }
    return !InterruptGuard::interrupted();
  };
}

void Console::finishProgress() {
  if (!barDrawn_) return;
  err_ << "\n";
  barDrawn_ = false;
}

InterruptGuard::InterruptGuard() {
  gInterrupted.store(false);
  std::signal(SIGINT, onInterrupt);
}

InterruptGuard::~InterruptGuard() {
  std::signal(SIGINT, SIG_DFL);
}

bool InterruptGuard::interrupted() {
  return gInterrupted.load();
}

void InterruptGuard::throwIfInterrupted() {
  if (interrupted()) throw Cancelled();
}

}  // namespace rad::cli
