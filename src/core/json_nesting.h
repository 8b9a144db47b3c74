#pragma once
// JSON parsers and printers recurse once per level of nesting, so a file of 100,000 '[' ends
// in a stack overflow. Files are checked with this scan before any parser sees them.

#include <cstddef>
#include <optional>
#include <string_view>

namespace rad {

/// Deepest nesting any file of ours needs (a glTF's node extras, a scene's keyframes) is a few
/// levels; 512 leaves room for any generator's extras and is far from a stack's limit.
constexpr size_t kMaxJsonNesting = 512;

/// The byte offset of the first '[' or '{' that opens level `maxDepth + 1`, or nothing when
/// the text never nests deeper. Brackets inside strings do not count.
std::optional<size_t> jsonNestingOverflow(std::string_view text, size_t maxDepth = kMaxJsonNesting);

}  // namespace rad
