#include "runtime/io/FramePng.h"

#include <algorithm>
#include <cstring>
#include <initializer_list>
#include <memory>
#include <string>
#include <system_error>
#include <thread>
#include <utility>
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

/** A stripe's raw deflate stream (no zlib header or trailer) and the Adler-32 of its rows. */
struct Stripe {
    std::unique_ptr<std::uint8_t[]> bytes;  // not zeroed: only the pages written count as RSS
    std::size_t size = 0;
    uLong adler = 0;
    bool ok = false;
};

/**
 * Filter rows [y0, y1) a few at a time (a small buffer instead of the stripe's 3 MB) and deflate
 * them raw; a stripe that is not the last ends with a sync flush (byte-aligned, not final), the
 * last with the final block. `dictionary`: the bytes the stream continues (deflate's window).
 */
Stripe deflateStripe(const std::uint8_t* rgba, int width, int y0, int y1,
                     const std::vector<std::uint8_t>& dictionary, bool last) {
    Stripe out;
    out.adler = adler32(0, nullptr, 0);
    z_stream z{};
    if (deflateInit2(&z, kLevel, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) return out;
    const std::size_t stride = std::size_t(width) * 3 + 1;
    const std::size_t bound = deflateBound(&z, uLong(stride * std::size_t(y1 - y0))) + 64;
    out.bytes.reset(new std::uint8_t[bound]);
    z.next_out = out.bytes.get();
    z.avail_out = uInt(bound);
    bool ok = dictionary.empty() ||
              deflateSetDictionary(&z, dictionary.data(), uInt(dictionary.size())) == Z_OK;
    constexpr int kRows = 16;
    std::vector<std::uint8_t> rows(stride * kRows);
    for (int y = y0; ok && y < y1; y += kRows) {
        const int n = std::min(kRows, y1 - y);
        filterRows(rgba, width, y, y + n, rows.data());
        const uInt bytes = uInt(stride * std::size_t(n));
        out.adler = adler32(out.adler, rows.data(), bytes);
        z.next_in = rows.data();
        z.avail_in = bytes;
        const bool end = y + n == y1;
        const int flush = !end ? Z_NO_FLUSH : last ? Z_FINISH : Z_SYNC_FLUSH;
        const int rc = deflate(&z, flush);
        ok = (rc == Z_OK || (rc == Z_STREAM_END && flush == Z_FINISH)) && z.avail_in == 0;
    }
    out.size = bound - z.avail_out;
    out.ok = ok;
    deflateEnd(&z);
    return out;
}

void put32(std::vector<std::uint8_t>& v, std::uint32_t x) {
    for (int s = 24; s >= 0; s -= 8) v.push_back(std::uint8_t(x >> s));
}

/** A PNG chunk whose data is the concatenation of `parts`. */
void chunk(std::vector<std::uint8_t>& png, const char* type,
           std::initializer_list<std::pair<const std::uint8_t*, std::size_t>> parts) {
    std::size_t size = 0;
    for (const auto& [p, n] : parts) size += n;
    put32(png, std::uint32_t(size));
    const std::size_t start = png.size();
    png.insert(png.end(), type, type + 4);
    for (const auto& [p, n] : parts) png.insert(png.end(), p, p + n);
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
    Stripe first, second;
    auto secondStripe = [&] {
        // The first stripe's last 32 KiB of scanlines are the second's dictionary: filtered
        // here from the same pixels, so the stripes need not wait for each other.
        const int dictRows = std::min<int>(split, int((kWindow + stride - 1) / stride));
        std::vector<std::uint8_t> dict(stride * std::size_t(dictRows));
        filterRows(rgba, width, split - dictRows, split, dict.data());
        dict.erase(dict.begin(), dict.end() - std::ptrdiff_t(std::min(kWindow, dict.size())));
        second = deflateStripe(rgba, width, split, height, dict, true);
    };
    std::thread worker;
    try {
        worker = std::thread(secondStripe);
    } catch (const std::system_error&) {
        secondStripe();  // no thread to be had: the same bytes, one stripe after the other
    }
    first = deflateStripe(rgba, width, 0, split, {}, false);
    if (worker.joinable()) worker.join();
    if (!first.ok || !second.ok) {
        d.error("IMAGE_ENCODE", "", "", "png encode: deflate failed");
        return d;
    }
    const uLong adler =
        adler32_combine(first.adler, second.adler, z_off_t(stride * std::size_t(height - split)));
    std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    png.reserve(8 + 25 + 12 + 6 + first.size + second.size + 12);
    std::vector<std::uint8_t> ihdr;
    put32(ihdr, std::uint32_t(width));
    put32(ihdr, std::uint32_t(height));
    ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // 8-bit RGB, deflate, adaptive filters, no interlace
    chunk(png, "IHDR", {{ihdr.data(), ihdr.size()}});
    std::vector<std::uint8_t> trailer;
    put32(trailer, std::uint32_t(adler));
    // One IDAT: the zlib header (deflate, 32 KiB window, FLEVEL 1 as zlib writes for level 2;
    // 0x785e is a multiple of 31), both stripes, the Adler-32 of all scanlines.
    const std::uint8_t header[2] = {0x78, 0x5e};
    chunk(png, "IDAT",
          {{header, 2},
           {first.bytes.get(), first.size},
           {second.bytes.get(), second.size},
           {trailer.data(), trailer.size()}});
    chunk(png, "IEND", {});
    return png;
}

}  // namespace kiosk::io
