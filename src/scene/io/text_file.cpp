#include "scene/io/text_file.h"

#include <fmt/format.h>
#include <radiosity/error.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace rad {

std::string readTextFile(const std::string& path, const std::string& what, size_t maxBytes) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path, "cannot open " + what + ": it is a directory");
  const auto tooLarge = [&] {
    return InputError(path, fmt::format("{} is larger than {} MiB, the most read into memory", what,
                                        maxBytes >> 20));
  };
  if (const auto size = std::filesystem::file_size(path, ec); !ec && size > maxBytes)
    throw tooLarge();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open " + what + " (missing or unreadable)");
  // Read in chunks up to the limit: a device or a pipe has no size to check beforehand.
  std::string text;
  std::vector<char> chunk(size_t(1) << 20);
  while (in) {
    in.read(chunk.data(), std::streamsize(chunk.size()));
    text.append(chunk.data(), size_t(in.gcount()));
    if (text.size() > maxBytes) throw tooLarge();
  }
  if (in.bad()) throw InputError(path, "cannot read " + what);
  return text;
}

std::string textPosition(std::string_view text, size_t offset) {
  offset = std::min(offset, text.size());
  const size_t line = size_t(std::count(text.begin(), text.begin() + long(offset), '\n')) + 1;
  const size_t lineStart = offset == 0 ? std::string_view::npos : text.rfind('\n', offset - 1);
  const size_t column = lineStart == std::string_view::npos ? offset + 1 : offset - lineStart;
  return fmt::format("{}:{}", line, column);
}

std::vector<std::string_view> splitWords(std::string_view line) {
  std::vector<std::string_view> words;
  size_t i = 0;
  auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (i < line.size()) {
    while (i < line.size() && blank(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !blank(line[i])) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

std::optional<double> parseNumber(std::string_view token) {
  if (!token.empty() && token[0] == '+') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
  double v = 0.0;
  auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return v;
}

std::string parentDirectory(const std::string& path) {
  return std::filesystem::path(path).parent_path().string();
}

std::string fileStem(const std::string& path) {
  return std::filesystem::path(path).stem().string();
}

std::string resolvePath(const std::string& directory, const std::string& relative) {
  const std::filesystem::path p(relative);
  if (p.is_absolute() || directory.empty()) return p.string();
  return (std::filesystem::path(directory) / p).string();
}

}  // namespace rad
