#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "runtime/core/Result.h"

namespace kiosk::render {

/** @brief Placement of one glyph in the atlas and its metrics, in pixels. */
struct Glyph {
    int x = 0, y = 0, width = 0, height = 0;  ///< rectangle in the atlas
    int bearingX = 0, bearingY = 0;           ///< from the pen position to the bitmap's top-left
    float advance = 0;
};

/**
 * @brief Glyph coverage for printable Latin-1 rasterised once with FreeType into one R8 atlas.
 * CPU only (no GL): built at start-up, uploaded by OverlayRenderer.
 */
class FontAtlas {
public:
    /** @brief `fontPath` a TrueType/OpenType file; errors FONT_LOAD name the file. */
    static Result<FontAtlas> build(const std::string& fontPath, int pixelSize);
    /** @brief The default UI font (DejaVu Sans from fonts-dejavu-core), or GEOKIOSK_FONT. */
    static std::string defaultFontPath();

    const Glyph* glyph(unsigned char c) const;
    /** @brief Advance width of a UTF-8/Latin-1 string in pixels (unknown characters as '?'). */
    float measure(std::string_view text) const;

    int width() const noexcept { return mWidth; }
    int height() const noexcept { return mHeight; }
    int lineHeight() const noexcept { return mLineHeight; }
    int ascent() const noexcept { return mAscent; }
    const std::vector<std::uint8_t>& pixels() const noexcept { return mPixels; }

private:
    int mWidth = 0, mHeight = 0, mLineHeight = 0, mAscent = 0;
    std::vector<std::uint8_t> mPixels;
    std::array<Glyph, 256> mGlyphs{};
    std::array<bool, 256> mHave{};
};

/**
 * @brief Call `emit(unsigned char)` with each Latin-1 code point of UTF-8 `s` (others become
 * '?'): the overlay font's range, decoded in place (overlays run every frame; no string).
 */
template <class Emit>
void forEachLatin1(std::string_view s, Emit&& emit) {
    for (std::size_t i = 0; i < s.size();) {
        const auto c = static_cast<unsigned char>(s[i]);
        if (c < 0x80) {
            emit(c);
            ++i;
        } else if ((c & 0xE0) == 0xC0 && i + 1 < s.size()) {
            const unsigned cp = ((c & 0x1Fu) << 6) | (static_cast<unsigned char>(s[i + 1]) & 0x3Fu);
            emit(static_cast<unsigned char>(cp < 256 ? cp : '?'));
            i += 2;
        } else {
            emit(static_cast<unsigned char>('?'));
            ++i;
            while (i < s.size() && (static_cast<unsigned char>(s[i]) & 0xC0) == 0x80) ++i;
        }
    }
}

/** @brief Decode UTF-8 to Latin-1 code points (others become '?'); the overlay font's range. */
std::string utf8ToLatin1(std::string_view text);

}  // namespace kiosk::render
