#pragma once
// What a command prints and where: results on `out`, warnings, progress and the summary line on
// `err`; --quiet silences all but errors (its warnings are kept for the stats file), --verbose
// adds the banner and timings.

#include <radiosity/progress.h>

#include <chrono>
#include <iosfwd>
#include <string>
#include <vector>

namespace rad::cli {

class Console {
 public:
  Console(std::ostream& out, std::ostream& err) : out_(out), err_(err) {}

  std::ostream& out() { return out_; }
  void setQuiet(bool quiet) { quiet_ = quiet; }
  void setVerbose(bool verbose) { verbose_ = verbose; }
  /// Off in the processes of a split run past rank 0: rank 0 gives the run's warnings.
  void setWarnings(bool warnings) { speaksWarnings_ = warnings; }
  bool verbose() const { return verbose_; }

  /// Printed unless --quiet, and kept either way (warnings()).
  void warn(const std::string& message);
  void info(const std::string& message);    ///< unless --quiet
  void detail(const std::string& message);  ///< only with --verbose
  /// A progress callback for a long computation named `label`: draws a bar on stderr when it
  /// is a terminal, else prints a line every 5 s (neither with --quiet), and cancels (returns
  /// false) once the user has pressed Ctrl-C.
  ProgressCallback progress(const std::string& label);
  /// Ends a progress bar's line.
  void finishProgress();
  /// The warnings given so far (none in the processes of a split run past rank 0).
  const std::vector<std::string>& warnings() const { return warnings_; }
  /// The run's closing line when it had warnings ("3 warnings"), unless --quiet.
  void summarizeWarnings();

 private:
  std::ostream& out_;
  std::ostream& err_;
  bool quiet_ = false;
  bool verbose_ = false;
  bool speaksWarnings_ = true;
  bool barDrawn_ = false;
  std::vector<std::string> warnings_;
};

/// Installs a SIGINT handler for the lifetime of the object: the first Ctrl-C asks running
/// computations to stop (through Console::progress), so no partial output is written.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  static bool interrupted();
  /// Throws rad::Cancelled if Ctrl-C came: called before the outputs are written, so that an
  /// interrupted run writes none of them.
  static void throwIfInterrupted();
};

/// A duration as a progress line shows it: "42 s", "3 min 05 s", "2 h 07 min".
std::string durationText(double seconds);

/// The time a computation still needs when it went from `startFraction` done to `fraction` done
/// in `seconds`, at that rate; negative until it has made progress to judge by.
double secondsLeft(double startFraction, double fraction, double seconds);

/// Seconds elapsed since construction.
class Stopwatch {
 public:
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace rad::cli
