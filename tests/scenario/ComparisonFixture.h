#pragma once
// Two synthetic model runs for the comparison-lens tests (issue 19): stores "a" and "b" on the
// same flat 64 x 64 grid (30 m, UTM 10N), each with a sequence "run" of six hourly frames whose
// value is uniform per frame (A: k, B: 2 + k / 2), so the step a side shows can be read from
// any of its pixels. A is drawn in reds, B in blues; the sun stands at the zenith over the flat
// bed, so a pixel's colour is its transfer function's colour (lighting factor 1).
#include "runtime/app/Session.h"
#include "runtime/core/TimeParse.h"
#include "runtime/import/Importer.h"
#include "tests/support/EglTestContext.h"
#include "tests/support/SettleView.h"
#include "tests/unit/import/ImportTestSupport.h"

#include <gdal.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace kiosk::test {

namespace compare {

namespace fs = std::filesystem;
inline constexpr int kFrames = 6;
inline constexpr double kWest = 500000, kNorth = 5000000, kPixel = 30, kSize = 64 * 30;
inline constexpr double kCentreX = kWest + kSize / 2, kCentreY = kNorth - kSize / 2;
inline constexpr const char* kStart = "2026-03-14T00:00:00Z";

inline float valueA(int k) {
    return float(k);
}
inline float valueB(int k) {
    return 2.0f + 0.5f * float(k);
}

inline void writeTiff(const fs::path& p, float value) {
    GDALDatasetH ds =
        GDALCreate(GDALGetDriverByName("GTiff"), p.c_str(), 64, 64, 1, GDT_Float32, nullptr);
    ASSERT_NE(ds, nullptr);
    double gt[6] = {kWest, kPixel, 0, kNorth, 0, -kPixel};
    GDALSetGeoTransform(ds, gt);
    GDALSetProjection(ds, import::test::wktOf(32610).c_str());
    std::vector<float> v(64 * 64, value);
    ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, 64, 64, v.data(), 64, 64,
                           GDT_Float32, 0, 0),
              CE_None);
    GDALClose(ds);
}

/** @brief Store `name`.gpkg in `dir`: the flat bed and the run of `value(k)`; "" or the error. */
template <class Value>
std::string makeRun(const fs::path& dir, const std::string& name, Value value) {
    GDALAllRegister();
    writeTiff(dir / "bed.tif", 100.0f);
    import::ImportOptions o;
    o.quiet = true;
    o.store = dir / (name + ".gpkg");
    o.name = "elevation";
    if (auto d = import::importElevation((dir / "bed.tif").string(), o); d.hasErrors())
        return d.format();
    std::vector<std::string> files;
    std::ofstream times(dir / (name + "-times.csv"));
    const double start = *parseIso8601(kStart);
    for (int k = 0; k < kFrames; ++k) {
        const fs::path f = dir / (name + "_" + std::to_string(k) + ".tif");
        writeTiff(f, value(k));
        files.push_back(f.string());
        times << f.filename().string() << "," << formatIso8601(start + 3600.0 * k) << "\n";
    }
    times.close();
    o.name = "run";
    o.timesCsv = (dir / (name + "-times.csv")).string();
    o.units = "m";
    return import::importSequence(files, o).format();
}

/** @brief A scenario over both stores, viewed from straight above. */
inline std::string scenario(const std::string& layers, const std::string& lenses) {
    return std::string(R"({ "version": 1, "stores": { "a": "a.gpkg", "b": "b.gpkg" },
  "terrain": { "store": "a", "tauGeom": 1, "tauTex": 1 },
  "clock": { "start": "2026-03-14T00:00:00Z", "end": "2026-03-14T05:00:00Z", "paused": true },
  "lighting": { "sunAzimuth": 0, "sunAltitude": 90, "ambient": 0.3 },
  "overlays": { "legend": { "enabled": false }, "timeLabel": { "enabled": false },
                "title": { "enabled": false }, "status": { "enabled": false },
                "progress": { "enabled": false } },
  "viewpoints": { "top": { "target": [500960, 4999040, 100], "heading": 0, "pitch": -89.9,
                           "range": 2600 } },
  "camera": { "viewpoint": "top" },
  "transferFunctions": {
    "reds": { "stops": [ { "value": 0, "color": "#200000" }, { "value": 6, "color": "#ff6040" } ] },
    "blues": { "stops": [ { "value": 0, "color": "#000020" }, { "value": 6, "color": "#4060ff" } ] },
    "diff": { "stops": [ { "value": -3, "color": "#2166ac" }, { "value": 0, "color": "#f7f7f7" },
                         { "value": 3, "color": "#b2182b" } ] } },
  "layers": [ )") +
           layers + R"( ],
  "lenses": [ )" +
           lenses + R"( ] })";
}

inline std::string runLayer(const std::string& id, const std::string& store,
                            const std::string& transfer, const std::string& extra = "") {
    return R"({ "id": ")" + id + R"(", "kind": "sequence", "source": { "store": ")" + store +
           R"(", "sequence": "run" }, "transfer": ")" + transfer + R"(", "interpolate": "none")" +
           extra + " }";
}
inline const std::string kRuns = runLayer("A", "a", "reds") + ", " + runLayer("B", "b", "blues");

/** @brief Screen pixel (top row first) of scene point (x, y) at the bed's height. */
inline glm::ivec2 project(const math::Camera& cam, double x, double y, int w, int h) {
    const glm::dvec4 c = cam.projection() * cam.view() * glm::dvec4(x, y, 100.0, 1.0);
    const glm::dvec2 ndc = glm::dvec2(c) / c.w;
    return {int(std::floor((ndc.x + 1) * 0.5 * w)), int(std::floor((1 - ndc.y) * 0.5 * h))};
}

}  // namespace compare

/** @brief GL fixture with both runs imported once per test process into a fresh folder. */
class ComparisonTest : public EglTest {
protected:
    static constexpr int kW = 320, kH = 180;
    static void SetUpTestSuite() {
        sDir =
            compare::fs::temp_directory_path() / ("kiosk-comparison-" + std::to_string(::getpid()));
        compare::fs::create_directories(sDir);
        sImport = compare::makeRun(sDir, "a", compare::valueA);
        if (sImport.empty()) sImport = compare::makeRun(sDir, "b", compare::valueB);
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        compare::fs::remove_all(sDir, ec);
    }
    void SetUp() override {
        EglTest::SetUp();
        ASSERT_EQ(sImport, "");
    }
    /** @brief Write `text` as `name` in the test folder and open it. */
    std::unique_ptr<app::Session> open(const std::string& name, const std::string& text) {
        std::ofstream(sDir / name) << text;
        auto s = app::Session::open(sDir / name, mCaps);
        EXPECT_TRUE(s.ok()) << s.diagnostics.format();
        return s ? std::move(*s.value) : nullptr;
    }
    math::Camera camera(app::Session& s) {
        auto vp = s.viewpointAt(s.startTime(), "");
        return app::makeCamera(*vp, s.terrain().bounds(), kW, kH, 45.0);
    }
    /** @brief The view `hours` after the start (whole hours: frame step k) once every tile of
     * the view is resident. */
    gl::Image settled(app::Session& s, double hours) {
        const double t = s.startTime() + 3600.0 * hours;
        const math::Camera cam = camera(s);
        EXPECT_TRUE(settleView(s, cam, t));
        auto rt = makeTarget(kW, kH);
        rt.bind();
        s.drawFrame(cam, t, kW, kH);
        return rt.readColor();
    }
    static inline compare::fs::path sDir;
    static inline std::string sImport;
};

}  // namespace kiosk::test
