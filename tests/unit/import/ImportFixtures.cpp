#include "tests/unit/import/ImportFixtures.h"

#include "tests/unit/import/ImportTestSupport.h"

#include <gdal.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace kiosk::import::test {

fs::path testDir() {
    return freshTestDir("geokiosk-import-test");
}

std::string sharedData(const std::string& rel) {
    const char* root = std::getenv("KIOSK_SHARED_DATA");
    fs::path base = root ? fs::path(root) : fs::path("../shared/data");
    fs::path p = base / rel;
    return fs::exists(p) ? p.string() : std::string();
}

void writeTiff(const fs::path& p, int w, int h, const double gt[6], int epsg,
               const std::vector<float>& v, std::optional<double> nodata, const char* unit) {
    GDALAllRegister();
    GDALDatasetH ds =
        GDALCreate(GDALGetDriverByName("GTiff"), p.c_str(), w, h, 1, GDT_Float32, nullptr);
    ASSERT_NE(ds, nullptr);
    GDALSetGeoTransform(ds, const_cast<double*>(gt));
    if (epsg) GDALSetProjection(ds, wktOf(epsg).c_str());
    GDALRasterBandH b = GDALGetRasterBand(ds, 1);
    if (nodata) GDALSetRasterNoDataValue(b, *nodata);
    if (unit) GDALSetRasterUnitType(b, unit);
    ASSERT_EQ(GDALRasterIO(b, GF_Write, 0, 0, w, h, const_cast<float*>(v.data()), w, h, GDT_Float32,
                           0, 0),
              CE_None);
    GDALClose(ds);
}

namespace {

float demValue(int x, int y) {
    return 1000.0f + 300.0f * std::sin(float(x) / 50.0f) * std::cos(float(y) / 70.0f) +
           0.5f * float((x * y) % 13);
}

}  // namespace

fs::path makeDem(const fs::path& dir, std::vector<float>* values) {
    const int w = 600, h = 520;
    std::vector<float> v(std::size_t(w * h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            v[std::size_t(y * w + x)] = (x < 40 && y < 30) ? -9999.f : demValue(x, y);
    const double gt[6] = {550000, 30, 0, 5200000, 0, -30};
    const fs::path p = dir / "dem.tif";
    writeTiff(p, w, h, gt, 32610, v, -9999.0);
    if (values) *values = v;
    return p;
}

std::vector<float> finestArray(io::StoreReader& r, const std::string& layer, int w, int h,
                               int frame) {
    const auto& g = r.info().grid;
    const int t = g.levels.back().tileWidth, L = g.maxLevel();
    std::vector<float> out(std::size_t(w) * std::size_t(h), kNaN);
    for (int row = 0; row * t < h; ++row)
        for (int col = 0; col * t < w; ++col) {
            auto tile = frame < 0 ? r.readElevation(layer, TileId{L, col, row})
                                  : r.readSequenceFrame(layer, frame, TileId{L, col, row});
            if (!tile) continue;
            for (int y = 0; y < t && row * t + y < h; ++y)
                for (int x = 0; x < t && col * t + x < w; ++x)
                    out[std::size_t(row * t + y) * std::size_t(w) + std::size_t(col * t + x)] =
                        tile->at(x, y);
        }
    return out;
}

std::vector<double> gdalLocationValues(const fs::path& store,
                                       const std::vector<std::pair<int, int>>& px) {
    const fs::path in = store.string() + ".coords";
    {
        std::ofstream f(in);
        for (auto [x, y] : px) f << x << " " << y << "\n";
    }
    const std::string cmd =
        "gdallocationinfo -valonly '" + store.string() + "' < '" + in.string() + "'";
    std::vector<double> out;
    if (FILE* p = popen(cmd.c_str(), "r")) {
        char line[256];
        while (std::fgets(line, sizeof line, p)) out.push_back(std::strtod(line, nullptr));
        pclose(p);
    }
    return out;
}

std::string validateGpkg(const fs::path& store) {
    const char* script = "/usr/lib/python3/dist-packages/osgeo_utils/samples/validate_gpkg.py";
    if (!fs::exists(script) || !haveTool("python3")) return "";
    const std::string cmd = std::string("python3 ") + script + " '" + store.string() + "' 2>&1";
    std::string out;
    if (FILE* p = popen(cmd.c_str(), "r")) {
        char line[512];
        while (std::fgets(line, sizeof line, p)) out += line;
        if (pclose(p) == 0) return "";
    }
    return out.empty() ? "validator failed" : out;
}

std::vector<std::string> leftovers(const fs::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().find(".tmp-") != std::string::npos)
            out.push_back(e.path().string());
    return out;
}

std::string fileBytes(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

}  // namespace kiosk::import::test
