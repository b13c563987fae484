#include "runtime/render/FontAtlas.h"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <cstdlib>
#include <memory>

namespace kiosk::render {

std::string FontAtlas::defaultFontPath() {
    if (const char* f = std::getenv("GEOKIOSK_FONT"); f && *f) return f;
    return "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
}

Result<FontAtlas> FontAtlas::build(const std::string& fontPath, int pixelSize) {
    Diagnostics diags;
    FT_Library lib = nullptr;
    if (FT_Init_FreeType(&lib) != 0) {
        diags.error("FONT_LOAD", fontPath, "", "cannot initialise FreeType");
        return diags;
    }
    std::unique_ptr<FT_LibraryRec_, decltype(&FT_Done_FreeType)> libGuard(lib, FT_Done_FreeType);
    FT_Face face = nullptr;
    if (FT_New_Face(lib, fontPath.c_str(), 0, &face) != 0) {
        diags.error("FONT_LOAD", fontPath, "", "cannot open font (install fonts-dejavu-core or set GEOKIOSK_FONT)");
        return diags;
    }
    std::unique_ptr<FT_FaceRec_, decltype(&FT_Done_Face)> faceGuard(face, FT_Done_Face);
    FT_Set_Pixel_Sizes(face, 0, FT_UInt(pixelSize));

    FontAtlas atlas;
    atlas.mAscent = int(face->size->metrics.ascender >> 6);
    atlas.mLineHeight = int(face->size->metrics.height >> 6);
    // Shelf packing into a fixed-width atlas; 32..126 and 160..255 fit easily in 512 wide.
    atlas.mWidth = 512;
    const int pad = 1;
    int penX = pad, penY = pad, shelf = 0;
    struct Pending {
        unsigned char c;
        std::vector<std::uint8_t> bitmap;
        Glyph g;
    };
    std::vector<Pending> pending;
    for (int c = 32; c < 256; ++c) {
        if (c >= 127 && c < 160) continue;
        if (FT_Load_Char(face, FT_ULong(c), FT_LOAD_RENDER) != 0) continue;
        const FT_GlyphSlot slot = face->glyph;
        Pending p{static_cast<unsigned char>(c), {}, {}};
        p.g.width = int(slot->bitmap.width);
        p.g.height = int(slot->bitmap.rows);
        p.g.bearingX = slot->bitmap_left;
        p.g.bearingY = slot->bitmap_top;
        p.g.advance = float(slot->advance.x) / 64.0f;
        for (int row = 0; row < p.g.height; ++row)
            for (int col = 0; col < p.g.width; ++col)
                p.bitmap.push_back(slot->bitmap.buffer[row * slot->bitmap.pitch + col]);
        if (penX + p.g.width + pad > atlas.mWidth) {
            penX = pad;
            penY += shelf + pad;
            shelf = 0;
        }
        p.g.x = penX;
        p.g.y = penY;
        penX += p.g.width + pad;
        shelf = std::max(shelf, p.g.height);
        pending.push_back(std::move(p));
    }
    atlas.mHeight = penY + shelf + pad;
    atlas.mPixels.assign(std::size_t(atlas.mWidth) * std::size_t(atlas.mHeight), 0);
    for (const auto& p : pending) {
        for (int row = 0; row < p.g.height; ++row)
            for (int col = 0; col < p.g.width; ++col)
                atlas.mPixels[std::size_t(p.g.y + row) * std::size_t(atlas.mWidth) +
                              std::size_t(p.g.x + col)] =
                    p.bitmap[std::size_t(row) * std::size_t(p.g.width) + std::size_t(col)];
        atlas.mGlyphs[p.c] = p.g;
        atlas.mHave[p.c] = true;
    }
    if (!atlas.mHave['?']) {
        diags.error("FONT_LOAD", fontPath, "", "font has no basic Latin glyphs");
        return diags;
    }
    return atlas;
}

const Glyph* FontAtlas::glyph(unsigned char c) const {
    if (mHave[c]) return &mGlyphs[c];
    return &mGlyphs['?'];
}

float FontAtlas::measure(std::string_view text) const {
    float w = 0;
    for (char ch : text) w += glyph(static_cast<unsigned char>(ch))->advance;
    return w;
}

std::string utf8ToLatin1(std::string_view s) {
    std::string out;
    forEachLatin1(s, [&](unsigned char c) { out += char(c); });
    return out;
}

}  // namespace kiosk::render
