#pragma once
// Text that goes into an error message: a file may put anything in a token (300 KB of it, raw
// control characters, a terminal escape), and a message must stay one readable line.

#include <string>
#include <string_view>

namespace rad {

/// The message on one printable line: control characters escaped (\n, \t, \xNN), and a message
/// longer than a screenful cut in the middle with the number of bytes left out.
std::string printableMessage(std::string_view text);

/// A token from a file for a message: quoted, control characters escaped, at most `maxChars`
/// characters of it followed by how long it was ('abc...' (300000 bytes)).
std::string quotedToken(std::string_view token, size_t maxChars = 60);

}  // namespace rad
