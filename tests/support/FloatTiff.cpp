#include "tests/support/FloatTiff.h"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
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

std::string writeRasterTiff(const std::string& path, const RasterSpec& spec,
                            const std::function<double(int, int, int)>& value) {
    GDALAllRegister();
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    const GDALDataType type = spec.bands == 1 ? GDT_Float32 : GDT_Byte;
    GDALDataset* ds =
        driver ? driver->Create(path.c_str(), spec.width, spec.height, spec.bands, type, nullptr)
               : nullptr;
    if (!ds) return "cannot create " + path;
    double geo[6];
    std::copy(spec.geoTransform, spec.geoTransform + 6, geo);
    ds->SetGeoTransform(geo);
    OGRSpatialReference srs;
    srs.importFromEPSG(spec.epsg);
    srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    ds->SetSpatialRef(&srs);
    if (spec.nodata && type == GDT_Float32) ds->GetRasterBand(1)->SetNoDataValue(std::nan(""));
    const std::size_t n = std::size_t(spec.width) * std::size_t(spec.height);
    std::vector<double> v(n);
    bool ok = true;
    for (int b = 0; b < spec.bands && ok; ++b) {
        for (int y = 0; y < spec.height; ++y)
            for (int x = 0; x < spec.width; ++x)
                v[std::size_t(y) * std::size_t(spec.width) + std::size_t(x)] = value(b, x, y);
        ok = ds->GetRasterBand(b + 1)->RasterIO(GF_Write, 0, 0, spec.width, spec.height, v.data(),
                                                spec.width, spec.height, GDT_Float64, 0,
                                                0) == CE_None;
    }
    GDALClose(ds);
    return ok ? std::string() : "cannot write " + path;
}

}  // namespace kiosk::test
