#pragma once
// One field of a CSV row as RFC 4180 writes it, shared by the CSV exports.

#include <string>

namespace rad {

/// `s` as it is, or quoted (its quotes doubled) when it holds a separator or a quote.
inline std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string quoted = "\"";
  for (char c : s) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace rad
