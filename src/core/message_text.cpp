#include <fmt/format.h>
#include <radiosity/message_text.h>

namespace rad {

namespace {

// Longest message printed whole; a longer one keeps its head (where and what) and its tail.
constexpr size_t kMaxMessage = 1000;

std::string escapeControl(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '\n')
      out += "\\n";
    else if (c == '\t')
      out += "\\t";
    else if (c == '\r')
      out += "\\r";
    else if (u < 0x20 || u == 0x7f)
      out += fmt::format("\\x{:02x}", u);
    else
      out += c;
  }
  return out;
}

}  // namespace

std::string printableMessage(std::string_view text) {
  if (text.size() <= kMaxMessage) return escapeControl(text);
  const size_t head = kMaxMessage * 2 / 3, tail = kMaxMessage - head;
  return escapeControl(text.substr(0, head)) +
         fmt::format(" [... {} bytes left out ...] ", text.size() - head - tail) +
         escapeControl(text.substr(text.size() - tail));
}

std::string quotedToken(std::string_view token, size_t maxChars) {
  if (token.size() <= maxChars) return fmt::format("'{}'", escapeControl(token));
  return fmt::format("'{}...' ({} bytes)", escapeControl(token.substr(0, maxChars)), token.size());
}

}  // namespace rad
