// What a user can get wrong: one clear line, a documented exit code, the store untouched.
#include "runtime/app/ImportCommand.h"
#include "runtime/app/InfoCommand.h"
#include "runtime/core/TimeParse.h"
#include "runtime/import/Importer.h"
#include "runtime/import/Pyramid.h"
#include "runtime/import/Topographic.h"
#include "runtime/io/StoreReader.h"
#include "runtime/topo/NormalMap.h"
#include "tests/unit/import/CfSequenceFile.h"
#include "tests/unit/import/ImportFixtures.h"
#include "tests/unit/import/ImportTestSupport.h"

#include <cpl_conv.h>
#include <gdal.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <netcdf.h>
#include <random>
#include <sstream>

namespace fs = std::filesystem;
using namespace kiosk;
using namespace kiosk::import;
using namespace kiosk::import::test;

namespace {

struct BadInput {
    const char* name;
    std::function<Diagnostics(const fs::path& dir, const fs::path& store)> run;
    const char* code;
    const char* message;
};

}  // namespace

TEST(ImportErrors, BadInputsTable) {
    const fs::path dir = testDir();
    const fs::path dem = makeDem(dir);
    const fs::path base = dir / "base.gpkg";
    ASSERT_FALSE(importElevation(dem.string(), options(base)).hasErrors());
    const double gt[6] = {550000, 30, 0, 5200000, 0, -30};
    writeTiff(dir / "nodata.tif", 50, 40, gt, 32610, std::vector<float>(2000, -5.f), -5.0);
    std::vector<float> withNan(2000, 3.f);
    withNan[777] = kNaN;
    writeTiff(dir / "nan.tif", 50, 40, gt, 32610, withNan);
    writeTiff(dir / "feet.tif", 50, 40, gt, 32610, std::vector<float>(2000, 100.f), std::nullopt,
              "ft");
    const double far[6] = {100000, 30, 0, 1000000, 0, -30};
    writeTiff(dir / "far.tif", 50, 40, far, 32610, std::vector<float>(2000, 1.f));
    { std::ofstream(dir / "text.tif") << "this is not a raster"; }
    // 446 bytes whose classic NetCDF header makes libnetcdf's nc_open ask for 7.6 GB for one
    // variable: found by SwwFuzzSmoke (tests/fuzz/CMakeLists.txt).
    fs::copy_file("tests/fuzz/seeds/sww/9d4e72bf320411a353c1a99efa4c2a6687fd2099",
                  dir / "header-bomb.sww");
    // 596 bytes whose variable of an unknown type made libnetcdf 4.9's nc_open divide by zero
    // (SIGFPE, the importer killed): found by SwwFuzzSmoke in a CI rehearsal.
    fs::copy_file("tests/fuzz/seeds/sww/96d676ae4d3a7c46781c640db9f0f7c05000ce02",
                  dir / "header-fpe.sww");
    // 15 bytes, a classic header cut off inside its dimension count: libnetcdf read the rest as
    // zeros and opened 14.9 million dimensions (1 GB, 2 s): found by SwwFuzzSmoke.
    fs::copy_file("tests/fuzz/seeds/sww/94e1f741f9a1e65ea79e7e3b92374ae7ed1c538a",
                  dir / "header-cut.sww");
    GDALDatasetH png = GDALCreate(GDALGetDriverByName("MEM"), "", 8, 8, 1, GDT_Byte, nullptr);
    GDALClose(GDALCreateCopy(GDALGetDriverByName("PNG"), (dir / "bare.png").c_str(), png, 0,
                             nullptr, nullptr, nullptr));
    GDALClose(png);
    writeTiff(dir / "a_20240101T0000.tif", 50, 40, gt, 32610, std::vector<float>(2000, 1.f));
    writeTiff(dir / "b_20240101T0000.tif", 50, 40, gt, 32610, std::vector<float>(2000, 2.f));
    writeTiff(dir / "c_20231231T0000.tif", 50, 40, gt, 32610, std::vector<float>(2000, 2.f));

    auto elev = [](const char* file, std::function<void(ImportOptions&)> tweak = {}) {
        return [=](const fs::path& d, const fs::path& store) {
            ImportOptions o = options(store);
            o.name = "second";
            if (tweak) tweak(o);
            return importElevation((d / file).string(), o);
        };
    };
    auto seq = [](std::vector<std::string> files) {
        return [=](const fs::path& d, const fs::path& store) {
            ImportOptions o = options(store);
            o.name = "s";
            std::vector<std::string> paths;
            for (const auto& f : files) paths.push_back((d / f).string());
            return importSequence(paths, o);
        };
    };
    const BadInput cases[] = {
        {"missing file", elev("nope.tif"), "IMPORT_UNREADABLE", "nope.tif: cannot read raster"},
        {"not a raster", elev("text.tif"), "IMPORT_UNREADABLE", "text.tif: cannot read raster"},
        {"SWW header claiming gigabytes", elev("header-bomb.sww"), "IMPORT_UNREADABLE",
         "header-bomb.sww: cannot read SWW"},
        {"SWW header that made nc_open divide by zero", elev("header-fpe.sww"), "IMPORT_UNREADABLE",
         "header-fpe.sww: cannot read SWW: header gives a variable the unknown type"},
        {"SWW header cut off inside its lists", elev("header-cut.sww"), "IMPORT_UNREADABLE",
         "header-cut.sww: cannot read SWW: header ends before the lists it declares"},
        {"no georeferencing", elev("bare.png"), "IMPORT_NO_GEOREF",
         "bare.png: source has no georeferencing"},
        {"all nodata", elev("nodata.tif"), "IMPORT_ALL_NODATA",
         "nodata.tif: source holds no valid value"},
        {"NaN values", elev("nan.tif"), "IMPORT_NAN",
         "nan.tif: row 15: source contains NaN values"},
        {"declared feet, told metres", elev("feet.tif", [](ImportOptions& o) { o.units = "m"; }),
         "IMPORT_UNITS_MISMATCH", "feet.tif: source declares its values in 'ft' but --units m"},
        {"outside the store", elev("far.tif"), "IMPORT_EXTENT_MISMATCH", "far.tif: source extent"},
        {"bad CRS", elev("far.tif", [](ImportOptions& o) { o.crs = "EPSG:99999999"; }),
         "IMPORT_BAD_CRS", "unknown CRS 'EPSG:99999999'"},
        {"existing layer name",
         elev("far.tif",
              [](ImportOptions& o) {
                  o.name = "elevation";
                  o.crs.reset();
              }),
         "IMPORT_EXTENT_MISMATCH", "far.tif"},
        {"duplicate timestamps", seq({"a_20240101T0000.tif", "b_20240101T0000.tif"}),
         "IMPORT_TIMES_DUPLICATE",
         "b_20240101T0000.tif: frame 1: duplicate timestamp 2024-01-01T00:00:00Z"},
        {"unsorted timestamps", seq({"a_20240101T0000.tif", "c_20231231T0000.tif"}),
         "IMPORT_TIMES_UNSORTED",
         "c_20231231T0000.tif: frame 1: timestamp 2023-12-31T00:00:00Z is earlier"},
        {"no timestamps", seq({"nan.tif"}), "IMPORT_NO_TIMES",
         "nan.tif: no timestamp for this frame"},
    };
    const std::string original = fileBytes(base);
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        const fs::path store = dir / "case.gpkg";
        fs::copy_file(base, store, fs::copy_options::overwrite_existing);
        Diagnostics d = c.run(dir, store);
        ASSERT_TRUE(d.hasErrors()) << d.format();
        EXPECT_EQ(d.firstError()->code, c.code) << d.format();
        EXPECT_NE(d.firstError()->format().find(c.message), std::string::npos) << d.format();
        EXPECT_EQ(fileBytes(store), original);
        EXPECT_TRUE(leftovers(dir).empty());
    }
}

