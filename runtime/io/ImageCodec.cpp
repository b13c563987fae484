#include "runtime/io/ImageCodec.h"

#include "runtime/io/ImageHeader.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstring>

namespace kiosk::io {

namespace {

Result<std::vector<std::uint8_t>> encode(const char* format, const void* pixels, int width,
                                         int height, int channels, OIIO::TypeDesc type, int level,
                                         int quality) {
    std::vector<unsigned char> out;
    OIIO::Filesystem::IOVecOutput proxy(out);
    auto writer = OIIO::ImageOutput::create(format);
    Diagnostics d;
    if (!writer) {
        d.error("IMAGE_ENCODE", "", "", std::string("no ") + format + " encoder available");
        return d;
    }
    OIIO::ImageSpec spec(width, height, channels, type);
    if (level >= 0) spec.attribute("png:compressionLevel", level);
    if (quality > 0) spec.attribute("CompressionQuality", quality);
    // Our RGBA is straight (unassociated) alpha, as PNG stores it: no premultiply round trip.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    writer->set_ioproxy(&proxy);
    const std::string name = std::string("tile.") + format;
    if (!writer->open(name, spec) || !writer->write_image(type, pixels) || !writer->close()) {
        d.error("IMAGE_ENCODE", "", "",
                std::string(format) + " encode failed: " + writer->geterror());
        return d;
    }
    return std::vector<std::uint8_t>(out.begin(), out.end());
}

Result<DecodedImage> decode(const std::uint8_t* data, std::size_t size, const std::string& where,
                            bool gray16) {
    // Header peek first: a few bytes claiming 60000x60000 must not reach the decoder.
    Diagnostics d = checkDecodeBudget(data, size, where);
    if (d.hasErrors()) return d;
    const ImageFormat fmt = sniffImageFormat(data, size);
    const char* name = fmt == ImageFormat::Png    ? "png"
                       : fmt == ImageFormat::Jpeg ? "jpeg"
                       : fmt == ImageFormat::Tiff ? "tiff"
                                                  : nullptr;
    if (!name) {
        d.error("IMAGE_DECODE", "", where, "tile data is not PNG, JPEG or TIFF");
        return d;
    }
    OIIO::Filesystem::IOMemReader proxy(const_cast<std::uint8_t*>(data), size);
    auto reader = OIIO::ImageInput::create(name);
    if (!reader) {
        d.error("IMAGE_DECODE", "", where, std::string("no ") + name + " decoder available");
        return d;
    }
    reader->set_ioproxy(&proxy);
    OIIO::ImageSpec spec, config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    if (!reader->open(std::string("tile.") + name, spec, config)) {
        d.error("IMAGE_DECODE", "", where,
                std::string("cannot decode tile: ") + reader->geterror());
        return d;
    }
    DecodedImage img;
    img.width = spec.width;
    img.height = spec.height;
    img.channels = spec.nchannels;
    const std::size_t n = std::size_t(spec.width) * std::size_t(spec.height);
    bool ok = true;
    if (gray16) {
        std::vector<std::uint16_t> all(n * std::size_t(spec.nchannels));
        ok = reader->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT16, all.data());
        img.samples16.resize(n);
        for (std::size_t i = 0; i < n; ++i) img.samples16[i] = all[i * std::size_t(spec.nchannels)];
        img.channels = 1;
    } else {
        std::vector<std::uint8_t> all(n * std::size_t(spec.nchannels));
        ok = reader->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, all.data());
        img.samples8.resize(n * 4);
        const int c = spec.nchannels;
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint8_t* s = &all[i * std::size_t(c)];
            std::uint8_t* o = &img.samples8[i * 4];
            if (c >= 3) {
                o[0] = s[0], o[1] = s[1], o[2] = s[2];
                o[3] = c >= 4 ? s[3] : 255;
            } else {
                o[0] = o[1] = o[2] = s[0];
                o[3] = c == 2 ? s[1] : 255;
            }
        }
        img.channels = 4;
    }
    reader->close();
    if (!ok) {
        d.error("IMAGE_DECODE", "", where,
                std::string("cannot decode tile pixels: ") + reader->geterror());
        return d;
    }
    return img;
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
    return encode("png", gray, width, height, 1, OIIO::TypeDesc::UINT16, compressionLevel, 0);
}

Result<std::vector<std::uint8_t>> encodePng8(const std::uint8_t* pixels, int width, int height,
                                             int channels, int compressionLevel) {
    return encode("png", pixels, width, height, channels, OIIO::TypeDesc::UINT8, compressionLevel,
                  0);
}

Result<std::vector<std::uint8_t>> encodeJpeg(const std::uint8_t* rgb, int width, int height,
                                             int quality) {
    return encode("jpeg", rgb, width, height, 3, OIIO::TypeDesc::UINT8, -1, quality);
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
