#include "tests/support/FloatTiff.h"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <vector>

namespace kiosk::test {

std::string writeFloatTiff(const std::string& path, int size, double west, double north,
                           double post, const std::function<float(int, int)>& value,
                           const double* nodata) {
    GDALAllRegister();
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    GDALDataset* ds =
        driver ? driver->Create(path.c_str(), size, size, 1, GDT_Float32, nullptr) : nullptr;
    if (!ds) return "cannot create " + path;
    double geo[6] = {west, post, 0.0, north, 0.0, -post};
    ds->SetGeoTransform(geo);
    OGRSpatialReference srs;
    srs.importFromEPSG(32610);
    ds->SetSpatialRef(&srs);
    if (nodata) ds->GetRasterBand(1)->SetNoDataValue(*nodata);
    std::vector<float> z(std::size_t(size) * std::size_t(size));
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            z[std::size_t(y) * std::size_t(size) + std::size_t(x)] = value(x, y);
    const bool ok = ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, size, size, z.data(), size, size,
                                                   GDT_Float32, 0, 0) == CE_None;
    GDALClose(ds);
    return ok ? std::string() : "cannot write " + path;
}

}  // namespace kiosk::test
