#pragma once
// Small text helpers shared by the scene file readers: whole-file reads with the project's
// "cannot open" error, whitespace tokens and strict number parsing.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rad {

/// Largest scene, OBJ or MTL file read into memory (an OBJ of 30 million triangles).
constexpr size_t kMaxTextFileBytes = size_t(2) << 30;

/// The whole file as bytes. Throws InputError(path, "cannot open ...") if it cannot be read, and
/// InputError naming the limit if it holds more than `maxBytes` (a device such as /dev/zero
/// is read no further than that).
std::string readTextFile(const std::string& path, const std::string& what,
                         size_t maxBytes = kMaxTextFileBytes);

/// "line:column" (1-based) of a byte offset in a text, for messages about where parsing stopped.
std::string textPosition(std::string_view text, size_t offset);

/// Splits a line on blanks (spaces, tabs, CR).
std::vector<std::string_view> splitWords(std::string_view line);

/// The number the whole token spells ("1", "-2.5e3", "+4"), or nothing. "nan" and "inf" parse
/// (so the caller can say "not finite" rather than "not a number").
std::optional<double> parseNumber(std::string_view token);

/// Directory part of a path ("" for a bare file name) and the file name without directory and
/// extension.
std::string parentDirectory(const std::string& path);
std::string fileStem(const std::string& path);
/// Joins a relative path to a directory; absolute paths are returned unchanged.
std::string resolvePath(const std::string& directory, const std::string& relative);

}  // namespace rad