TEST(ImportErrors, FailureMidImportLeavesTheStoreUntouched) {
    const fs::path dir = testDir();
    const fs::path dem = makeDem(dir);
    const fs::path store = dir / "s.gpkg";
    ASSERT_FALSE(importElevation(dem.string(), options(store)).hasErrors());
    const std::string before = fileBytes(store);
    ImportOptions o = options(store);
    o.name = "again";
    o.failAfterTiles = 5;
    Diagnostics d = importElevation(dem.string(), o);
    ASSERT_TRUE(d.hasErrors());
    EXPECT_EQ(d.firstError()->code, "IMPORT_INJECTED_FAILURE");
    EXPECT_EQ(fileBytes(store), before);
    EXPECT_TRUE(leftovers(dir).empty());
    auto r = openStore(store);
    EXPECT_EQ(r->info().findLayer("again"), nullptr);

    // A new store that fails is not created at all.
    const fs::path fresh = dir / "fresh.gpkg";
    ImportOptions f = options(fresh);
    f.failAfterTiles = 2;
    EXPECT_TRUE(importElevation(dem.string(), f).hasErrors());
    EXPECT_FALSE(fs::exists(fresh));
    EXPECT_TRUE(leftovers(dir).empty());
}

TEST(ImportCommand, ExitCodes) {
    const fs::path dir = testDir();
    const fs::path dem = makeDem(dir);
    const std::string store = (dir / "s.gpkg").string();
    EXPECT_EQ(app::runImportCommand({}), 2);
    EXPECT_EQ(app::runImportCommand({"elevaton", dem.string(), "--store", store}), 2);
    EXPECT_EQ(app::runImportCommand({"elevation", dem.string()}), 2);
    EXPECT_EQ(
        app::runImportCommand({"elevation", dem.string(), "--store", store, "--pixel-sise", "3"}),
        2);
    EXPECT_EQ(
        app::runImportCommand({"elevation", dem.string(), "--store", store, "--z-scale", "abc"}),
        2);
    EXPECT_EQ(app::runImportCommand({"imagery", dem.string(), "--store", store}), 2);
    EXPECT_EQ(
        app::runImportCommand({"elevation", (dir / "missing.tif").string(), "--store", store}), 1);
    EXPECT_FALSE(fs::exists(store));
    EXPECT_EQ(app::runImportCommand({"elevation", dem.string(), "--store", store, "--quiet"}), 0);
    EXPECT_EQ(app::runInfoCommand({store}), 0);
    EXPECT_EQ(app::runInfoCommand({store, "--json"}), 0);
    EXPECT_EQ(app::runInfoCommand({(dir / "nothing.gpkg").string()}), 1);
    EXPECT_EQ(app::runInfoCommand({}), 2);
}
