// Units survive the import: CF `units` of a NetCDF sequence and a GeoTIFF band's unit type go
// into the store, `info` prints them, and a transfer function without units adopts them for
// its legend (config::adoptDataUnits).
#include "config/DataUnits.h"
#include "runtime/app/ImportCommand.h"
#include "runtime/app/InfoCommand.h"
#include "runtime/import/Importer.h"
#include "runtime/io/StoreReader.h"
#include "tests/unit/import/CfSequenceFile.h"
#include "tests/unit/import/ImportTestSupport.h"

#include <gdal.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using namespace kiosk;
using namespace kiosk::import;
using namespace kiosk::import::test;

namespace {

// A projected CF NetCDF rainfall sequence (2 steps, 10 x 8) with `units` (none when empty),
// its time axis starting `startHour` hours into 2024.
void writeRain(const fs::path& p, const std::string& units = "mm/h", int startHour = 0) {
    CfSequenceFile f;
    f.variable = "rain";
    f.times = {double(startHour), double(startHour + 1)};
    f.units = units;
    f.value = [](int k, int i) { return float((k * 80 + i) % 17); };
    f.write(p);
}

// `geokiosk info STORE` output (stdout redirected to a file through dup2, then restored).
std::string captureInfo(const fs::path& store) {
    const fs::path out = store.string() + ".info.txt";
    std::fflush(stdout);
    const int saved = dup(STDOUT_FILENO);
    const int fd = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, STDOUT_FILENO);
    close(fd);
    const int rc = app::runInfoCommand({store.string()});
    std::fflush(stdout);
    dup2(saved, STDOUT_FILENO);
    close(saved);
    EXPECT_EQ(rc, 0);
    std::ifstream f(out);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

}  // namespace

TEST(ImportUnits, CfUnitsOfASequenceReachStoreInfoAndLegend) {
    const fs::path dir = freshTestDir("geokiosk-units-import-test");
    const fs::path nc = dir / "rain.nc";
    writeRain(nc);
    const fs::path store = dir / "s.gpkg";
    ImportOptions o = options(store);
    o.name = "rain";
    o.variable = "rain";
    Diagnostics d = importSequence({nc.string()}, o);
    ASSERT_FALSE(d.hasErrors()) << d.format();
    auto r = openStore(store);
    ASSERT_TRUE(r);
    const auto* s = r->info().findSequence("rain");
    ASSERT_NE(s, nullptr);
    EXPECT_EQ(s->units, "mm/h");
    EXPECT_NE(captureInfo(store).find("(mm/h)"), std::string::npos);

    // --units still overrides what the file says.
    const fs::path store2 = dir / "s2.gpkg";
    ImportOptions o2 = options(store2);
    o2.name = "rain";
    o2.variable = "rain";
    o2.units = "kg m-2 h-1";
    ASSERT_FALSE(importSequence({nc.string()}, o2).hasErrors());
    EXPECT_EQ(openStore(store2)->info().findSequence("rain")->units, "kg m-2 h-1");

    // A transfer function without units adopts the sequence's for its legend.
    config::Scenario sc;
    config::Layer l;
    l.kind = config::LayerKind::Sequence;
    l.source.store = "v";
    l.source.sequence = "rain";
    l.transfer = "t";
    sc.layers.push_back(l);
    sc.transferFunctions["t"].function.units = "";
    sc.transferFunctions["u"].function.units = "in/h";
    l.transfer = "u";
    sc.layers.push_back(l);
    config::adoptDataUnits(sc,
                           [&](const std::string& id) { return id == "v" ? &r->info() : nullptr; });
    EXPECT_EQ(sc.transferFunctions["t"].function.units, "mm/h");
    EXPECT_EQ(sc.transferFunctions["u"].function.units, "in/h");  // stated units are kept
}

