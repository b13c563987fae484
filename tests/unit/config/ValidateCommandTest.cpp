// geokiosk validate end to end, in process. The store layer is replaced at link time by the fake
// io::StoreReader::open below (this test does not link kiosk_io), so the command is tested
// without SQLite and independently of the store module's progress.
#include "runtime/app/ValidateCommand.h"
#include "runtime/io/StoreIntegrity.h"
#include "runtime/io/StoreReader.h"
#include "tests/unit/config/ConfigTestSupport.h"

#include <gtest/gtest.h>

#include <sstream>

namespace kiosk::io {

namespace {
class FakeStore : public StoreReader {
public:
    explicit FakeStore(StoreInfo info) : mInfo(std::move(info)) {}
    const StoreInfo& info() const noexcept override { return mInfo; }
    Result<RasterTile> readElevation(const std::string&, const TileId&) override { return {}; }
    Result<ImageTile> readImagery(const std::string&, const TileId&) override { return {}; }
    Result<RasterTile> readSequenceFrame(const std::string&, int, const TileId&) override {
        return {};
    }
    std::optional<TileStats> tileStats(const std::string&, const TileId&) override {
        return std::nullopt;
    }

private:
    StoreInfo mInfo;
};
}  // namespace

// A store "exists" when its file name is valley.gpkg; it has elevation and imagery layers.
Result<std::unique_ptr<StoreReader>> StoreReader::open(const std::filesystem::path& path) {
    if (path.filename() != "valley.gpkg") {
        Diagnostics d;
        d.error("STORE_OPEN", path.string(), "", "cannot open store (no such file)");
        return d;
    }
    StoreInfo info;
    info.path = path.string();
    LayerInfo elevation;
    elevation.name = "elevation";
    elevation.units = "m";
    LayerInfo imagery;
    imagery.name = "imagery";
    imagery.kind = LayerKind::Imagery;
    info.layers = {elevation, imagery};
    return std::unique_ptr<StoreReader>(new FakeStore(std::move(info)));
}

// The fake stores have no tables to check.
// Integrity checks are tested against real stores in tests/unit/io and tests/hostile.
Diagnostics checkStoreIntegrity(const std::filesystem::path&, IntegrityLevel) {
    return {};
}

}  // namespace kiosk::io

namespace kiosk::app {
namespace {

struct Outcome {
    int status;
    std::string out, err;
};

Outcome run(const std::vector<std::string>& args) {
    std::ostringstream out, err;
    const int status = runValidateCommand(args, out, err);
    return {status, out.str(), err.str()};
}

TEST(ValidateCommand, ValidScenarioExitsZero) {
    const Outcome r = run({"tests/unit/config/data/minimal.json"});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out,
              "tests/unit/config/data/minimal.json: ok (1 layers, 0 transfer functions, 1 files, "
              "1 stores checked)\n");
    EXPECT_EQ(r.err, "");
}

TEST(ValidateCommand, StoreProblemsExitOne) {
    test::TempDir dir("validate");
    const auto bad = dir.write("s.json", R"({
  "version": 1,
  "stores": { "valley": "valley.gpkg", "other": "missing.gpkg" },
  "terrain": { "store": "valley" },
  "layers": [{ "id": "i", "kind": "thematic", "source": { "store": "valley", "layer": "imagry" } }]
})");
    const Outcome r = run({bad.string()});
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.out, "");
    // One line for the store: the scenario's file:line:col and pointer, then the store's reason.
    EXPECT_NE(r.err.find("s.json:3:49: /stores/other: store \""), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("missing.gpkg\": cannot open store (no such file) [STORE_OPEN]"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(r.err.find("SCENARIO_STORE_UNAVAILABLE"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("s.json:5:87: /layers/0/source/layer: store \"valley\" has no layer "
                         "\"imagry\" (it has: elevation, imagery) (did you mean \"imagery\"?) "
                         "[SCENARIO_UNKNOWN_LAYER]"),
              std::string::npos)
        << r.err;
    // --no-stores: the same file is fine as far as the scenario itself goes.
    const Outcome skip = run({"--no-stores", bad.string()});
    EXPECT_EQ(skip.status, 0) << skip.err;
    EXPECT_NE(skip.out.find("stores not checked"), std::string::npos);
}

TEST(ValidateCommand, AnyInvalidScenarioExitsOneAndAllAreChecked) {
    const Outcome r = run({"--quiet", "scenarios/broken/unknown-transfer.json",
                           "tests/unit/config/data/minimal.json", "scenarios/broken/empty.json"});
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.out, "");  // --quiet
    EXPECT_NE(r.err.find("scenarios/broken/unknown-transfer.json:15:19: /layers/1/transfer: "
                         "unknown transfer function \"depht\" (did you mean \"depth\"?)"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("scenarios/broken/empty.json:1:1:"), std::string::npos) << r.err;
}

TEST(ValidateCommand, UsageErrorsExitTwo) {
    EXPECT_EQ(run({}).status, 2);
    const Outcome typo = run({"--no-store", "x.json"});
    EXPECT_EQ(typo.status, 2);
    EXPECT_NE(typo.err.find("unknown option '--no-store' (did you mean '--no-stores'?)"),
              std::string::npos)
        << typo.err;
    EXPECT_EQ(run({"--quiet"}).status, 2);
    const Outcome help = run({"--help"});
    EXPECT_EQ(help.status, 0);
    EXPECT_NE(help.out.find("usage: geokiosk validate"), std::string::npos);
}

TEST(ValidateCommand, EveryBrokenScenarioExitsOne) {
    for (const auto& e : std::filesystem::directory_iterator("scenarios/broken")) {
        if (e.path().extension() != ".json") continue;
        const Outcome r = run({"--no-stores", e.path().string()});
        EXPECT_EQ(r.status, 1) << e.path();
        EXPECT_FALSE(r.err.empty()) << e.path();
    }
}

}  // namespace
}  // namespace kiosk::app
