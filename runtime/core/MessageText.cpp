#include "runtime/core/MessageText.h"

#include <algorithm>

namespace kiosk {

namespace {

// Length of the valid UTF-8 sequence starting at `s[i]`, 0 if it is not one.
std::size_t utf8Length(std::string_view s, std::size_t i) {
    const auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
    const unsigned char c = b(i);
    std::size_t n = c < 0x80           ? 1
                    : (c >> 5) == 0x6  ? 2
                    : (c >> 4) == 0xE  ? 3
                    : (c >> 3) == 0x1E ? 4
                                       : 0;
    if (n == 0 || i + n > s.size()) return 0;
    for (std::size_t k = 1; k < n; ++k)
        if ((b(i + k) & 0xC0) != 0x80) return 0;
    if (n == 2 && c < 0xC2) return 0;  // overlong
    return n;
}

}  // namespace

std::string escapeForMessage(std::string_view text, std::size_t maxBytes) {
    static const char* const kHex = "0123456789abcdef";
    std::string out;
    out.reserve(std::min(text.size(), maxBytes) + 8);
    const auto hexByte = [&](std::string& dst, unsigned char c, bool unicode) {
        dst += unicode ? "\\u{" : "\\x";
        dst += kHex[c >> 4];
        dst += kHex[c & 15];
        if (unicode) dst += '}';
    };
    for (std::size_t i = 0; i < text.size();) {
        std::string piece;
        const unsigned char c = static_cast<unsigned char>(text[i]);
        const std::size_t n = utf8Length(text, i);
        if (n == 0) {
            hexByte(piece, c, false);
            i += 1;
        } else if (n == 1) {
            if (c == '\n')
                piece = "\\n";
            else if (c == '\r')
                piece = "\\r";
            else if (c == '\t')
                piece = "\\t";
            else if (c < 0x20 || c == 0x7F)
                hexByte(piece, c, false);
            else
                piece = std::string(1, char(c));
            i += 1;
        } else {
            // C1 controls (U+0080..U+009F; 0x9B is a CSI on some terminals) are escaped too.
            const unsigned char c2 = static_cast<unsigned char>(text[i + 1]);
            if (n == 2 && c == 0xC2 && c2 < 0xA0)
                hexByte(piece, c2, true);
            else
                piece = std::string(text.substr(i, n));
            i += n;
        }
        if (out.size() + piece.size() > maxBytes) {
            out += "\u2026";  // "…"
            return out;
        }
        out += piece;
    }
    return out;
}

}  // namespace kiosk
