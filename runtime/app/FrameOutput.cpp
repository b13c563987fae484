#include "runtime/app/FrameOutput.h"

#include "runtime/app/ImageOutput.h"

#include <cstdio>

namespace kiosk::app {

std::optional<FrameOutput::Kind> FrameOutput::kindOf(const std::string& out) {
    if (out.empty()) return std::nullopt;
    std::error_code ec;
    if (out.back() == '/' || std::filesystem::is_directory(out, ec)) return Kind::PngFolder;
    if (video::videoFormatForPath(out)) return Kind::Video;
    if (std::filesystem::path(out).extension() == ".png") return Kind::Png;
    return std::nullopt;
}

FrameOutput FrameOutput::png(std::filesystem::path file) {
    FrameOutput o;
    o.mKind = Kind::Png;
    o.mPath = std::move(file);
    return o;
}

FrameOutput FrameOutput::folder(std::filesystem::path dir) {
    FrameOutput o;
    o.mKind = Kind::PngFolder;
    o.mPath = std::move(dir);
    return o;
}

Result<FrameOutput> FrameOutput::video(const video::VideoOptions& options) {
    auto encoder = video::VideoEncoder::open(options);
    if (!encoder) return encoder.diagnostics;
    FrameOutput o;
    o.mKind = Kind::Video;
    o.mPath = options.path;
    o.mEncoder = std::move(*encoder.value);
    return o;
}

bool FrameOutput::write(const gl::RenderTarget& target, Diagnostics& diags) {
    ++mWritten;
    switch (mKind) {
        case Kind::Png:
            return writePng(mPath, target.readColor(), diags);
        case Kind::PngFolder: {
            char name[32];
            std::snprintf(name, sizeof name, "%06zu.png", mWritten);
            return writePng(mPath / name, target.readColor(), diags);
        }
        case Kind::Video: {
            std::uint8_t* slot = mEncoder->acquire(diags);
            if (!slot) return false;
            target.readInto(slot);
            mEncoder->submit();
            return true;
        }
    }
    return false;
}

bool FrameOutput::finish(Diagnostics& diags) {
    return mKind != Kind::Video || mEncoder->finish(diags);
}

}  // namespace kiosk::app
