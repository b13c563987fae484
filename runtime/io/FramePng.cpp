#include "runtime/io/FramePng.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <string>
#include <thread>
#include <zlib.h>

namespace kiosk::io {
namespace {

constexpr int kLevel = 2;               // zlib level: speed first (docs/performance.md §5.2)
constexpr std::size_t kWindow = 32768;  // deflate's window: the second stripe's dictionary

/** Rows [y0, y1) as PNG scanlines: filter byte 1 (Sub), RGB with each byte minus its left one. */
void filterRows(const std::uint8_t* rgba, int width, int y0, int y1, std::uint8_t* out) {
    const std::size_t stride = std::size_t(width) * 3 + 1;
    for (int y = y0; y < y1; ++y) {
        const std::uint8_t* src = rgba + std::size_t(y) * std::size_t(width) * 4;
        std::uint8_t* dst = out + std::size_t(y - y0) * stride;
        dst[0] = 1;
        std::uint8_t prev[3] = {0, 0, 0};
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) {
                const std::uint8_t v = src[std::size_t(x) * 4 + std::size_t(c)];
                dst[1 + std::size_t(x) * 3 + std::size_t(c)] = std::uint8_t(v - prev[c]);
                prev[c] = v;
            }
    }
}

/**
 * Raw deflate of `data` (no zlib header or trailer); a stripe that is not the last ends with a
 * sync flush (byte-aligned, not final), the last one with the final block. False on a zlib error.
 */
bool deflateStripe(const std::vector<std::uint8_t>& data, const std::uint8_t* dictionary,
                   std::size_t dictionarySize, bool last, std::vector<std::uint8_t>& out) {
    z_stream z{};
    if (deflateInit2(&z, kLevel, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) return false;
    bool ok =
        dictionarySize == 0 || deflateSetDictionary(&z, dictionary, uInt(dictionarySize)) == Z_OK;
    out.resize(deflateBound(&z, uLong(data.size())) + 16);
    z.next_in = const_cast<Bytef*>(data.data());
    z.avail_in = uInt(data.size());
    z.next_out = out.data();
    z.avail_out = uInt(out.size());
    if (ok) ok = deflate(&z, last ? Z_FINISH : Z_SYNC_FLUSH) == (last ? Z_STREAM_END : Z_OK);
    ok = ok && z.avail_in == 0;
    out.resize(out.size() - z.avail_out);
    deflateEnd(&z);
    return ok;
}

void put32(std::vector<std::uint8_t>& v, std::uint32_t x) {
    for (int s = 24; s >= 0; s -= 8) v.push_back(std::uint8_t(x >> s));
}

void chunk(std::vector<std::uint8_t>& png, const char* type, const std::uint8_t* data,
           std::size_t size) {
    put32(png, std::uint32_t(size));
    const std::size_t start = png.size();
    png.insert(png.end(), type, type + 4);
    png.insert(png.end(), data, data + size);
    put32(png, std::uint32_t(crc32(0, png.data() + start, uInt(size + 4))));
}

}  // namespace

Result<std::vector<std::uint8_t>> encodeFramePng(const std::uint8_t* rgba, int width, int height) {
    Diagnostics d;
    const std::size_t stride = std::size_t(width) * 3 + 1;
    // IDAT holds one chunk: its length field is 32 bits.
    if (width < 1 || height < 1 || stride * std::size_t(height) > 0x7fffffffu / 2) {
        d.error(
            "IMAGE_ENCODE", "", "",
            "png encode: bad frame size " + std::to_string(width) + "x" + std::to_string(height));
        return d;
    }
    const int split = height / 2;
    std::array<std::vector<std::uint8_t>, 2> rows, packed;
    rows[0].resize(stride * std::size_t(split));
    rows[1].resize(stride * std::size_t(height - split));
    bool ok1 = false;
    std::thread second([&] {
        filterRows(rgba, width, split, height, rows[1].data());
        // The first stripe's last rows are its dictionary: filtered here from the same pixels.
        const int dictRows = std::min<int>(split, int((kWindow + stride - 1) / stride));
        std::vector<std::uint8_t> dict(stride * std::size_t(dictRows));
        filterRows(rgba, width, split - dictRows, split, dict.data());
        const std::size_t n = std::min(kWindow, dict.size());
        ok1 = deflateStripe(rows[1], dict.data() + dict.size() - n, n, true, packed[1]);
    });
    filterRows(rgba, width, 0, split, rows[0].data());
    const bool ok0 = split == 0 || deflateStripe(rows[0], nullptr, 0, false, packed[0]);
    second.join();
    if (!ok0 || !ok1) {
        d.error("IMAGE_ENCODE", "", "", "png encode: deflate failed");
        return d;
    }
    const uLong adler =
        adler32_combine(adler32(adler32(0, nullptr, 0), rows[0].data(), uInt(rows[0].size())),
                        adler32(adler32(0, nullptr, 0), rows[1].data(), uInt(rows[1].size())),
                        z_off_t(rows[1].size()));
    std::vector<std::uint8_t> idat;
    idat.reserve(2 + packed[0].size() + packed[1].size() + 4);
    idat.push_back(0x78);  // deflate, 32 KiB window
    idat.push_back(0x5e);  // FLEVEL 1 (fast), header check: 0x785e % 31 == 0
    idat.insert(idat.end(), packed[0].begin(), packed[0].end());
    idat.insert(idat.end(), packed[1].begin(), packed[1].end());
    put32(idat, std::uint32_t(adler));
    std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    png.reserve(png.size() + idat.size() + 64);
    std::vector<std::uint8_t> ihdr;
    put32(ihdr, std::uint32_t(width));
    put32(ihdr, std::uint32_t(height));
    ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // 8-bit RGB, deflate, adaptive filters, no interlace
    chunk(png, "IHDR", ihdr.data(), ihdr.size());
    chunk(png, "IDAT", idat.data(), idat.size());
    chunk(png, "IEND", nullptr, 0);
    return png;
}

}  // namespace kiosk::io
