#pragma once

#include "runtime/core/Diagnostics.h"

#include <cstddef>
#include <string>

namespace kiosk::topo {

/**
 * @brief Read-only view of a float elevation grid: an output window plus an apron around it.
 *
 * The topographic functions (hillshade, shadows, normal maps) compute one output pixel per
 * window pixel and read neighbours from the apron, so a tile cut from a larger DEM is shaded
 * exactly as if the whole DEM had been processed at once (no seams between tiles).
 *
 * Layout: `data` points at window pixel (0,0); pixel (col,row) is `data[row * stride + col]`
 * for col in [-apronLeft, width + apronRight) and row in [-apronTop, height + apronBottom).
 * Those are the only elements ever read.
 *
 * Meaning of the apron widths: an apron of 0 on a side says that the window touches the
 * border of the source DEM there (there is nothing beyond it). The hillshade then follows
 * GDAL's edge rules for that side (nodata, or extrapolation with computeEdges). A caller that
 * merely forgot the apron gets DEM-border behaviour at every tile edge, i.e. visible seams.
 * Shadow rays need a wide apron on the sun side, see requiredShadowApron().
 *
 * Values: heights in vertical units (scaled by zFactor / scale in the params); NaN = nodata.
 * Rows run southwards (north-up raster), columns eastwards. Pixel sizes are positive
 * horizontal units per pixel (metres for projected DEMs, degrees for geographic ones with a
 * matching `scale`, as in gdaldem).
 *
 * Thread safety: a view is a plain value; the functions reading it never write through it, so
 * many threads may read the same DEM through different views at once.
 */
struct RasterView {
    const float* data = nullptr;
    int width = 0;
    int height = 0;
    std::ptrdiff_t stride = 0;  ///< floats from one row to the next
    int apronLeft = 0;
    int apronTop = 0;
    int apronRight = 0;
    int apronBottom = 0;
    double pixelSizeX = 1.0;
    double pixelSizeY = 1.0;

    /** @brief Value at window coordinates (may be inside the apron). No bounds check. */
    float at(int col, int row) const noexcept {
        return data[static_cast<std::ptrdiff_t>(row) * stride + col];
    }

    /**
     * @brief View of the window (x0, y0, w, h) of a whole in-memory DEM of demWidth x
     * demHeight floats (`stride` floats per row), with aprons reaching as far as the DEM
     * goes, capped at `maxApron` pixels per side. The window is clipped to the DEM; a window
     * entirely outside gives width/height 0 (validate() reports it).
     */
    static RasterView window(const float* dem, int demWidth, int demHeight, std::ptrdiff_t stride,
                             int x0, int y0, int w, int h, double pixelSizeX, double pixelSizeY,
                             int maxApron = 1 << 30) noexcept;

    /**
     * @brief Checks the view before any pixel is read: non-null data, positive size, non-negative
     * aprons, stride large enough, finite positive pixel sizes. Errors carry code
     * TOPO_INVALID_VIEW and name the field; `where` names the calling function.
     */
    Diagnostics validate(const std::string& where) const;
};

}  // namespace kiosk::topo
