#include "config/MeaningCheck.h"
#include "config/ScenarioReader.h"

#include <gtest/gtest.h>

namespace kiosk::config {
namespace {

io::StoreInfo valleyStore() {
    io::StoreInfo s;
    s.path = "valley.gpkg";
    io::LayerInfo elev;
    elev.name = "elevation";
    elev.kind = io::LayerKind::Elevation;
    elev.units = "m";
    elev.minValue = 10;
    elev.maxValue = 1500;
    io::LayerInfo img;
    img.name = "imagery";
    img.kind = io::LayerKind::Imagery;
    s.layers = {elev, img};
    io::SequenceInfo flood;
    flood.name = "flood_depth";
    flood.units = "m";
    const double t0 = *parseIso8601("2026-03-14T00:00:00Z");
    flood.frameTimes = {t0, t0 + 3600, t0 + 7200};
    flood.frameMin = {0, 0, 0};
    flood.frameMax = {1.2, 4.1, 7.3};
    s.sequences = {flood};
    return s;
}

std::string scenario(const std::string& clockStart, const std::string& clockEnd,
                     const std::string& tfUnits, const std::string& domain,
                     const std::string& imageryLayer, const std::string& sequence,
                     const std::string& elevation = "elevation") {
    return R"({
  "version": 1,
  "stores": { "valley": "valley.gpkg" },
  "terrain": { "store": "valley", "elevation": ")" +
           elevation + R"(" },
  "clock": { "start": ")" +
           clockStart + R"(", "end": ")" + clockEnd + R"(" },
  "transferFunctions": {
    "depth": { "units": ")" +
           tfUnits + R"(", "domain": )" + domain + R"(, "preset": "flood-depth" }
  },
  "layers": [
    { "id": "imagery", "kind": "thematic", "source": { "store": "valley", "layer": ")" +
           imageryLayer + R"(" } },
    { "id": "flood", "kind": "sequence",
      "source": { "store": "valley", "sequence": ")" +
           sequence + R"(" }, "transfer": "depth" }
  ]
})";
}

const char* kStart = "2026-03-14T00:00:00Z";
const char* kEnd = "2026-03-14T02:00:00Z";

Diagnostics check(const std::string& text, const io::StoreInfo* store) {
    auto r = parseScenario(text, "m.json");
    EXPECT_TRUE(r.ok()) << r.diagnostics.format();
    if (!r.ok()) return r.diagnostics;
    return checkMeaning(*r.value, [&](const std::string& id) -> const io::StoreInfo* {
        return id == "valley" ? store : nullptr;
    });
}

TEST(MeaningCheck, ValidScenarioHasOnlyTheDomainWarning) {
    const auto store = valleyStore();
    const Diagnostics d =
        check(scenario(kStart, kEnd, "m", "[0, 5]", "imagery", "flood_depth"), &store);
    EXPECT_FALSE(d.hasErrors()) << d.format();
    ASSERT_EQ(d.size(), 1u) << d.format();
    EXPECT_EQ(d.items()[0].code, "SCENARIO_DOMAIN");
    EXPECT_EQ(d.items()[0].severity, Severity::Warning);
    EXPECT_NE(d.format().find("sequence \"flood_depth\" spans [0, 7.3], beyond the domain [0, 5]"),
              std::string::npos)
        << d.format();
    const Diagnostics wide =
        check(scenario(kStart, kEnd, "m", "[0, 8]", "imagery", "flood_depth"), &store);
    EXPECT_TRUE(wide.empty()) << wide.format();
}

struct Case {
    const char* name;
    std::string text;
    const char* code;
    const char* where;
    int line;
    const char* message;
};

TEST(MeaningCheck, ProblemsNameTheScenarioLocation) {
    const auto store = valleyStore();
    const Case cases[] = {
        {"unknown layer", scenario(kStart, kEnd, "m", "[0, 8]", "imagry", "flood_depth"),
         "SCENARIO_UNKNOWN_LAYER", "/layers/0/source/layer", 10,
         "store \"valley\" has no layer \"imagry\" (it has: elevation, imagery) (did you mean "
         "\"imagery\"?)"},
        {"unknown sequence", scenario(kStart, kEnd, "m", "[0, 8]", "imagery", "flood"),
         "SCENARIO_UNKNOWN_SEQUENCE", "/layers/1/source/sequence", 12, "has no sequence \"flood\""},
        {"units", scenario(kStart, kEnd, "cm", "[0, 800]", "imagery", "flood_depth"),
         "SCENARIO_UNITS", "/layers/1/transfer", 12,
         "transfer function \"depth\" is in \"cm\" but sequence \"flood_depth\" is in \"m\""},
        {"time range",
         scenario("2027-01-01T00:00:00Z", "2027-01-02T00:00:00Z", "m", "[0, 8]", "imagery",
                  "flood_depth"),
         "SCENARIO_TIME_RANGE", "/layers/1/source/sequence", 12,
         "covers 2026-03-14T00:00:00Z .. 2026-03-14T02:00:00Z, which the clock"},
        {"domain disjoint", scenario(kStart, kEnd, "m", "[100, 200]", "imagery", "flood_depth"),
         "SCENARIO_DOMAIN", "/layers/1/transfer", 12, "entirely outside the domain [100, 200]"},
        {"thematic on elevation", scenario(kStart, kEnd, "m", "[0, 8]", "elevation", "flood_depth"),
         "SCENARIO_LAYER_KIND", "/layers/0/source/layer", 10,
         "a thematic layer needs an imagery layer"},
        {"terrain elevation",
         scenario(kStart, kEnd, "m", "[0, 8]", "imagery", "flood_depth", "dem"),
         "SCENARIO_UNKNOWN_LAYER", "/terrain/elevation", 4, "has no layer \"dem\""},
        {"terrain on imagery",
         scenario(kStart, kEnd, "m", "[0, 8]", "imagery", "flood_depth", "imagery"),
         "SCENARIO_LAYER_KIND", "/terrain/elevation", 4, "is not an elevation layer"},
    };
    for (const auto& c : cases) {
        const Diagnostics d = check(c.text, &store);
        ASSERT_TRUE(d.hasErrors()) << c.name << d.format();
        const Diagnostic* e = d.firstError();
        EXPECT_EQ(e->code, c.code) << c.name << ": " << d.format();
        EXPECT_EQ(e->where, c.where) << c.name;
        EXPECT_EQ(e->file, "m.json") << c.name;
        EXPECT_EQ(e->line, c.line) << c.name << ": " << e->format();
        EXPECT_GT(e->column, 0) << c.name;
        EXPECT_NE(e->format().find(c.message), std::string::npos) << c.name << ": " << e->format();
    }
}

TEST(MeaningCheck, PartialTimeOverlapIsAWarning) {
    const auto store = valleyStore();
    const Diagnostics d = check(
        scenario("2026-03-13T23:00:00Z", kEnd, "m", "[0, 8]", "imagery", "flood_depth"), &store);
    EXPECT_FALSE(d.hasErrors()) << d.format();
    EXPECT_TRUE(d.has("SCENARIO_TIME_RANGE"));
}

TEST(MeaningCheck, UnavailableStore) {
    const Diagnostics d =
        check(scenario(kStart, kEnd, "m", "[0, 8]", "imagery", "flood_depth"), nullptr);
    ASSERT_EQ(d.size(), 1u) << d.format();
    EXPECT_EQ(d.items()[0].code, "SCENARIO_STORE_UNAVAILABLE");
    EXPECT_EQ(d.items()[0].where, "/stores/valley");
    EXPECT_EQ(d.items()[0].line, 3);
}

}  // namespace
}  // namespace kiosk::config
