#pragma once

#include "runtime/color/ColorSpace.h"
#include "runtime/core/Diagnostics.h"

#include <cstdint>
#include <string>
#include <vector>

// One definition drives the shader LUT and the legend (issue 5): the model below, buildLut() for
// the GPU and Legend.h for the overlay. Pure data and functions; any thread.
namespace kiosk::color {

/** @brief A colour at a data value (data units, e.g. metres of depth). */
struct Stop {
    double value = 0;
    Rgba color;
};

/**
 * @brief A discrete class (FEWS style): values in [from, next class's from) take `color`. The
 * last class ends at the domain maximum.
 */
struct ClassBreak {
    double from = 0;
    Rgba color;
    std::string label;
};

/** @brief Opacity (0..1) at a data value; multiplies the colour's own alpha. */
struct OpacityPoint {
    double value = 0;
    double opacity = 1;
};

/**
 * @brief A colour transfer function: piecewise-linear stops OR class breaks, in data units.
 *
 * Exactly one of `stops` / `classes` is non-empty. `domainMin/Max` is the value range the LUT
 * covers (defaults: first and last stop, or first class's `from` and domainMax given by the
 * author). Values below/above the domain take `below`/`above`; NaN (nodata) takes `nodata`.
 */
struct TransferFunction {
    std::string name;
    std::string units;  ///< e.g. "m"; compared with the store's units by the scenario checks
    Space space = Space::Lab;
    std::vector<Stop> stops;            ///< sorted by value; equal values make a step
    std::vector<ClassBreak> classes;    ///< sorted by from
    std::vector<OpacityPoint> opacity;  ///< sorted; empty = fully opaque
    Rgba nodata{0, 0, 0, 0};
    Rgba below{0, 0, 0, 0};  ///< set from the first stop/class unless the author gives one
    Rgba above{0, 0, 0, 0};  ///< set from the last stop/class unless the author gives one
    /** @brief below/above came from a colour file (GMT B/F lines, GRASS `default`): finalize
     *  keeps them as if the author had given them. */
    bool belowGiven = false, aboveGiven = false;
    double domainMin = 0;
    double domainMax = 1;

    bool discrete() const noexcept { return !classes.empty(); }

    /**
     * @brief Sorts stops/classes/opacity (stably: equal values keep their order and make a
     * step), derives the domain and the below/above colours where the `explicit*` flags say the
     * author gave none, and reports problems: TF_EMPTY (no stops or classes), TF_NOT_FINITE,
     * TF_DOMAIN (min >= max). `file`/`where` locate the messages (file name, JSON pointer).
     */
    Diagnostics finalize(bool explicitDomain, bool explicitBelow, bool explicitAbove,
                         const std::string& file = {}, const std::string& where = {});

    /** @brief Colour of one value inside the domain (clamped to it), with the opacity ramp. */
    Rgba evaluate(double value) const;
    /** @brief evaluate() plus nodata (NaN) and below/above handling: what a pixel gets. */
    Rgba shade(double value) const;

    /** @brief Same function with stops/classes/opacity mapped linearly onto a new domain. */
    TransferFunction rescaled(double newMin, double newMax) const;
};

/** @brief Smallest LUT size the renderer accepts (issue 5: at least 1024 entries). */
inline constexpr int kMinLutSize = 1024;

/**
 * @brief Sample a transfer function into an RGBA8 LUT of `size` texels (size < kMinLutSize is
 * raised to it). Texel i holds evaluate(domainMin + i / (size - 1) * (domainMax - domainMin)):
 * the first and last texel *centres* sit at the domain ends, matching lutCoord() in
 * runtime/shaders/common/encode.glsl. A stop on a texel centre is reproduced exactly; between
 * centres linear filtering reproduces it within 1 DN for in-gamut colours (at the sRGB gamut
 * boundary the curve can bend more; pick `size` so that (size - 1) * (stop - min) / (max - min)
 * is whole for exact stops). Any thread.
 */
std::vector<std::uint8_t> buildLut(const TransferFunction& tf, int size = kMinLutSize);

/** @brief Texture coordinate in [0,1] of a data value, identical to the shader's lutCoord(). */
double lutCoordinate(double value, double domainMin, double domainMax, int size) noexcept;
inline double lutCoordinate(const TransferFunction& tf, double value, int size) noexcept {
    return lutCoordinate(value, tf.domainMin, tf.domainMax, size);
}

/** @brief Round a [0,1] channel to 8 bits. */
std::uint8_t toByte(double v) noexcept;

}  // namespace kiosk::color
