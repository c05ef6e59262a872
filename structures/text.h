// Text from files and libraries made safe to print and to write into CSV and JSON: bytes that
// are not part of well-formed UTF-8 (RFC 3629: no overlongs, surrogates or code points beyond
// U+10FFFF) are written as \xNN.
#pragma once
#include <string>
#include <string_view>

namespace rtbench {

// Also escapes control characters except tab: for one-line messages quoting a file's bytes.
std::string printable(std::string_view text);
// Keeps control characters (line breaks in a CSV field stay line breaks).
std::string validUtf8(std::string_view text);

}  // namespace rtbench
