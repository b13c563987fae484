// geokiosk validate end to end, in process. The store layer is replaced at link time by the fake
// io::StoreReader::open below (this test does not link kiosk_io), so the command is tested
// without SQLite and independently of the store module's progress.
#include "runtime/app/ValidateCommand.h"
#include "runtime/io/StoreIntegrity.h"
#include "runtime/io/StoreReader.h"
#include "tests/unit/config/ConfigTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
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

// flood.gpkg: a depth sequence and what the product kinds' mistakes need beside it.
std::unique_ptr<StoreReader> floodStore(const std::filesystem::path& path) {
    StoreInfo info;
    info.path = path.string();
    LayerInfo elevation;
    elevation.name = "elevation";
    elevation.units = "m";
    info.layers = {elevation};
    auto sequence = [](const char* name, const char* units, int frames) {
        SequenceInfo s;
        s.name = name;
        s.units = units;
        for (int k = 0; k < frames; ++k) {
            s.frameTimes.push_back(1.7e9 + 60.0 * k);
            s.frameMin.push_back(0);
            s.frameMax.push_back(3);
        }
        return s;
    };
    info.sequences = {sequence("flood", "m", 4), sequence("speed", "m/s", 4),
                      sequence("speed_kmh", "km/h", 4), sequence("speed_short", "m/s", 3),
                      sequence("stage_cm", "cm", 4)};
    return std::unique_ptr<StoreReader>(new FakeStore(std::move(info)));
}

