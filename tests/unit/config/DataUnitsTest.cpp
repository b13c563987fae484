// Units between scenario and store: the same units spelled differently are no mismatch, a
// transfer function without units shows the units of the data it colours in its legend (and
// none, with one warning naming the file and JSON pointer, when that data disagrees).
#include "config/DataUnits.h"
#include "config/MeaningCheck.h"
#include "config/ScenarioReader.h"

#include <gtest/gtest.h>

namespace kiosk::config {
namespace {

io::StoreInfo rainStore() {
    io::StoreInfo s;
    s.path = "rain.gpkg";
    io::LayerInfo elev;
    elev.name = "elevation";
    elev.kind = io::LayerKind::Elevation;
    elev.units = "m";
    elev.minValue = 0;
    elev.maxValue = 900;
    s.layers = {elev};
    io::SequenceInfo rain;
    rain.name = "rain";
    rain.units = "mm h-1";
    rain.frameTimes = {0, 3600};
    rain.frameMin = {0, 0};
    rain.frameMax = {20, 30};
    io::SequenceInfo fire = rain;
    fire.name = "fire";
    fire.units = "class";
    s.sequences = {rain, fire};
    return s;
}

// Two layers coloured by transfer functions "a" (units tfUnits, "" = none) and "b" (none).
std::string scenario(const std::string& tfUnits, const std::string& secondData) {
    const std::string units = tfUnits.empty() ? "" : R"("units": ")" + tfUnits + R"(", )";
    return R"({
  "version": 1,
  "stores": { "v": "rain.gpkg" },
  "terrain": { "store": "v", "elevation": "elevation" },
  "transferFunctions": {
    "a": { )" +
           units + R"("stops": [ { "value": 0, "color": "#000000" },
                                     { "value": 1000, "color": "#ffffff" } ] },
    "b": { "stops": [ { "value": 0, "color": "#000000" }, { "value": 3, "color": "#ffffff" } ] }
  },
  "layers": [
    { "id": "rain", "kind": "sequence", "source": { "store": "v", "sequence": "rain" },
      "transfer": "a" },
    { "id": "second", "kind": ")" +
           std::string(secondData == "elevation" ? "data" : "sequence") +
           R"(", "source": { "store": "v", ")" +
           std::string(secondData == "elevation" ? "layer" : "sequence") + R"(": ")" + secondData +
           R"(" }, "transfer": "a" },
    { "id": "fire", "kind": "sequence", "source": { "store": "v", "sequence": "fire" },
      "transfer": "b" }
  ]
})";
}

struct Checked {
    std::unique_ptr<Scenario> scenario;
    Diagnostics diagnostics;
};

Checked checkAndAdopt(const std::string& text, const io::StoreInfo& store) {
    auto r = parseScenario(text, "units.json");
    EXPECT_TRUE(r.ok()) << r.diagnostics.format();
    if (!r.ok()) return {nullptr, r.diagnostics};
    const StoreLookup lookup = [&](const std::string& id) -> const io::StoreInfo* {
        return id == "v" ? &store : nullptr;
    };
    Checked c{std::make_unique<Scenario>(std::move(*r.value)), {}};
    c.diagnostics = checkMeaning(*c.scenario, lookup);
    adoptDataUnits(*c.scenario, lookup);
    return c;
}

TEST(DataUnits, SpellingsOfTheSameUnitsAreNoMismatch) {
    const auto store = rainStore();
    auto c = checkAndAdopt(scenario("mm/h", "rain"), store);
    for (const auto& d : c.diagnostics.items()) EXPECT_NE(d.code, "SCENARIO_UNITS") << d.format();
    EXPECT_EQ(c.scenario->transferFunctions["a"].function.units, "mm/h");  // stated: kept
    auto wrong = checkAndAdopt(scenario("mm", "rain"), store);
    ASSERT_TRUE(wrong.diagnostics.hasErrors());
    EXPECT_EQ(wrong.diagnostics.firstError()->code, "SCENARIO_UNITS");
}

TEST(DataUnits, TransferFunctionWithoutUnitsAdoptsTheStores) {
    const auto store = rainStore();
    auto c = checkAndAdopt(scenario("", "rain"), store);
    EXPECT_FALSE(c.diagnostics.hasErrors()) << c.diagnostics.format();
    for (const auto& d : c.diagnostics.items()) EXPECT_NE(d.code, "SCENARIO_UNITS") << d.format();
    EXPECT_EQ(c.scenario->transferFunctions["a"].function.units, "mm h-1");
    // Categorical data ("class") gives a legend no units.
    EXPECT_EQ(c.scenario->transferFunctions["b"].function.units, "");
}

TEST(DataUnits, DataInDifferentUnitsLeavesTheLegendWithoutAndWarnsOnce) {
    const auto store = rainStore();
    auto c = checkAndAdopt(scenario("", "elevation"), store);
    EXPECT_FALSE(c.diagnostics.hasErrors()) << c.diagnostics.format();
    int warnings = 0;
    for (const auto& d : c.diagnostics.items()) {
        if (d.code != "SCENARIO_UNITS") continue;
        ++warnings;
        EXPECT_EQ(d.severity, Severity::Warning);
        EXPECT_EQ(d.file, "units.json");
        EXPECT_EQ(d.where, "/layers/1/transfer");
        EXPECT_GT(d.line, 0);
        EXPECT_NE(d.message.find("transfer function \"a\" states no units and colours sequence "
                                 "\"rain\" in \"mm h-1\" and layer \"elevation\" in \"m\""),
                  std::string::npos)
            << d.message;
    }
    EXPECT_EQ(warnings, 1) << c.diagnostics.format();
    EXPECT_EQ(c.scenario->transferFunctions["a"].function.units, "");
}

TEST(DataUnits, ProjectiveMappingDataGivesItsTransferFunctionUnits) {
    const auto store = rainStore();
    Scenario sc;
    sc.transferFunctions["t"].function.units = "";
    ProjectiveMapping m;
    m.data.store = "v";
    m.data.layer = "elevation";
    m.transfer = "t";
    sc.projectiveMappings.push_back(m);
    adoptDataUnits(sc, [&](const std::string& id) { return id == "v" ? &store : nullptr; });
    EXPECT_EQ(sc.transferFunctions["t"].function.units, "m");
    // A store that cannot be looked up gives nothing.
    sc.transferFunctions["t"].function.units = "";
    adoptDataUnits(sc, [](const std::string&) { return nullptr; });
    EXPECT_EQ(sc.transferFunctions["t"].function.units, "");
}

}  // namespace
}  // namespace kiosk::config
