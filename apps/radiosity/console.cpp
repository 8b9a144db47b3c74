#include "console.h"

#include <fmt/format.h>

#include <atomic>
#include <csignal>
#include <iostream>
#include <memory>
#include <ostream>
#include <unistd.h>

namespace rad::cli {

namespace {

std::atomic<bool> gInterrupted{false};

extern "C" void onInterrupt(int) { gInterrupted.store(true); }

}  // namespace

void Console::warn(const std::string& message) {
  finishProgress();
  err_ << "radiosity: warning: " << message << "\n";
}

void Console::info(const std::string& message) {
  if (quiet_) return;
  finishProgress();
  err_ << message << "\n";
}

void Console::detail(const std::string& message) {
  if (verbose_) info(message);
}

ProgressCallback Console::progress(const std::string& label) {
  const bool draw = !quiet_ && &err_ == &std::cerr && isatty(STDERR_FILENO);
  auto started = std::make_shared<Stopwatch>();
  return [this, draw, label, started](double fraction) {
    if (draw) {
      constexpr int kWidth = 40;
      const int filled = int(fraction * kWidth + 0.5);
      err_ << fmt::format("\r{} [{}{}] {:5.1f}% {:6.1f} s", label, std::string(filled, '='),
                          std::string(kWidth - filled, ' '), 100.0 * fraction, started->seconds())
           << std::flush;
      barDrawn_ = true;
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

InterruptGuard::~InterruptGuard() { std::signal(SIGINT, SIG_DFL); }

bool InterruptGuard::interrupted() { return gInterrupted.load(); }

}  // namespace rad::cli
