// A projective mapping of a layer of the stack (issue 19, docs/projective-mappings.md): each
// mistake is one error naming the JSON pointer of the offending value.
#include "config/ScenarioReader.h"
#include "tests/unit/config/ConfigTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace kiosk::config {
namespace {

std::string scenario(const std::string& mapping) {
    return std::string(R"({"version": 1, "stores": {"s": "s.gpkg"}, "terrain": {"store": "s"},
        "transferFunctions": {"t": {"preset": "viridis"}},
        "layers": [
          {"id": "max", "kind": "maximum", "source": {"store": "s", "sequence": "run"}, "transfer": "t"},
          {"id": "off", "kind": "sequence", "source": {"store": "s", "sequence": "run"}, "transfer": "t", "enabled": false},
          {"id": "hill", "kind": "topographic"}],
        "projectiveMappings": [)") +
           mapping + "]}";
}

const char* const kRect = R"("origin": [0, 0, 0], "u": [10, 0, 0], "v": [0, 10, 0])";

TEST(MappingLayerScenario, ReadsTheLayer) {
    auto r = parseScenario(
        scenario(std::string(R"({"id": "m", "layer": "max", "transfer": "t", )") + kRect + "}"),
        "ok.json");
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    EXPECT_EQ(r.value->projectiveMappings.at(0).layer, "max");
    EXPECT_TRUE(r.value->projectiveMappings.at(0).data.store.empty());
}

TEST(MappingLayerScenario, MistakesNameTheirPointer) {
    struct Case {
        std::string mapping;
        const char* code;
        const char* where;
        const char* message;
    };
    const std::string rect = kRect;
    const Case cases[] = {
        {R"({"id": "m", "layer": "mx", "transfer": "t", )" + rect + "}",
         "SCENARIO_UNKNOWN_REFERENCE", "/projectiveMappings/0/layer", "unknown layer \"mx\""},
        {R"({"id": "m", "layer": "hill", "transfer": "t", )" + rect + "}",
         "SCENARIO_UNKNOWN_REFERENCE", "/projectiveMappings/0/layer", "unknown scalar layer"},
        {R"({"id": "m", "layer": "off", "transfer": "t", )" + rect + "}", "SCENARIO_CONFLICT",
         "/projectiveMappings/0/layer", "is disabled"},
        {R"({"id": "m", "layer": "max", "transfer": "t", "data": {"store": "s", "sequence": "run"}, )" +
             rect + "}",
         "SCENARIO_CONFLICT", "/projectiveMappings/0/layer", "either \"layer\" or \"data\""},
        {R"({"id": "m", "layer": "max", "transfer": "t", "textureMatrix": [1,0,0, 0,1,0, 0,0,1], )" +
             rect + "}",
         "SCENARIO_CONFLICT", "/projectiveMappings/0/textureMatrix", "no \"textureMatrix\""},
        {R"({"id": "m", "layer": "max", "transfer": "t", )" + rect +
             R"(, "keys": [{"time": "2026-03-14T00:00:00Z", "textureMatrix": [1,0,0, 0,1,0, 0,0,1]}]})",
         "SCENARIO_CONFLICT", "/projectiveMappings/0/keys/0/textureMatrix", "no \"textureMatrix\""},
        {R"({"id": "m", "layer": "max", )" + rect + "}", "SCENARIO_MISSING",
         "/projectiveMappings/0", "needs \"transfer\""},
    };
    for (const auto& c : cases) {
        auto r = parseScenario(scenario(c.mapping), "c.json");
        ASSERT_FALSE(r.ok()) << c.where;
        EXPECT_TRUE(test::isOneErrorLine(r.diagnostics, c.code, c.where, c.message));
    }
}

}  // namespace
}  // namespace kiosk::config
