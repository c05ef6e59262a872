#include "text.h"

#include <cstdint>
#include <cstdio>

#include "error.h"

namespace rtbench {

namespace {
std::string escapeBytes(std::string_view text, bool controls) {
    std::string out;
    auto escape = [&](unsigned char c) {
        constexpr char kHex[] = "0123456789ABCDEF";
        out += "\\x";
        out += kHex[c >> 4];
        out += kHex[c & 15];
    };
    for (std::size_t i = 0; i < text.size();) {
        const unsigned char c = text[i];
        // Length of a well-formed UTF-8 sequence starting here (RFC 3629), 0 if none.
        std::size_t length = c < 0x80         ? 1
                             : (c >> 5) == 6  ? 2
                             : (c >> 4) == 14 ? 3
                             : (c >> 3) == 30 ? 4
                                              : 0;
        if (length > 1) {
            if (i + length > text.size()) length = 0;
            for (std::size_t k = 1; k < length; ++k)
                if ((static_cast<unsigned char>(text[i + k]) >> 6) != 2) length = 0;
            if (length) {  // reject overlong forms, surrogates and code points beyond U+10FFFF
                std::uint32_t cp = c & (0x7F >> length);
                for (std::size_t k = 1; k < length; ++k) cp = cp << 6 | (text[i + k] & 0x3F);
                const std::uint32_t least[] = {0, 0, 0x80, 0x800, 0x10000};
                if (cp < least[length] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF))
                    length = 0;
            }
        }
        if (controls && length == 1 && (c < 0x20 || c == 0x7F) && c != '\t') length = 0;
        if (length == 0) {
            escape(c);
            ++i;
        } else {
            out.append(text.substr(i, length));
            i += length;
        }
    }
    return out;
}
}  // namespace

std::string printable(std::string_view text) {
    return escapeBytes(text, true);
}
std::string validUtf8(std::string_view text) {
    return escapeBytes(text, false);
}

void refuseControlCharacters(const std::string& at, const std::string& v) {
    for (std::size_t i = 0; i < v.size(); ++i) {
        const unsigned char c = static_cast<unsigned char>(v[i]);
        if (c < 0x20 || c == 0x7f) {
            char code[8];
            std::snprintf(code, sizeof code, "U+%04X", c);
            throw Error(at + "control character " + code + " at byte " + std::to_string(i) +
                        " of the string: not allowed in a string value");
        }
    }
}

}  // namespace rtbench
