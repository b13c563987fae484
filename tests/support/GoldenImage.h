#pragma once

#include <string>

#include "runtime/gl/RenderTarget.h"

namespace kiosk::test {

/** @brief Per-channel tolerances for a golden comparison; say why in the test. */
struct Tolerance {
    int maxChannelDiff = 2;       ///< largest allowed |actual - expected| on any channel
    double meanChannelDiff = 0.5;  ///< allowed mean over all channels
};

/**
 * @brief Compare `actual` with tests/golden/<name>.png.
 *
 * On mismatch (or missing golden) writes <build>/golden-out/<name>.actual.png and
 * <name>.diff.png and returns a message; empty string means equal within tolerance.
 * With KIOSK_UPDATE_GOLDEN=1 the golden is (re)written from `actual` and the check passes;
 * tests/golden/update.sh does that for the whole suite.
 */
std::string compareWithGolden(const gl::Image& actual, const std::string& name, Tolerance tol);

/** @brief Read a PNG/any OIIO image into RGBA8 (alpha 255 if absent). Empty on failure. */
gl::Image readImage(const std::string& path);
bool writeImage(const std::string& path, const gl::Image& img);

}  // namespace kiosk::test
