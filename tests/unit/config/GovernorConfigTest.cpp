// Issue 12's scenario settings: `terrain.reference` and the `governor` object.
#include "config/ScenarioReader.h"

#include <gtest/gtest.h>

#include <string>

namespace kiosk::config {
namespace {

Result<Scenario> parse(const std::string& terrainExtra, const std::string& members) {
    return parseScenario(
        "{\"version\": 1, \"stores\": {\"v\": \"v.gpkg\"}, \"terrain\": {\"store\": \"v\"" +
            terrainExtra + "}, \"layers\": []" + members + "}",
        "t.json");
}

TEST(GovernorConfig, DefaultsAreOffAndLod) {
    auto r = parse("", "");
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    EXPECT_EQ(r.value->terrain.reference, TerrainReference::Lod);
    EXPECT_EQ(r.value->governor.targetFps, 0.0);
    EXPECT_EQ(r.value->governor.maxTauFactor, 4.0);
    EXPECT_EQ(r.value->governor.minRenderScale, 0.5);
}

TEST(GovernorConfig, ReadsReferenceAndGovernor) {
    auto r =
        parse(", \"reference\": \"full\"",
              ", \"governor\": {\"targetFps\": 30, \"maxTauFactor\": 2, \"minRenderScale\": 0.7}");
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    EXPECT_EQ(r.value->terrain.reference, TerrainReference::Full);
    EXPECT_EQ(r.value->governor.targetFps, 30.0);
    EXPECT_EQ(r.value->governor.maxTauFactor, 2.0);
    EXPECT_EQ(r.value->governor.minRenderScale, 0.7);
}

TEST(GovernorConfig, BadValuesNameTheirPointer) {
    const struct {
        const char* terrain;
        const char* members;
        const char* where;
    } cases[] = {
        {", \"reference\": \"exact\"", "", "/terrain/reference"},
        {"", ", \"governor\": {\"targetFps\": -1}", "/governor/targetFps"},
        {"", ", \"governor\": {\"maxTauFactor\": 0.5}", "/governor/maxTauFactor"},
        {"", ", \"governor\": {\"minRenderScale\": 0.1}", "/governor/minRenderScale"},
        {"", ", \"governor\": {\"targetFPS\": 30}", "/governor/targetFPS"},
    };
    for (const auto& c : cases) {
        auto r = parse(c.terrain, c.members);
        ASSERT_FALSE(r.ok()) << c.where;
        const Diagnostic* e = r.diagnostics.firstError();
        ASSERT_NE(e, nullptr) << c.where;
        EXPECT_EQ(e->where, c.where) << e->format();
    }
}

}  // namespace
}  // namespace kiosk::config
