#pragma once
// Small text helpers shared by the scene file readers: whole-file reads with the project's
// "cannot open" error, whitespace tokens and strict number parsing.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rad {

/// The whole file as bytes. Throws InputError(path, "cannot open ...") if it cannot be read.
std::string readTextFile(const std::string& path, const std::string& what);

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
