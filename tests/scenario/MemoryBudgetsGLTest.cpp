// Per-kiosk memory budgets beside the tile cache (issue 15, runtime/app/MemoryBudgets.h): a
// scenario needing more LUT or mapping-array bytes than its kiosk allows is refused before
// anything is allocated, with one line naming the kiosk file, line, pointer and the figures; the
// figure checked is the figure held (estimate == what the scene allocates); the font atlas is
// degraded to fit; the SQLite page cache setting is what SQLite reports per connection.
#include "runtime/app/MemoryBudgets.h"
#include "runtime/app/Session.h"
#include "runtime/io/StoreReader.h"
#include "tests/support/DemoStoreTest.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace kiosk::app {
namespace {

namespace fs = std::filesystem;
constexpr const char* kDemo = "scenarios/demo/rainier.json";
constexpr const char* kRoute = "scenarios/mappings/route.json";

config::MemoryBudget kioskBudget(std::int64_t bytes, const char* pointer) {
    return {bytes, "/etc/geokiosk/kiosk.json", 7, 19, pointer};
}

/** The demo with `extra` more data layers, each through its own transfer function. */
void addDataLayers(config::Scenario& sc, int extra) {
    const config::Layer relief = *sc.findLayer("relief");
    for (int i = 0; i < extra; ++i) {
        config::Layer l = relief;
        l.id = "relief" + std::to_string(i);
        l.transfer = "t" + std::to_string(i);
        l.pointer = "/layers/" + std::to_string(sc.layers.size());
        config::TransferFunctionDef def = sc.transferFunctions.at("relief");
        def.name = l.transfer;
        sc.transferFunctions[l.transfer] = def;
        l.operation.opacity = 0.1;
        sc.layers.push_back(l);
    }
}

class MemoryBudgets : public test::DemoStoreTest {
protected:
    void TearDown() override {
        io::StoreReader::setPageCacheBytes(0);  // back to the default for other tests
        test::EglTest::TearDown();
    }
    void drawOnce(Session& s, int w, int h) {
        auto rt = gl::RenderTarget::create(w, h);
        ASSERT_TRUE(rt.ok());
        auto vp = s.viewpointAt(s.startTime(), "overview");
        ASSERT_TRUE(vp.ok());
        rt->bind();
        s.drawFrame(makeCamera(*vp, s.terrain().bounds(), w, h, 45), s.startTime(), w, h);
    }
};

TEST_F(MemoryBudgets, LutBudgetRefusesManyTransferFunctionsAndNamesTheKioskFile) {
    // Six data layers (two of the demo's, four added): 6 LUTs, each a ramp of 1024 RGBA8 texels
    // (legends) and the stack's copy with its below, above and nodata texels (1027): 6 x 8204
    // bytes.
    auto over = Session::open(kDemo, mCaps, [](config::Scenario& sc) {
        addDataLayers(sc, 4);
        sc.memoryBudgets.luts = kioskBudget(16384, "/budgets/lutBytes");
    });
    ASSERT_FALSE(over.ok());
    const Diagnostic* e = over.diagnostics.firstError();
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->code, "BUDGET_LUTS");
    const std::string line = e->format();
    EXPECT_NE(line.find("/etc/geokiosk/kiosk.json:7:19: /budgets/lutBytes: "), std::string::npos)
        << line;
    EXPECT_NE(line.find("49224 bytes) of transfer-function LUTs (6 LUTs)"), std::string::npos)
        << line;
    EXPECT_NE(line.find("budget of 16.0 KiB (16384 bytes)"), std::string::npos) << line;
    EXPECT_EQ(line.find('\n'), std::string::npos);

    // The same scenario under a budget it fits: the LUTs the scene holds are the figure checked.
    auto fits = Session::open(kDemo, mCaps, [](config::Scenario& sc) {
        addDataLayers(sc, 4);
        sc.memoryBudgets.luts = kioskBudget(49224, "/budgets/lutBytes");
    });
    ASSERT_TRUE(fits.ok()) << fits.diagnostics.format();
    EXPECT_EQ((*fits)->memoryUsage().lutBytes, 49224u);
    EXPECT_EQ(memoryNeeds((*fits)->scenario()).lutBytes, 49224u);
}

TEST_F(MemoryBudgets, MappingBudgetRefusesRoutesArraysAndTheHeldFigureMatches) {
    if (!fs::exists(kRoute)) GTEST_SKIP() << kRoute;
    auto over = Session::open(kRoute, mCaps, [](config::Scenario& sc) {
        sc.memoryBudgets.mappings = kioskBudget(1 << 20, "/budgets/mappingBytes");
    });
    ASSERT_FALSE(over.ok());
    EXPECT_EQ(over.diagnostics.firstError()->code, "BUDGET_MAPPINGS");
    EXPECT_NE(over.diagnostics.format().find("/budgets/mappingBytes: "), std::string::npos)
        << over.diagnostics.format();
    auto fits = Session::open(kRoute, mCaps);  // the default budget
    ASSERT_TRUE(fits.ok()) << fits.diagnostics.format();
    const MemoryNeeds n = memoryNeeds((*fits)->scenario());
    EXPECT_GT(n.mappingBytes, std::uint64_t(1) << 20);
    EXPECT_EQ((*fits)->memoryUsage().mappingBytes, n.mappingBytes);
}

TEST_F(MemoryBudgets, FontAtlasIsDegradedToFit) {
    // 1200 px high: 30 px text. Its atlas is larger than 96 KiB; the budget gets smaller text.
    auto wide = Session::open(kDemo, mCaps);
    ASSERT_TRUE(wide.ok());
    drawOnce(**wide, 320, 1200);
    const std::uint64_t free = (*wide)->memoryUsage().fontAtlasBytes;
    ASSERT_GT(free, std::uint64_t(96) << 10);
    auto tight = Session::open(kDemo, mCaps, [](config::Scenario& sc) {
        sc.memoryBudgets.fontAtlas = kioskBudget(96 << 10, "/budgets/fontAtlasBytes");
    });
    ASSERT_TRUE(tight.ok());
    drawOnce(**tight, 320, 1200);
    const std::uint64_t held = (*tight)->memoryUsage().fontAtlasBytes;
    EXPECT_GT(held, 0u);  // still text, smaller
    EXPECT_LE(held, std::uint64_t(96) << 10);
    bool reported = false;
    for (const auto& [name, value] : (*tight)->budgets())
        if (name == "font_atlas_bytes") reported = value == double(96 << 10);
    EXPECT_TRUE(reported) << "--stats budgets name the font atlas budget";
}

TEST_F(MemoryBudgets, SqlitePageCacheSettingIsWhatSqliteReports) {
    const fs::path store = "data/generated/rainier.gpkg";
    auto byDefault = io::StoreReader::open(store);
    ASSERT_TRUE(byDefault.ok());
    EXPECT_EQ((*byDefault)->info().pageCacheBytes, io::StoreReader::kDefaultPageCacheBytes);
    io::StoreReader::setPageCacheBytes(64 << 10);
    auto small = io::StoreReader::open(store);
    ASSERT_TRUE(small.ok());
    EXPECT_EQ((*small)->info().pageCacheBytes, 64 << 10);
    io::StoreReader::setPageCacheBytes(8 << 20);
    auto large = io::StoreReader::open(store);
    ASSERT_TRUE(large.ok());
    EXPECT_EQ((*large)->info().pageCacheBytes, 8 << 20);
    EXPECT_EQ(io::StoreReader::openConnections(), 3);
}

}  // namespace
}  // namespace kiosk::app