// A 16 x 16 UTM 10N GeoTIFF whose band states `units` (GDAL unit type).
void writeTiff(const fs::path& tif, const std::string& units) {
    GDALAllRegister();
    GDALDatasetH ds =
        GDALCreate(GDALGetDriverByName("GTiff"), tif.c_str(), 16, 16, 1, GDT_Float32, nullptr);
    ASSERT_NE(ds, nullptr);
    double gt[6] = {500000, 10, 0, 5000000, 0, -10};
    GDALSetGeoTransform(ds, gt);
    GDALSetProjection(ds, wktOf(32610).c_str());
    GDALSetRasterUnitType(GDALGetRasterBand(ds, 1), units.c_str());
    std::vector<float> v(256);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = float(i % 16);
    ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, 16, 16, v.data(), 16, 16,
                           GDT_Float32, 0, 0),
              CE_None);
    GDALClose(ds);
}

const Diagnostic* find(const Diagnostics& d, const std::string& code) {
    for (const auto& i : d.items())
        if (i.code == code) return &i;
    return nullptr;
}

TEST(ImportUnits, GeoTiffUnitTypeOfASequenceFrameIsKept) {
    const fs::path dir = freshTestDir("geokiosk-units-import-test");
    const fs::path a = dir / "depth_20240101T0000.tif", b = dir / "depth_20240101T0100.tif";
    writeTiff(a, "cm");
    writeTiff(b, "centimetres");  // the same units, spelled otherwise
    const fs::path store = dir / "s.gpkg";
    ImportOptions o = options(store);
    o.name = "depth";
    const Diagnostics d = importSequence({a.string(), b.string()}, o);
    ASSERT_FALSE(d.hasErrors()) << d.format();
    EXPECT_EQ(openStore(store)->info().findSequence("depth")->units, "cm");
}

TEST(ImportUnits, FramesInDifferentUnitsAreOneErrorNamingTheFile) {
    const fs::path dir = freshTestDir("geokiosk-units-import-test");
    const fs::path a = dir / "depth_20240101T0000.tif", b = dir / "depth_20240101T0100.tif";
    writeTiff(a, "m");
    writeTiff(b, "ft");
    ImportOptions o = options(dir / "s.gpkg");
    o.name = "depth";
    const Diagnostics d = importSequence({a.string(), b.string()}, o);
    ASSERT_TRUE(d.hasErrors());
    ASSERT_EQ(d.size(), 1u) << d.format();
    const Diagnostic& e = d.items()[0];
    EXPECT_EQ(e.code, "IMPORT_UNITS_MISMATCH");
    EXPECT_EQ(e.file, b.string());
    EXPECT_EQ(e.where, "band 1");
    EXPECT_NE(e.message.find("values are in 'ft' but " + a.string() + " is in 'm'"),
              std::string::npos)
        << e.message;
    EXPECT_FALSE(fs::exists(dir / "s.gpkg"));  // nothing half-imported

    // --units decides: imported, one warning for the frames that say otherwise.
    o.units = "m";
    const Diagnostics ok = importSequence({a.string(), b.string()}, o);
    ASSERT_FALSE(ok.hasErrors()) << ok.format();
    ASSERT_EQ(ok.size(), 1u) << ok.format();
    EXPECT_EQ(ok.items()[0].code, "IMPORT_UNITS_OVERRIDDEN");
    EXPECT_EQ(ok.items()[0].file, b.string());
    EXPECT_EQ(openStore(dir / "s.gpkg")->info().findSequence("depth")->units, "m");
}

TEST(ImportUnits, AppendedFramesMustMatchTheStoredSequence) {
    const fs::path dir = freshTestDir("geokiosk-units-import-test");
    const fs::path first = dir / "first.nc", later = dir / "later.nc", same = dir / "same.nc";
    writeRain(first, "mm/h", 0);
    writeRain(later, "in/h", 5);
    writeRain(same, "mm h-1", 10);
    const fs::path store = dir / "s.gpkg";
    ImportOptions o = options(store);
    o.name = "rain";
    o.variable = "rain";
    ASSERT_FALSE(importSequence({first.string()}, o).hasErrors());
    const Diagnostics d = importSequence({later.string()}, o);
    ASSERT_TRUE(d.hasErrors());
    ASSERT_EQ(d.size(), 1u) << d.format();
    EXPECT_EQ(d.items()[0].code, "IMPORT_UNITS_MISMATCH");
    EXPECT_EQ(d.items()[0].file, later.string());
    EXPECT_EQ(d.items()[0].where, "rain");
    EXPECT_NE(d.items()[0].message.find("'in/h' but sequence \"rain\""), std::string::npos)
        << d.format();
    ImportOptions given = o;
    given.units = "in/h";
    const Diagnostics g = importSequence({later.string()}, given);
    ASSERT_TRUE(g.hasErrors());
    EXPECT_EQ(g.firstError()->code, "IMPORT_UNITS_MISMATCH");
    EXPECT_EQ(g.firstError()->file, store.string());
    // The same units spelled another way append.
    const Diagnostics ok = importSequence({same.string()}, o);
    EXPECT_FALSE(ok.hasErrors()) << ok.format();
    auto r = openStore(store);
    EXPECT_EQ(r->info().findSequence("rain")->frameTimes.size(), 4u);
    EXPECT_EQ(r->info().findSequence("rain")->units, "mm/h");
}

