// A layer names its store (issue 19): a scenario whose terrain comes from one store and whose
// flood sequence comes from another renders exactly as the same data from one store, and a
// store in another CRS is refused by `validate` with the JSON pointer of the layer's store.
#include "runtime/app/Session.h"
#include "runtime/app/ValidateCommand.h"
#include "runtime/core/TimeParse.h"
#include "runtime/import/Importer.h"
#include "tests/support/EglTestContext.h"
#include "tests/support/SettleView.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace kiosk::app {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 160, kHeight = 90;

std::string scenario(const std::string& stores, const std::string& terrainStore,
                     const std::string& layers) {
    return R"({ "version": 1, "stores": { )" + stores + R"( },
        "terrain": { "store": ")" +
           terrainStore + R"(", "tauGeom": 1, "tauTex": 1 },
        "clock": { "start": "2026-03-14T00:00:00Z", "end": "2026-03-14T00:08:00Z", "paused": true },
        "transferFunctions": { "depth": { "units": "m", "stops": [
            { "value": 0, "color": "#c6dbef00" }, { "value": 0.05, "color": "#6baed6" },
            { "value": 8, "color": "#08306b" } ] } },
        "layers": [ )" +
           layers + R"( ] })";
}

std::string floodLayer(const std::string& store) {
    return R"({ "id": "flood", "kind": "sequence", "source": { "store": ")" + store +
           R"(", "sequence": "flood" }, "transfer": "depth", "nodataAs": 0 })";
}

class TwoStores : public test::EglTest {
protected:
    static void SetUpTestSuite() {
        sSww = test::sharedData("anuga_sww_flood_timeseries/cairns.sww");
        if (sSww.empty()) return;
        sDir = fs::temp_directory_path() / ("kiosk-twostores-" + std::to_string(::getpid()));
        fs::create_directories(sDir);
        std::ofstream(sDir / "one.json")
            << scenario(R"("run": "run.gpkg")", "run", floodLayer("run"));
        std::ofstream(sDir / "two.json")
            << scenario(R"("bed": "bed.gpkg", "run": "run.gpkg")", "bed", floodLayer("run"));
        std::ofstream(sDir / "bare.json") << scenario(R"("bed": "bed.gpkg")", "bed", "");
        std::ofstream(sDir / "crs.json") << scenario(
            R"("bed": "bed.gpkg", "far": "elsewhere.gpkg")", "bed",
            R"({ "id": "far", "kind": "data", "source": { "store": "far", "layer": "elevation" },
                 "transfer": "depth" })");
    }
    /**
     * Import what a test needs (each test runs in its own process): "bed" the model's bed alone,
     * "run" bed and flood depth (one model run), "elsewhere" the same bed declared in another
     * CRS (UTM 10N instead of 55S). Returns the importer's messages (empty: fine).
     */
    static std::string importStore(const std::string& name) {
        import::ImportOptions o;
        o.quiet = true;
        o.name = "elevation";
        o.store = sDir / (name + ".gpkg");
        if (name == "elsewhere") o.assignCrs = "EPSG:32610";
        std::string messages = import::importElevation(sSww, o).format();
        if (name == "run" && messages.empty()) {
            o.name = "flood";
            o.start = *parseIso8601("2026-03-14T00:00:00Z");
            o.wetThreshold = 0.01;
            messages = import::importSequence({sSww}, o).format();
        }
        return messages;
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        if (!sDir.empty()) fs::remove_all(sDir, ec);
    }

    /** The scenario drawn 150 s into the flood once every tile of the view is resident. */
    gl::Image render(const std::string& name) {
        auto opened = Session::open(sDir / name, mCaps);
        EXPECT_TRUE(opened.ok()) << opened.diagnostics.format();
        if (!opened) return {};
        Session& s = **opened;
        const double time = s.startTime() + 150.0;
        auto vp = s.viewpointAt(time, "");
        EXPECT_TRUE(vp.ok());
        const math::Camera cam = makeCamera(*vp, s.terrain().bounds(), kWidth, kHeight, 45.0);
        EXPECT_TRUE(test::settleView(s, cam, time)) << name;
        for (const auto& st : s.terrain().layerStatus())
            EXPECT_EQ(st.state, scene::LayerState::Ready)
                << name << ": " << st.id << ": " << st.message;
        auto rt = makeTarget(kWidth, kHeight);
        rt.bind();
        s.drawFrame(cam, time, kWidth, kHeight);
        return rt.readColor();
    }

    static inline std::string sSww;
    static inline fs::path sDir;
};

TEST_F(TwoStores, LayerFromAnotherStoreRendersAsFromTheTerrainStore) {
    if (sSww.empty()) GTEST_SKIP() << "../shared/data/anuga_sww_flood_timeseries absent";
    ASSERT_EQ(importStore("bed"), "");
    ASSERT_EQ(importStore("run"), "");
    const gl::Image one = render("one.json"), two = render("two.json"), bare = render("bare.json");
    ASSERT_EQ(one.width, kWidth);
    ASSERT_EQ(two.width, kWidth);
    ASSERT_EQ(bare.width, kWidth);
    int differ = 0, flooded = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const auto *a = one.pixel(x, y), *b = two.pixel(x, y), *c = bare.pixel(x, y);
            for (int k = 0; k < 3; ++k) differ += std::abs(int(a[k]) - int(b[k])) > 1;
            flooded += std::abs(int(b[2]) - int(c[2])) > 8;  // the depth colours are blue
        }
    EXPECT_EQ(differ, 0) << "two stores must draw what one store with the same data draws";
    EXPECT_GT(flooded, kWidth * kHeight / 50) << "the second store's flood did not draw";
}

TEST_F(TwoStores, StoreInAnotherCrsIsRefusedWithThePointer) {
    if (sSww.empty()) GTEST_SKIP() << "../shared/data/anuga_sww_flood_timeseries absent";
    ASSERT_EQ(importStore("bed"), "");
    ASSERT_EQ(importStore("elsewhere"), "");
    std::ostringstream out, err;
    const int status = runValidateCommand({(sDir / "crs.json").string()}, out, err);
    EXPECT_EQ(status, 1) << out.str() << err.str();
    EXPECT_NE(err.str().find("/layers/0/source/store"), std::string::npos) << err.str();
    EXPECT_NE(err.str().find("UTM zone 10N"), std::string::npos) << err.str();
    // The session refuses it the same way (no half-drawn scenario).
    auto opened = Session::open(sDir / "crs.json", mCaps);
    EXPECT_FALSE(opened.ok());
}

}  // namespace
}  // namespace kiosk::app
