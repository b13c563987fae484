#include "runtime/import/ImageryResolution.h"

#include "runtime/import/GdalRaster.h"
#include "runtime/import/GeoTarget.h"

#include <cpl_string.h>
#include <gdal_alg.h>

#include <algorithm>
#include <cmath>

namespace kiosk::import {

int imageryExtraLevels(GDALDatasetH src, const io::TileGrid& grid, int maxExtra,
                       std::int64_t budget, const std::optional<std::string>& assignWkt) {
    if (grid.levels.empty() || maxExtra <= 0) return 0;
    double gt[6];
    if (GDALGetGeoTransform(src, gt) != CE_None) return 0;
    // The source's pixel and extent in the grid's CRS, as the warp onto the grid will see them.
    const char* own = GDALGetProjectionRef(src);
    const std::string srcWkt = assignWkt ? *assignWkt : (own && *own ? own : grid.crsWkt);
    double pixel = 0, width = 0;
    if (sameCrs(srcWkt, grid.crsWkt) && gt[2] == 0 && gt[4] == 0) {
        pixel = std::min(std::fabs(gt[1]), std::fabs(gt[5]));
        width = std::fabs(gt[1]) * GDALGetRasterXSize(src);
    } else {
        CPLStringList topts;
        topts.SetNameValue("SRC_SRS", srcWkt.c_str());
        topts.SetNameValue("DST_SRS", grid.crsWkt.c_str());
        void* tr = GDALCreateGenImgProjTransformer2(src, nullptr, topts.List());
        if (!tr) return 0;
        double ogt[6], ext[4];
        int nx = 0, ny = 0;
        const bool ok = GDALSuggestedWarpOutput2(src, GDALGenImgProjTransform, tr, ogt, &nx, &ny,
                                                 ext, 0) == CE_None;
        GDALDestroyGenImgProjTransformer(tr);
        if (!ok || nx < 1) return 0;
        pixel = ogt[1];
        width = ext[2] - ext[0];
    }
    if (!(pixel > 0)) return 0;
    const double finest = grid.levels.back().pixelXSize;
    const int tile = grid.levels.back().tileWidth;
    int extra = 0;
    // 1e-6: a source of exactly half the grid's pixel is finer, not a rounding victim.
    while (extra < maxExtra && finest / double(1 << (extra + 1)) >= pixel * (1 - 1e-6)) ++extra;
    while (extra > 0 &&
           estimateImportBytes(std::int64_t(std::ceil(width / (finest / double(1 << extra)))),
                               tile) > budget)
        --extra;
    return extra;
}

io::TileGrid refinedGrid(const io::TileGrid& grid, int extra) {
    io::TileGrid g = grid;
    if (extra > 0 && !grid.levels.empty())
        g.setPyramid(int(grid.levels.size()) + extra, grid.levels.back().tileWidth,
                     grid.levels.back().tileHeight,
                     grid.levels.back().pixelXSize / double(1 << extra));
    return g;
}

}  // namespace kiosk::import