TEST(ImportUnits, UnitsThatCannotBeShownAreRefusedUnlessStated) {
    const fs::path dir = freshTestDir("geokiosk-units-import-test");
    const fs::path nc = dir / "rain.nc";
    writeRain(nc, "mm/h\x1b[2J");
    ImportOptions o = options(dir / "s.gpkg");
    o.name = "rain";
    o.variable = "rain";
    const Diagnostics d = importSequence({nc.string()}, o);
    ASSERT_TRUE(d.hasErrors());
    ASSERT_EQ(d.size(), 1u) << d.format();
    EXPECT_EQ(d.items()[0].code, "IMPORT_BAD_UNITS");
    EXPECT_EQ(d.items()[0].file, nc.string());
    EXPECT_EQ(d.items()[0].where, "rain");
    EXPECT_NE(d.items()[0].message.find("control characters"), std::string::npos);
    o.units = "mm/h";
    EXPECT_FALSE(importSequence({nc.string()}, o).hasErrors());
    // Through the command: the source's bad units are bad input, a bad --units is usage.
    const std::string store = (dir / "c.gpkg").string();
    const std::vector<std::string> args = {"sequence", nc.string(),  "--store", store,    "--name",
                                           "rain",     "--variable", "rain",    "--quiet"};
    EXPECT_EQ(app::runImportCommand(args), 1);
    auto withUnits = args;
    withUnits.insert(withUnits.end(), {"--units", "mm\a"});
    EXPECT_EQ(app::runImportCommand(withUnits), 2);
    withUnits.back() = "mm/h";
    EXPECT_EQ(app::runImportCommand(withUnits), 0);
}

TEST(ImportUnits, SequenceWithoutUnitsShowsNoEmptyParentheses) {
    const fs::path dir = freshTestDir("geokiosk-units-import-test");
    const fs::path nc = dir / "rain.nc";
    writeRain(nc, "");
    const fs::path store = dir / "s.gpkg";
    ImportOptions o = options(store);
    o.name = "rain";
    o.variable = "rain";
    ASSERT_FALSE(importSequence({nc.string()}, o).hasErrors());
    EXPECT_EQ(openStore(store)->info().findSequence("rain")->units, "");
    const std::string text = captureInfo(store);
    EXPECT_NE(text.find("sequence: rain 2 frames"), std::string::npos) << text;
    EXPECT_EQ(text.find("()"), std::string::npos) << text;
}

TEST(ImportUnits, ElevationInANonLengthUnitIsSaid) {
    const fs::path dir = freshTestDir("geokiosk-units-import-test");
    const fs::path tif = dir / "t.tif";
    writeTiff(tif, "K");
    ImportOptions o = options(dir / "s.gpkg");
    const Diagnostics d = importElevation(tif.string(), o);
    ASSERT_FALSE(d.hasErrors()) << d.format();
    const Diagnostic* w = find(d, "IMPORT_UNITS_ASSUMED");
    ASSERT_NE(w, nullptr) << d.format();
    EXPECT_EQ(w->file, tif.string());
    EXPECT_NE(w->message.find("'K'"), std::string::npos);
    // --units m says the values are metres: nothing to warn about.
    fs::remove(dir / "s.gpkg");
    o.units = "m";
    const Diagnostics quiet = importElevation(tif.string(), o);
    EXPECT_EQ(find(quiet, "IMPORT_UNITS_ASSUMED"), nullptr) << quiet.format();
}
