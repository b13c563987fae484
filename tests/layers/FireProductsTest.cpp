// Fire products (issue 19) on the real Cell2Fire Harvest40x40 burn grids (16 hourly frames):
// the maximum of the burn state is the burned area so far (every cell burned in any frame up to
// k) and the arrival time with a threshold between unburned (0) and burned (1) is the hour a
// cell first burned (class data is not interpolated: the frame's own time). Checked against an
// independent pass over the raw frames, through the loader's product tiles.
#include "layers/Registry.h"
#include "runtime/core/TimeParse.h"
#include "runtime/import/Importer.h"
#include "runtime/io/StoreReader.h"
#include "runtime/loader/DerivedTiles.h"
#include "tests/support/EglTestContext.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace kiosk::layers {
namespace {

namespace fs = std::filesystem;

constexpr double kStart = 1773446400.0;  // 2026-03-14T00:00:00Z

TEST(FireProducts, BurnedAreaSoFarAndArrivalHourFromCell2Fire) {
    const std::string grids = test::sharedData("cell2fire_fire_spread/Harvest40x40/Grids/Grids1");
    const std::string forest = test::sharedData("cell2fire_fire_spread/Harvest40x40/Forest.asc");
    if (grids.empty() || forest.empty())
        GTEST_SKIP() << "../shared/data/cell2fire_fire_spread absent";
    const fs::path dir =
        fs::temp_directory_path() / ("kiosk-fireproducts-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    import::ImportOptions o;
    o.store = dir / "c2f.gpkg";
    o.quiet = true;
    o.name = "elevation";
    ASSERT_FALSE(import::importElevation(forest, o).hasErrors());
    o.name = "burn";
    o.start = kStart;
    ASSERT_FALSE(import::importSequence({grids}, o).hasErrors());
    auto reader = io::StoreReader::open(o.store);
    ASSERT_TRUE(reader.ok()) << reader.diagnostics.format();
    io::StoreReader& r = **reader;
    const io::SequenceInfo* seq = r.info().findSequence("burn");
    ASSERT_NE(seq, nullptr);
    ASSERT_TRUE(seq->categorical);
    ASSERT_GE(seq->frameTimes.size(), 10u);
    const TileId tile{seq->levels - 1, 0, 0};

    config::Layer layer;
    layer.source.sequence = "burn";
    layer.product.threshold = 0.5;
    layer.product.hasThreshold = true;
    layer.product.timeUnits = "h";
    const std::string elevation = "elevation";
    StoreView view{r.info(), elevation};
    view.timeOrigin = kStart;
    SourcePlan maximum, arrival;
    layer.kind = config::LayerKind::Maximum;
    ASSERT_EQ(registry().find("maximum")->plan(layer, view, maximum), "");
    layer.kind = config::LayerKind::Arrival;
    ASSERT_EQ(registry().find("arrival")->plan(layer, view, arrival), "");
    EXPECT_EQ(maximum.interpolation, anim::Interpolation::Categorical);

    std::vector<std::vector<float>> frames;
    for (std::size_t f = 0; f < seq->frameTimes.size(); ++f) {
        auto t = r.readSequenceFrame("burn", int(f), tile);
        ASSERT_TRUE(t.ok()) << t.diagnostics.format();
        frames.push_back(t->values);
    }
    loader::DerivedTiles tiles;
    int burnedAtEnd = 0, grew = 0;
    std::size_t previousBurned = 0;
    for (int k : {3, 8, int(frames.size()) - 1}) {
        io::RasterTile m, a;
        ASSERT_FALSE(tiles.compute(1, *maximum.frames, r, "burn", k, tile, m).hasErrors());
        ASSERT_FALSE(tiles.compute(2, *arrival.frames, r, "burn", k, tile, a).hasErrors());
        std::size_t burned = 0;
        for (std::size_t i = 0; i < frames[0].size(); ++i) {
            // Independent: burned in any frame up to k, and the first such frame's hour.
            bool everBurned = false;
            double firstHour = NAN;
            for (int j = 0; j <= k; ++j)
                if (frames[std::size_t(j)][i] >= 1.0f && !everBurned) {
                    everBurned = true;
                    firstHour = (seq->frameTimes[std::size_t(j)] - kStart) / 3600.0;
                }
            const float* mt = &m.values[i * 4];
            const float* at = &a.values[i * 4];
            const bool productBurned = mt[3] >= 0.5f && mt[0] >= 1.0f;
            ASSERT_EQ(productBurned, everBurned) << "cell " << i << " at frame " << k;
            ASSERT_EQ(at[3] >= 0.5f, everBurned) << "cell " << i << " at frame " << k;
            if (everBurned) {
                ASSERT_NEAR(at[0], firstHour, 1e-4) << "cell " << i;
            }
            burned += everBurned;
        }
        grew += burned > previousBurned;
        previousBurned = burned;
        burnedAtEnd = int(burned);
    }
    EXPECT_EQ(grew, 3) << "the scar did not grow over the frames: the test proves little";
    EXPECT_GT(burnedAtEnd, 50);
    std::error_code ec;
    fs::remove_all(dir, ec);
}

}  // namespace
}  // namespace kiosk::layers
