#include "tests/unit/topo/GdalFixture.h"

#include <cpl_conv.h>
#include <gdal_priv.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>

namespace kiosk::topo::test {

namespace fs = std::filesystem;

namespace {

// Reading a raster must never write a .aux.xml next to the shared (read-only) data.
void initGdal() {
    static const bool done = [] {
        CPLSetConfigOption("GDAL_PAM_ENABLED", "NO");
        GDALAllRegister();
        return true;
    }();
    (void)done;
}

GDALDataset* open(const std::string& path, std::string& error) {
    initGdal();
    auto* ds = static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_ReadOnly));
    if (ds == nullptr) error = path + ": GDAL cannot open it: " + CPLGetLastErrorMsg();
    return ds;
}

}  // namespace

std::optional<FloatRaster> readFloat(const std::string& path, std::string& error) {
    GDALDataset* ds = open(path, error);
    if (ds == nullptr) return std::nullopt;
    FloatRaster r;
    r.width = ds->GetRasterXSize();
    r.height = ds->GetRasterYSize();
    if (ds->GetGeoTransform(r.geoTransform) != CE_None) {
        const double identity[6] = {0, 1, 0, 0, 0, 1};
        std::copy(identity, identity + 6, r.geoTransform);
    }
    GDALRasterBand* band = ds->GetRasterBand(1);
    r.values.resize(static_cast<std::size_t>(r.width) * r.height);
    const CPLErr err = band->RasterIO(GF_Read, 0, 0, r.width, r.height, r.values.data(), r.width,
                                      r.height, GDT_Float32, 0, 0);
    int hasNodata = 0;
    const double nodata = band->GetNoDataValue(&hasNodata);
    GDALClose(ds);
    if (err != CE_None) {
        error = path + ": read failed: " + CPLGetLastErrorMsg();
        return std::nullopt;
    }
    if (hasNodata)
        for (float& v : r.values)
            if (v == static_cast<float>(nodata)) v = NAN;
    return r;
}

std::optional<ByteRaster> readByte(const std::string& path, std::string& error) {
    GDALDataset* ds = open(path, error);
    if (ds == nullptr) return std::nullopt;
    ByteRaster r;
    r.width = ds->GetRasterXSize();
    r.height = ds->GetRasterYSize();
    r.values.resize(static_cast<std::size_t>(r.width) * r.height);
    const CPLErr err = ds->GetRasterBand(1)->RasterIO(
        GF_Read, 0, 0, r.width, r.height, r.values.data(), r.width, r.height, GDT_Byte, 0, 0);
    GDALClose(ds);
    if (err != CE_None) {
        error = path + ": read failed: " + CPLGetLastErrorMsg();
        return std::nullopt;
    }
    return r;
}

bool writeFloatTiff(const std::string& path, const FloatRaster& r, std::string& error) {
    initGdal();
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
    if (drv == nullptr) {
        error = "GTiff driver missing";
        return false;
    }
    GDALDataset* ds = drv->Create(path.c_str(), r.width, r.height, 1, GDT_Float32, nullptr);
    if (ds == nullptr) {
        error = path + ": cannot create: " + CPLGetLastErrorMsg();
        return false;
    }
    double gt[6];
    std::copy(r.geoTransform, r.geoTransform + 6, gt);
    ds->SetGeoTransform(gt);
    GDALRasterBand* band = ds->GetRasterBand(1);
    band->SetNoDataValue(std::nan(""));
    const CPLErr err =
        band->RasterIO(GF_Write, 0, 0, r.width, r.height, const_cast<float*>(r.values.data()),
                       r.width, r.height, GDT_Float32, 0, 0);
    GDALClose(ds);
    if (err != CE_None) {
        error = path + ": write failed: " + CPLGetLastErrorMsg();
        return false;
    }
    return true;
}

std::string gdaldemPath() {
    const char* path = std::getenv("PATH");
    std::string dirs = path ? path : "/usr/bin:/bin";
    std::size_t start = 0;
    while (start <= dirs.size()) {
        const std::size_t end = std::min(dirs.find(':', start), dirs.size());
        const fs::path candidate = fs::path(dirs.substr(start, end - start)) / "gdaldem";
        std::error_code ec;
        if (!candidate.parent_path().empty() && fs::is_regular_file(candidate, ec))
            return candidate.string();
        start = end + 1;
    }
    return {};
}

int runGdaldem(const std::string& args, const std::string& in, const std::string& out) {
    const std::string cmd = "GDAL_PAM_ENABLED=NO '" + gdaldemPath() + "' hillshade " + args +
                            " -q '" + in + "' '" + out + "' >/dev/null 2>&1";
    return std::system(cmd.c_str());
}

std::string makeTempDir() {
    std::random_device rd;
    for (int attempt = 0; attempt < 100; ++attempt) {
        const fs::path dir = fs::temp_directory_path() / ("kiosk-topo-" + std::to_string(rd()));
        std::error_code ec;
        if (fs::create_directory(dir, ec)) return dir.string();
    }
    return {};
}

void removeDir(const std::string& dir) {
    std::error_code ec;
    if (!dir.empty()) fs::remove_all(dir, ec);
}

std::string sharedData(const std::string& rel) {
    const char* env = std::getenv("KIOSK_SHARED_DATA");
    const fs::path base = env ? fs::path(env) : fs::path("../shared/data");
    std::error_code ec;
    const fs::path p = base / rel;
    return fs::exists(p, ec) ? p.string() : std::string{};
}

}  // namespace kiosk::topo::test
