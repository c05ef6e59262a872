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

// Strings of a config or scene description name files, devices and folders: a NUL would cut them
// where the OS reads them (and every message quoting them), other control characters hide what
// they say. Throws rtbench::Error "<at>control character U+NNNN at byte i ..." on the first.
void refuseControlCharacters(const std::string& at, const std::string& value);

}  // namespace rtbench
