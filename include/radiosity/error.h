#pragma once
// Error policy (docs/CONTRIBUTING.md): bad user input throws InputError, whose message names the
// file (and line or JSON path) and what was expected; the CLI prints it on one line and exits 2.
// Any other exception is a runtime failure (exit 1). Broken invariants are assertions.

#include <stdexcept>
#include <string>

namespace rad {

class InputError : public std::runtime_error {
 public:
  /// `where` is "file", "file:line" or "file: /json/path"; `what` says what was wrong and what
  /// was expected, e.g. "fov_deg 200 out of range (0, 180)". The message is kept to one
  /// printable line of bounded length, whatever a file put in the parts it echoes.
  InputError(const std::string& where, const std::string& what);
  explicit InputError(const std::string& message);
};

/// Thrown when a progress callback asks a long computation to stop.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
  /// `howToGoOn` tells the user how the work continues ("goes on from iteration 3 when run
  /// again"); what() returns it too.
  explicit Cancelled(const std::string& howToGoOn)
      : std::runtime_error(howToGoOn), howToGoOn_(howToGoOn) {}
  /// How the work goes on when run again; empty when nothing of it was kept.
  const std::string& howToGoOn() const { return howToGoOn_; }

 private:
  std::string howToGoOn_;
};

}  // namespace rad
