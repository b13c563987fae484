#pragma once

// Helpers shared by the importer tests: a fresh directory per test, tool probing, EPSG WKT,
// default import options and opening a store.
#include "runtime/import/Importer.h"
#include "runtime/io/StoreReader.h"

#include <cpl_conv.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

namespace kiosk::import::test {

/** @brief An empty directory temp/<suite>/<test name>. */
inline std::filesystem::path freshTestDir(const std::string& suite) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::filesystem::path d = std::filesystem::temp_directory_path() / suite / info->name();
    std::filesystem::remove_all(d);
    std::filesystem::create_directories(d);
    return d;
}

inline bool haveTool(const char* name) {
    return std::system((std::string("command -v ") + name + " >/dev/null 2>&1").c_str()) == 0;
}

inline std::string wktOf(int epsg) {
    OGRSpatialReferenceH s = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(s, epsg);
    char* w = nullptr;
    OSRExportToWkt(s, &w);
    std::string out = w;
    CPLFree(w);
    OSRDestroySpatialReference(s);
    return out;
}

inline ImportOptions options(const std::filesystem::path& store) {
    ImportOptions o;
    o.store = store;
    o.quiet = true;
    return o;
}

inline std::unique_ptr<io::StoreReader> openStore(const std::filesystem::path& p) {
    auto r = io::StoreReader::open(p);
    EXPECT_TRUE(r.ok()) << r.diagnostics.format();
    return r.ok() ? std::move(*r) : nullptr;
}

// Every finest-level sample of a scalar layer (or, frame >= 0, of that frame of sequence
// `layer`), visited with its pixel-centre coordinates.
inline void forEachSample(io::StoreReader& r, const std::string& layer,
                          const std::function<void(double x, double y, float v)>& visit,
                          int frame = -1) {
    const auto& g = r.info().grid;
    const auto& m = g.levels.back();
    const int L = g.maxLevel(), t = m.tileWidth;
    for (int row = 0; row < m.matrixHeight; ++row)
        for (int col = 0; col < m.matrixWidth; ++col) {
            auto tile = frame < 0 ? r.readElevation(layer, TileId{L, col, row})
                                  : r.readSequenceFrame(layer, frame, TileId{L, col, row});
            if (!tile) continue;
            for (int y = 0; y < t; ++y)
                for (int x = 0; x < t; ++x) {
                    const float v = tile->at(x, y);
                    if (std::isnan(v)) continue;
                    visit(g.minX + ((col * t + x) + 0.5) * m.pixelXSize,
                          g.maxY - ((row * t + y) + 0.5) * m.pixelYSize, v);
                }
        }
}

// Store CRS -> WGS 84 lon/lat, exact (PROJ), longitudes as they come.
struct ToLonLat {
    OGRSpatialReferenceH src = nullptr, dst = nullptr;
    OGRCoordinateTransformationH ct = nullptr;
    explicit ToLonLat(const std::string& wkt) {
        src = OSRNewSpatialReference(wkt.c_str());
        dst = OSRNewSpatialReference(nullptr);
        OSRImportFromEPSG(dst, 4326);
        OSRSetAxisMappingStrategy(src, OAMS_TRADITIONAL_GIS_ORDER);
        OSRSetAxisMappingStrategy(dst, OAMS_TRADITIONAL_GIS_ORDER);
        ct = OCTNewCoordinateTransformation(src, dst);
    }
    ~ToLonLat() {
        OCTDestroyCoordinateTransformation(ct);
        OSRDestroySpatialReference(src);
        OSRDestroySpatialReference(dst);
    }
    bool operator()(double& x, double& y) const { return OCTTransform(ct, 1, &x, &y, nullptr); }
};

}  // namespace kiosk::import::test
