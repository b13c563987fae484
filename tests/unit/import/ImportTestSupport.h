#pragma once

// Helpers shared by the importer tests: a fresh directory per test, tool probing, EPSG WKT,
// default import options and opening a store.
#include "runtime/import/Importer.h"
#include "runtime/io/StoreReader.h"

#include <cpl_conv.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include <cstdlib>
#include <filesystem>
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

}  // namespace kiosk::import::test
