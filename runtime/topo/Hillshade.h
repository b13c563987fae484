#pragma once

#include "runtime/core/Diagnostics.h"
#include "runtime/topo/RasterView.h"

#include <cstddef>
#include <cstdint>

namespace kiosk::topo {

/** @brief Gradient estimator over the 3x3 neighbourhood (gdaldem -alg). */
enum class GradientAlgorithm {
    Horn,               ///< 3x3 weighted (1,2,1) differences; gdaldem default; rough terrain
    ZevenbergenThorne,  ///< 4-neighbour central differences; smoother landscapes
};

/** @brief Shading variant (gdaldem hillshade default / -multidirectional / -combined). */
enum class HillshadeVariant {
    Default,           ///< Lambert of the surface normal with one light
    Multidirectional,  ///< Mark (1992): lights at 225/270/315/360 deg weighted by aspect
    Combined,          ///< oblique shading darkened by slope
};

/**
 * @brief Parameters shared by hillshade, shadows and normal maps; the defaults are gdaldem's.
 *
 * Heights are multiplied by zFactor / scale before being compared with horizontal distances:
 * `scale` is the number of horizontal units per vertical unit (111120 for a DEM in degrees
 * with heights in metres, 1 for metres over metres), `zFactor` a vertical exaggeration (or a
 * unit conversion, e.g. 0.1 for heights stored in decimetres).
 */
struct HillshadeParams {
    double azimuthDeg = 315.0;  ///< direction the light comes from, clockwise from north
    double altitudeDeg = 45.0;  ///< light elevation above the horizon, [0, 90]
    double zFactor = 1.0;
    double scale = 1.0;
    GradientAlgorithm algorithm = GradientAlgorithm::Horn;
    HillshadeVariant variant = HillshadeVariant::Default;
    /**
     * gdaldem -compute_edges. false: a pixel whose 3x3 neighbourhood touches nodata or the DEM
     * border is nodata (the hole grows by one pixel, the DEM loses its outer ring). true: such
     * neighbours are replaced (nodata -> the centre value; beyond the border -> linear
     * extrapolation), so only nodata pixels themselves stay nodata.
     */
    bool computeEdges = false;
};

/** @brief Output value reserved for nodata in hillshade rasters (shading uses 1..255). */
inline constexpr std::uint8_t kHillshadeNodata = 0;

/**
 * @brief 8-bit hillshade of the view's window, matching `gdaldem hillshade` within +-1 DN.
 *
 * Writes dem.width x dem.height bytes, row r at out + r * outStride. Values 1..255 are
 * shading (1 = facing away from the light, 255 = facing it), exactly as gdaldem. Value 0
 * (kHillshadeNodata) means nodata and must be treated as transparent by consumers:
 * hillshade of nodata areas stays nodata (transparent), never a black or white rim.
 *
 * Bad input (invalid view, non-finite or out-of-range params, null output, outStride <
 * width) returns errors with codes TOPO_INVALID_VIEW / TOPO_INVALID_PARAMS /
 * TOPO_INVALID_OUTPUT and writes nothing. Thread: pure function, any thread; concurrent calls
 * on disjoint outputs are safe (that is how callers use several cores).
 */
Diagnostics hillshade(const RasterView& dem, const HillshadeParams& params, std::uint8_t* out,
                      std::ptrdiff_t outStride);

/** @brief Validates params (shared by every function of the module). */
Diagnostics validateParams(const HillshadeParams& params, const char* where);

}  // namespace kiosk::topo
