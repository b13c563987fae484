// Numbers that reach the GPU as 32-bit floats are range-checked when read (docs/scenario-format.md,
// "Ranges"): each value beyond its bound is refused at its own pointer, the bound itself passes.
#include "config/ScenarioReader.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace kiosk::config {
namespace {

std::string scenario(const std::string& extra) {
    return R"({"version": 1, "stores": {"s": "s.gpkg"}, "terrain": {"store": "s"},
               "layers": [{"id": "a", "kind": "thematic", "source": {"store": "s", "layer": "i"}}])" +
           extra + "}";
}

std::string lens(const std::string& members) {
    return R"(, "lenses": [{"id": "l", "kind": "highlight", )" + members + "}]";
}

std::string mapping(const std::string& members) {
    return R"(, "projectiveMappings": [{"id": "m", "data": {"store": "s", "layer": "i"}, )" +
           members + "}]";
}

struct Case {
    const char* what;
    std::string extra;
    const char* pointer;
};

TEST(RangeChecks, ValuesBeyondAGpuFloatAreRefusedAtTheirPointer) {
    const std::string uv = R"("u": [1000, 0, 0], "v": [0, 1000, 0])";
    const std::vector<Case> cases = {
        {"lens radius", lens(R"("center": [0, 0], "radius": 1e39)"), "/lenses/0/radius"},
        {"lens radii", lens(R"("center": [0, 0], "radii": [10, 1e39])"), "/lenses/0/radii/1"},
        {"lens centre", lens(R"("center": [0, -1e39], "radius": 10)"), "/lenses/0/center/1"},
        {"lens soft edge", lens(R"("center": [0, 0], "radius": 10, "softEdge": 2e8)"),
         "/lenses/0/softEdge"},
        {"lens key radius",
         R"(, "clock": {"start": "2026-03-14T00:00:00Z", "end": "2026-03-15T00:00:00Z"})" +
             lens(R"("center": [0, 0], "radius": 10, "keys": [{"time": "+1h", "radius": 1e30}])"),
         "/lenses/0/keys/0/radius"},
        {"mapping origin", mapping(R"("origin": [0, 0, 1e39], )" + uv),
         "/projectiveMappings/0/origin/2"},
        {"mapping u", mapping(R"("origin": [0, 0, 0], "u": [3e38, 0, 0], "v": [0, 1, 0])"),
         "/projectiveMappings/0/u/0"},
        {"texture matrix",
         mapping(R"("origin": [0, 0, 0], )" + uv +
                 R"(, "textureMatrix": [1, 0, 0, 0, 1e7, 0, 0, 0, 1])"),
         "/projectiveMappings/0/textureMatrix/4"},
        {"route point",
         R"(, "projectiveMappings": [{"id": "m", "route": {"points": [[0, 0], [1e39, 0]]}}])",
         "/projectiveMappings/0/route/points/1/0"},
        {"viewpoint range", R"(, "viewpoints": {"v": {"target": [0, 0, 0], "range": 1e39}})",
         "/viewpoints/v/range"},
        {"viewpoint target", R"(, "viewpoints": {"v": {"target": [0, 0, 1e39]}})",
         "/viewpoints/v/target/2"},
        {"transfer domain",
         R"(, "transferFunctions": {"t": {"domain": [0, 1e31], "stops": [{"value": 0, "color": "red"}, {"value": 1, "color": "blue"}]}})",
         "/transferFunctions/t/domain/1"},
        {"stop value",
         R"(, "transferFunctions": {"t": {"stops": [{"value": 0, "color": "red"}, {"value": 1e39, "color": "blue"}]}})",
         "/transferFunctions/t/stops/1/value"},
    };
    for (const Case& c : cases) {
        auto r = parseScenario(scenario(c.extra), "range.json");
        ASSERT_FALSE(r.ok()) << c.what << " was accepted";
        const Diagnostic* e = r.diagnostics.firstError();
        EXPECT_EQ(e->code, "SCENARIO_RANGE") << c.what << ": " << r.diagnostics.format();
        EXPECT_EQ(e->where, c.pointer) << c.what << ": " << e->format();
        EXPECT_EQ(e->format().find('\n'), std::string::npos) << c.what;
    }
}

TEST(RangeChecks, TheBoundsThemselvesPass) {
    auto r = parseScenario(
        scenario(lens(R"("center": [-1e8, 1e8], "radius": 1e8, "softEdge": 1e8)") +
                 R"(, "viewpoints": {"v": {"target": [1e8, -1e8, 0], "range": 1e8}})"),
        "bounds.json");
    EXPECT_TRUE(r.ok()) << r.diagnostics.format();
}

}  // namespace
}  // namespace kiosk::config
