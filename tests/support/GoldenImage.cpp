#include "tests/support/GoldenImage.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "tests/support/EglTestContext.h"

namespace kiosk::test {

gl::Image readImage(const std::string& path) {
    gl::Image img;
    auto in = OIIO::ImageInput::open(path);
    if (!in) return img;
    const auto& spec = in->spec();
    std::vector<std::uint8_t> px(std::size_t(spec.width) * std::size_t(spec.height) *
                                 std::size_t(spec.nchannels));
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, px.data())) return img;
    img.width = spec.width;
    img.height = spec.height;
    img.rgba.assign(std::size_t(img.width) * std::size_t(img.height) * 4, 255);
    for (std::size_t i = 0, n = std::size_t(img.width) * std::size_t(img.height); i < n; ++i)
        for (int c = 0; c < std::min(spec.nchannels, 4); ++c)
            img.rgba[i * 4 + std::size_t(c)] = px[i * std::size_t(spec.nchannels) + std::size_t(c)];
    return img;
}

bool writeImage(const std::string& path, const gl::Image& img) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) return false;
    OIIO::ImageSpec spec(img.width, img.height, 4, OIIO::TypeDesc::UINT8);
    return out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, img.rgba.data()) &&
           out->close();
}

std::string compareWithGolden(const gl::Image& actual, const std::string& name, Tolerance tol) {
    const std::filesystem::path golden = std::filesystem::path("tests/golden") / (name + ".png");
    if (envFlag("KIOSK_UPDATE_GOLDEN")) {
        std::filesystem::create_directories(golden.parent_path());
        return writeImage(golden.string(), actual) ? "" : "cannot write " + golden.string();
    }
    const char* outRoot = std::getenv("KIOSK_TEST_OUTPUT");
    std::filesystem::path outDir = outRoot && *outRoot ? outRoot : "build/golden-out";
    std::filesystem::create_directories(outDir);
    const auto actualPath = outDir / (name + ".actual.png");
    gl::Image expected = readImage(golden.string());
    if (expected.width == 0) {
        writeImage(actualPath.string(), actual);
        return "golden " + golden.string() + " is missing; actual written to " +
               actualPath.string() + " (KIOSK_UPDATE_GOLDEN=1 to accept)";
    }
    if (expected.width != actual.width || expected.height != actual.height) {
        writeImage(actualPath.string(), actual);
        return "size differs from golden " + golden.string();
    }
    gl::Image diff = actual;
    int maxDiff = 0;
    double sum = 0;
    for (std::size_t i = 0; i < actual.rgba.size(); ++i) {
        int d = std::abs(int(actual.rgba[i]) - int(expected.rgba[i]));
        maxDiff = std::max(maxDiff, d);
        sum += d;
        diff.rgba[i] = (i % 4 == 3) ? 255 : std::uint8_t(std::min(255, d * 16));
    }
    const double mean = sum / double(actual.rgba.size());
    if (maxDiff <= tol.maxChannelDiff && mean <= tol.meanChannelDiff) return "";
    writeImage(actualPath.string(), actual);
    writeImage((outDir / (name + ".diff.png")).string(), diff);
    std::ostringstream msg;
    msg << name << ": max channel diff " << maxDiff << " (allowed " << tol.maxChannelDiff
        << "), mean " << mean << " (allowed " << tol.meanChannelDiff << "); actual and diff in "
        << outDir.string();
    return msg.str();
}

}  // namespace kiosk::test