// A store "exists" when its file name is valley.gpkg (elevation and imagery layers) or
// flood.gpkg (above).
Result<std::unique_ptr<StoreReader>> StoreReader::open(const std::filesystem::path& path) {
    if (path.filename() == "flood.gpkg") return floodStore(path);
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

// The product kinds' mistakes (docs/products.md): each is exactly one line on stderr naming its
// JSON pointer and code, and validate exits 1; a hazard layer without velocity (the stated
// depth-only fallback) is valid.
TEST(ValidateCommand, EachProductMistakeIsOneLineWithItsPointer) {
    test::TempDir dir("validate-products");
    auto scenario = [&](const std::string& name, const std::string& layer) {
        return dir
            .write(name, R"({
  "version": 1,
  "stores": { "s": "flood.gpkg" },
  "terrain": { "store": "s" },
  "transferFunctions": {
    "depth": { "units": "m", "stops": [ { "value": 0, "color": "#000000" }, { "value": 3, "color": "#ffffff" } ] },
    "hours": { "units": "h", "stops": [ { "value": 0, "color": "#000000" }, { "value": 2, "color": "#ffffff" } ] },
    "classes": { "classes": [ { "from": 1, "color": "#ffff00", "label": "H1" }, { "from": 6, "color": "#ff0000", "label": "H6" } ] }
  },
  "layers": [
    )" + layer + R"(
  ]
})")
            .string();
    };
    struct Case {
        const char* layer;
        const char* code;
        const char* where;    ///< file:line:col: pointer
        const char* message;  ///< a substring of the line
    };
    const Case cases[] = {
        // A product of something that is not a sequence.
        {R"({ "id": "m", "kind": "maximum", "source": { "store": "s", "layer": "elevation" }, "transfer": "depth" })",
         "SCENARIO_MISSING", ":11:47: /layers/0/source:", "a maximum layer needs \"sequence\""},
        // "product" on a kind that is not a product.
        {R"({ "id": "q", "kind": "sequence", "source": { "store": "s", "sequence": "flood" }, "transfer": "depth", "product": { "threshold": 1 } })",
         "SCENARIO_CONFLICT", ":11:119: /layers/0/product:", "not to a sequence layer"},
        // An option of another product kind.
        {R"({ "id": "m", "kind": "maximum", "source": { "store": "s", "sequence": "flood" }, "transfer": "depth", "product": { "threshold": 1 } })",
         "SCENARIO_CONFLICT", ":11:133: /layers/0/product/threshold:",
         "\"threshold\" applies to arrival and duration layers only"},
        {R"({ "id": "a", "kind": "arrival", "source": { "store": "s", "sequence": "flood" }, "transfer": "hours", "product": { "threshold": 1, "velocity": "speed" } })",
         "SCENARIO_CONFLICT",
         ":11:148: /layers/0/product/velocity:", "\"velocity\" applies to hazard layers only"},
        {R"({ "id": "d", "kind": "duration", "source": { "store": "s", "sequence": "flood" }, "transfer": "hours", "product": { "threshold": 1, "isochrones": 1 } })",
         "SCENARIO_CONFLICT",
         ":11:151: /layers/0/product/isochrones:", "\"isochrones\" applies to arrival layers only"},
        // Arrival and duration need a threshold.
        {R"({ "id": "d", "kind": "duration", "source": { "store": "s", "sequence": "flood" }, "transfer": "hours" })",
         "SCENARIO_MISSING", ":11:5: /layers/0:", "a duration layer needs \"product\""},
        {R"({ "id": "a", "kind": "arrival", "source": { "store": "s", "sequence": "flood" }, "transfer": "hours", "product": { "units": "m" } })",
         "SCENARIO_MISSING",
         ":11:118: /layers/0/product:", "missing required property \"threshold\""},
        // The threshold in other units than the sequence's.
        {R"({ "id": "a", "kind": "arrival", "source": { "store": "s", "sequence": "flood" }, "transfer": "hours", "product": { "threshold": 1, "units": "cm" } })",
         "SCENARIO_UNITS", ":11:145: /layers/0/product/units:",
         "threshold stated in \"cm\" but sequence \"flood\" is in \"m\""},
        // Hazard: velocity absent, with other frames, not in m/s; depth not in metres.
        {R"({ "id": "h", "kind": "hazard", "source": { "store": "s", "sequence": "flood" }, "transfer": "classes", "product": { "velocity": "sped" } })",
         "SCENARIO_UNKNOWN_SEQUENCE",
         ":11:133: /layers/0/product/velocity:", "store \"s\" has no sequence \"sped\""},
        {R"({ "id": "h", "kind": "hazard", "source": { "store": "s", "sequence": "flood" }, "transfer": "classes", "product": { "velocity": "speed_short" } })",
         "SCENARIO_TIME_RANGE", ":11:133: /layers/0/product/velocity:",
         "velocity sequence \"speed_short\" does not have the frames of \"flood\" (3 and 4 "
         "frames)"},
        {R"({ "id": "h", "kind": "hazard", "source": { "store": "s", "sequence": "flood" }, "transfer": "classes", "product": { "velocity": "speed_kmh" } })",
         "SCENARIO_UNITS", ":11:133: /layers/0/product/velocity:",
         "velocity sequence \"speed_kmh\" is in \"km/h\"; the hazard curves need m/s"},
        {R"({ "id": "h", "kind": "hazard", "source": { "store": "s", "sequence": "stage_cm" }, "transfer": "classes", "product": { "velocity": "speed" } })",
         "SCENARIO_UNITS", ":11:74: /layers/0/source/sequence:",
         "hazard classes need depth in metres; sequence \"stage_cm\" is in \"cm\""},
    };
    int n = 0;
    for (const Case& c : cases) {
        const std::string file = scenario("p" + std::to_string(n++) + ".json", c.layer);
        const Outcome r = run({file});
        EXPECT_EQ(r.status, 1) << c.layer << "\n" << r.err;
        EXPECT_EQ(r.out, "") << c.layer;
        // Exactly one line, and it is the mistake: file:line:col: pointer: message [CODE].
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.layer << "\n" << r.err;
        EXPECT_EQ(r.err.rfind(file + c.where, 0), 0u) << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(std::string("[") + c.code + "]\n"), std::string::npos) << r.err;
    }
    // Depth only: no velocity is the stated fallback, not a mistake.
    const Outcome fallback = run(
        {"--quiet",
         scenario(
             "fallback.json",
             R"({ "id": "h", "kind": "hazard", "source": { "store": "s", "sequence": "flood" }, "transfer": "classes" })")});
    EXPECT_EQ(fallback.status, 0) << fallback.err;
    EXPECT_EQ(fallback.err, "");
    // Every option where it belongs: valid.
    const Outcome good = run(
        {"--quiet",
         scenario(
             "good.json",
             R"({ "id": "a", "kind": "arrival", "source": { "store": "s", "sequence": "flood" }, "transfer": "hours", "product": { "threshold": 0.5, "units": "m", "timeUnits": "h", "isochrones": 1 } },
    { "id": "h", "kind": "hazard", "source": { "store": "s", "sequence": "flood" }, "transfer": "classes", "product": { "velocity": "speed" } })")});
    EXPECT_EQ(good.status, 0) << good.err;
    EXPECT_EQ(good.err, "");
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
