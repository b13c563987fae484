#pragma once

#include "runtime/core/Diagnostics.h"
#include "runtime/topo/Hillshade.h"
#include "runtime/topo/RasterView.h"

#include <cstddef>
#include <cstdint>

namespace kiosk::topo {

/** @brief Shadow mask values (one byte per pixel). */
inline constexpr std::uint8_t kLit = 0;
inline constexpr std::uint8_t kShadowed = 255;

/**
 * @brief Cast shadows: for every window pixel, march from the pixel centre towards the light
 * (light.azimuthDeg) over the full-resolution DEM, one pixel per step along the dominant axis
 * (linear interpolation across the other), with the ray rising at tan(light.altitudeDeg).
 * The pixel is shadowed when the terrain anywhere along the ray is higher than the ray.
 *
 * Heights and distances are compared in horizontal units: height * zFactor / scale (the same
 * convention as hillshade). The march stops when the ray is above the highest height of the
 * view (the max relief bounds the ray length: relief / tan(altitude)) or when it leaves the
 * view. Samples that cannot occlude are skipped without changing the result: cells of a
 * block-maximum grid lying entirely below the ray, and stretches where a per-cell bound on the
 * terrain's climb per step proves the ray stays above it (see docs/topographic.md).
 *
 * Seams: a ray that leaves the view is treated as lit, so the view must extend at least
 * requiredShadowApron() pixels beyond the window on the sun side (the DEM border is fine:
 * nothing occludes from beyond it). Nodata (NaN) samples never occlude; nodata pixels get
 * kLit. Altitude 90 (or zFactor 0) gives no shadows.
 *
 * Writes dem.width x dem.height bytes (kLit / kShadowed) at mask + r * maskStride. Errors as
 * hillshade() (TOPO_INVALID_VIEW / TOPO_INVALID_PARAMS / TOPO_INVALID_OUTPUT), nothing written.
 * Thread: pure, any thread.
 */
Diagnostics castShadows(const RasterView& dem, const HillshadeParams& light, std::uint8_t* mask,
                        std::ptrdiff_t maskStride);

/**
 * @brief Apron (pixels, each side) a tile needs so that shadows are seamless: the horizontal
 * reach of a ray climbing `maxRelief` (vertical units: max - min height of the DEM) at the
 * light's altitude, in pixels of the smaller pixel size, plus one. Returns 0 for altitude 90
 * and a large but finite cap (1 << 20) for altitude 0 or invalid input.
 */
int requiredShadowApron(double maxRelief, const HillshadeParams& light, double pixelSizeX,
                        double pixelSizeY);

/** @brief How shadows darken a hillshade (see combineShadows()). */
struct ShadowParams {
    /**
     * Fraction of the direct shading removed in shadow, [0, 1]: a shadowed pixel with
     * hillshade v becomes 1 + (v - 1) * (1 - darkening). 0 = shadows invisible, 1 = shadowed
     * pixels become 1 (as dark as a slope facing away from the light). The default keeps half,
     * like Baumann's shadowed facets that retain their ambient term, so relief stays readable
     * inside large shadows.
     */
    double darkening = 0.5;
};

/**
 * @brief Darkens a hillshade in place where the mask says kShadowed (values in between are a
 * partial shadow: darkening * mask / 255). Nodata (0) stays 0; shading stays within 1..255.
 * Errors: TOPO_INVALID_OUTPUT (null buffer, bad stride), TOPO_INVALID_PARAMS (darkening
 * outside [0, 1]).
 */
Diagnostics combineShadows(std::uint8_t* shade, std::ptrdiff_t shadeStride,
                           const std::uint8_t* mask, std::ptrdiff_t maskStride, int width,
                           int height, const ShadowParams& params);

/**
 * @brief hillshade() + castShadows() + combineShadows() in one call (the importer's
 * `--hillshade --shadows` path). Same output convention as hillshade(): 0 = nodata,
 * 1..255 shading. Uses a temporary mask of width x height bytes.
 */
Diagnostics shadedRelief(const RasterView& dem, const HillshadeParams& light,
                         const ShadowParams& shadow, std::uint8_t* out, std::ptrdiff_t outStride);

}  // namespace kiosk::topo
