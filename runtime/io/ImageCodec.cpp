#include "runtime/io/ImageCodec.h"

#include "runtime/io/ImageHeader.h"

#include <cstdlib>
#include <cstring>
#include <memory>
#include <spng.h>
#include <turbojpeg.h>

// PNG through libspng and JPEG through libjpeg-turbo's TurboJPEG API: the runtime links these two
// small libraries instead of OpenImageIO (and the codec zoo behind it). Both work on memory
// buffers, so no temporary files and no I/O proxies are needed.

namespace kiosk::io {

namespace {

struct SpngFree {
    void operator()(spng_ctx* c) const noexcept { spng_ctx_free(c); }
};
using SpngCtx = std::unique_ptr<spng_ctx, SpngFree>;

struct TjFree {
    void operator()(void* h) const noexcept { tjDestroy(h); }
};
using TjHandle = std::unique_ptr<void, TjFree>;

Result<std::vector<std::uint8_t>> encodePng(const void* pixels, int width, int height, int channels,
                                            int bitDepth, int level) {
    Diagnostics d;
    static constexpr std::uint8_t kColorType[5] = {
        0, SPNG_COLOR_TYPE_GRAYSCALE, SPNG_COLOR_TYPE_GRAYSCALE_ALPHA, SPNG_COLOR_TYPE_TRUECOLOR,
        SPNG_COLOR_TYPE_TRUECOLOR_ALPHA};
    if (width < 1 || height < 1 || channels < 1 || channels > 4) {
        d.error("IMAGE_ENCODE", "", "",
                "png encode: bad image shape " + std::to_string(width) + "x" +
                    std::to_string(height) + "x" + std::to_string(channels));
        return d;
    }
    SpngCtx ctx(spng_ctx_new(SPNG_CTX_ENCODER));
    if (!ctx) {
        d.error("IMAGE_ENCODE", "", "", "png encode: out of memory");
        return d;
    }
    spng_ihdr ihdr{};
    ihdr.width = std::uint32_t(width);
    ihdr.height = std::uint32_t(height);
    ihdr.bit_depth = std::uint8_t(bitDepth);
    ihdr.color_type = kColorType[channels];
    const std::size_t bytes = std::size_t(width) * std::size_t(height) * std::size_t(channels) *
                              std::size_t(bitDepth / 8);
    int err = spng_set_option(ctx.get(), SPNG_ENCODE_TO_BUFFER, 1);
    if (!err && level >= 0) err = spng_set_option(ctx.get(), SPNG_IMG_COMPRESSION_LEVEL, level);
    if (!err) err = spng_set_ihdr(ctx.get(), &ihdr);
    // SPNG_FMT_PNG: samples as the PNG stores them, 16-bit ones in host byte order.
    if (!err) err = spng_encode_image(ctx.get(), pixels, bytes, SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE);
    std::size_t size = 0;
    void* buf = err ? nullptr : spng_get_png_buffer(ctx.get(), &size, &err);
    if (err || !buf) {
        std::free(buf);
        d.error("IMAGE_ENCODE", "", "", std::string("png encode failed: ") + spng_strerror(err));
        return d;
    }
    const auto* p = static_cast<const std::uint8_t*>(buf);
    std::vector<std::uint8_t> out(p, p + size);
    std::free(buf);
    return out;
}

Result<DecodedImage> decodePng(const std::uint8_t* data, std::size_t size, const std::string& where,
                               bool gray16) {
    Diagnostics d;
    SpngCtx ctx(spng_ctx_new(0));
    if (!ctx) {
        d.error("IMAGE_DECODE", "", where, "cannot decode tile: out of memory");
        return d;
    }
    spng_ihdr ihdr{};
    int err = spng_set_png_buffer(ctx.get(), data, size);
    if (!err) err = spng_get_ihdr(ctx.get(), &ihdr);
    // Native 16-bit grey is copied as stored; anything else is expanded to RGBA (16-bit
    // samples scaled from 8-bit ones by 257, as before) and its first channel kept.
    const bool native =
        gray16 && ihdr.color_type == SPNG_COLOR_TYPE_GRAYSCALE && ihdr.bit_depth == 16;
    const int fmt = native ? SPNG_FMT_PNG : gray16 ? SPNG_FMT_RGBA16 : SPNG_FMT_RGBA8;
    std::size_t bytes = 0;
    if (!err) err = spng_decoded_image_size(ctx.get(), fmt, &bytes);
    DecodedImage img;
    img.width = int(ihdr.width);
    img.height = int(ihdr.height);
    const std::size_t n = std::size_t(ihdr.width) * std::size_t(ihdr.height);
    if (!err) {
        if (native) {
            img.samples16.resize(n);
            err = spng_decode_image(ctx.get(), img.samples16.data(), bytes, fmt, 0);
        } else if (gray16) {
            std::vector<std::uint16_t> rgba(n * 4);
            err = spng_decode_image(ctx.get(), rgba.data(), bytes, fmt, SPNG_DECODE_TRNS);
            img.samples16.resize(n);
            for (std::size_t i = 0; i < n; ++i) img.samples16[i] = rgba[i * 4];
        } else {
            img.samples8.resize(n * 4);
            err = spng_decode_image(ctx.get(), img.samples8.data(), bytes, fmt, SPNG_DECODE_TRNS);
        }
    }
    if (err) {
        d.error("IMAGE_DECODE", "", where,
                std::string("cannot decode tile: ") + spng_strerror(err));
        return d;
    }
    img.channels = gray16 ? 1 : 4;
    return img;
}

Result<DecodedImage> decodeJpeg(const std::uint8_t* data, std::size_t size,
                                const std::string& where, bool gray16) {
    Diagnostics d;
    TjHandle tj(tjInitDecompress());
    int w = 0, h = 0, subsamp = 0, colorspace = 0;
    auto* src = const_cast<unsigned char*>(data);  // TurboJPEG 2.1 takes non-const input
    const unsigned long len = static_cast<unsigned long>(size);
    if (!tj || tjDecompressHeader3(tj.get(), src, len, &w, &h, &subsamp, &colorspace) != 0 ||
        w < 1 || h < 1) {
        d.error("IMAGE_DECODE", "", where,
                std::string("cannot decode tile: ") + tjGetErrorStr2(tj.get()));
        return d;
    }
    DecodedImage img;
    img.width = w;
    img.height = h;
    const std::size_t n = std::size_t(w) * std::size_t(h);
    img.samples8.resize(n * 4);
    if (tjDecompress2(tj.get(), src, len, img.samples8.data(), w, 0, h, TJPF_RGBA, 0) != 0 &&
        tjGetErrorCode(tj.get()) == TJERR_FATAL) {
        d.error("IMAGE_DECODE", "", where,
                std::string("cannot decode tile pixels: ") + tjGetErrorStr2(tj.get()));
        return d;
    }
    img.channels = 4;
    if (gray16) {
        img.samples16.resize(n);
        for (std::size_t i = 0; i < n; ++i)
            img.samples16[i] = std::uint16_t(img.samples8[i * 4] * 257u);
        img.samples8 = {};
        img.channels = 1;
    }
    return img;
}

Result<DecodedImage> decode(const std::uint8_t* data, std::size_t size, const std::string& where,
                            bool gray16) {
    // Header peek first: a few bytes claiming 60000x60000 must not reach the decoder.
    if (Diagnostics d = checkDecodeBudget(data, size, where); d.hasErrors()) return d;
    switch (sniffImageFormat(data, size)) {
        case ImageFormat::Png:
            return decodePng(data, size, where, gray16);
        case ImageFormat::Jpeg:
            return decodeJpeg(data, size, where, gray16);
        case ImageFormat::Tiff: {
            Diagnostics d;
            d.error("IMAGE_DECODE", "", where,
                    "TIFF tiles are not supported (GeoPackage tiles are PNG or JPEG)");
            return d;
        }
        case ImageFormat::Unknown:
            break;
    }
    Diagnostics d;
    d.error("IMAGE_DECODE", "", where, "tile data is not PNG or JPEG");
    return d;
}

}  // namespace

ImageFormat sniffImageFormat(const std::uint8_t* data, std::size_t size) noexcept {
    if (!data || size < 4) return ImageFormat::Unknown;
    if (data[0] == 0x89 && data[1] == 'P' && data[2] == 'N' && data[3] == 'G')
        return ImageFormat::Png;
    if (data[0] == 0xFF && data[1] == 0xD8) return ImageFormat::Jpeg;
    if ((data[0] == 'I' && data[1] == 'I') || (data[0] == 'M' && data[1] == 'M'))
        return ImageFormat::Tiff;
    return ImageFormat::Unknown;
}

Result<std::vector<std::uint8_t>> encodePng16(const std::uint16_t* gray, int width, int height,
                                              int compressionLevel) {
    return encodePng(gray, width, height, 1, 16, compressionLevel);
}

Result<std::vector<std::uint8_t>> encodePng8(const std::uint8_t* pixels, int width, int height,
                                             int channels, int compressionLevel) {
    return encodePng(pixels, width, height, channels, 8, compressionLevel);
}

Result<std::vector<std::uint8_t>> encodeJpeg(const std::uint8_t* rgb, int width, int height,
                                             int quality) {
    Diagnostics d;
    TjHandle tj(tjInitCompress());
    unsigned char* buf = nullptr;
    unsigned long size = 0;
    // 4:2:0 chroma subsampling, as libjpeg's default that OpenImageIO used.
    if (!tj || width < 1 || height < 1 ||
        tjCompress2(tj.get(), rgb, width, 0, height, TJPF_RGB, &buf, &size, TJSAMP_420,
                    quality > 0 ? quality : 90, 0) != 0) {
        d.error("IMAGE_ENCODE", "", "",
                std::string("jpeg encode failed: ") + tjGetErrorStr2(tj.get()));
        tjFree(buf);
        return d;
    }
    std::vector<std::uint8_t> out(buf, buf + size);
    tjFree(buf);
    return out;
}

Result<DecodedImage> decodeGray16(const std::uint8_t* data, std::size_t size,
                                  const std::string& where) {
    return decode(data, size, where, true);
}

Result<DecodedImage> decodeRgba8(const std::uint8_t* data, std::size_t size,
                                 const std::string& where) {
    return decode(data, size, where, false);
}

}  // namespace kiosk::io
