#pragma once

#include <filesystem>
#include <string>

#include "runtime/core/Diagnostics.h"
#include "runtime/topo/Hillshade.h"

namespace kiosk::import {

struct TopographicOptions {
    std::filesystem::path store;
    std::string elevation = "elevation";  ///< scalar layer to shade
    std::string name = "hillshade";       ///< imagery layer to write
    topo::HillshadeParams light;          ///< azimuth, altitude, z factor, variant
    bool shadows = false;                 ///< cast shadows along the light (ray marching)
    double shadowDarkening = 0.5;
    /**
     * @brief Write a normal-map pyramid instead of the hillshade (dynamic light at run time):
     * R, G, B = topo::NormalEncoding::Rgb8 of the unit normal (east, north, up) from the same
     * gradient as the hillshade (light.zFactor, light.scale, light.algorithm); A = 255, or 0
     * where the elevation is nodata (docs/store-format.md "Normal maps").
     */
    bool normals = false;
    int threads = 2;
    bool quiet = false;
};

/**
 * @brief `geokiosk import topographic`: a hillshade pyramid computed from the store's own
 * full-resolution elevation (Döllner §7 / Baumann: shading as a texture, so coarse geometry still
 * looks fully detailed). Stored as an imagery layer, R = G = B = shade, A = 0 where the
 * elevation is nodata (transparent, no rim). Streams strip by strip with a one-row apron (or the
 * shadow reach), so memory stays bounded whatever the DEM size. Atomic like every import.
 * With `normals`, the same streaming writes encoded normals instead (coarser levels average
 * the encoded vectors of valid texels; the shader renormalises).
 * Errors: IMPORT_NO_ELEVATION (layer missing), STORE_* from the store.
 */
Diagnostics importTopographic(const TopographicOptions& options);

}  // namespace kiosk::import
