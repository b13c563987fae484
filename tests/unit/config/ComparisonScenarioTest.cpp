// Scenario pieces of the comparison lens and the difference layer (issue 19): each mistake is
// one error naming the JSON pointer of the offending value.
#include "config/ScenarioReader.h"
#include "tests/unit/config/ConfigTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace kiosk::config {
namespace {

std::string scenario(const std::string& extraLayer, const std::string& lens) {
    return std::string(R"({"version": 1, "stores": {"a": "a.gpkg", "b": "b.gpkg"},
        "terrain": {"store": "a"},
        "transferFunctions": {"t": {"preset": "viridis"}},
        "layers": [
          {"id": "A", "kind": "sequence", "source": {"store": "a", "sequence": "run"}, "transfer": "t"},
          {"id": "B", "kind": "sequence", "source": {"store": "b", "sequence": "run"}, "transfer": "t"},
          {"id": "hill", "kind": "topographic"})") +
           (extraLayer.empty() ? "" : ", " + extraLayer) + R"(],
        "lenses": [)" +
           lens + "]}";
}

const std::string kGoodLens =
    R"({"id": "c", "kind": "comparison", "center": [0, 0], "radius": 5, "inside": ["B"], "outside": ["A"]})";

TEST(ComparisonScenario, ReadsLensAndDifference) {
    auto r = parseScenario(
        scenario(R"({"id": "d", "kind": "difference", "of": ["A", "B"], "transfer": "t"})",
                 R"({"id": "c", "kind": "comparison", "shape": "swipe", "center": [1, 2],
                     "rotation": 90, "softEdge": 3, "inside": ["B", "d"], "outside": ["A"],
                     "keys": [{"time": "2026-03-14T00:00:00Z", "center": [4, 5]}]})"),
        "ok.json");
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    const Lens& l = r.value->lenses.at(0);
    EXPECT_EQ(l.kind, LensKind::Comparison);
    EXPECT_EQ(l.shape, LensShape::Swipe);
    EXPECT_EQ(l.insideStack, (std::vector<std::string>{"B", "d"}));
    EXPECT_EQ(l.outsideStack, (std::vector<std::string>{"A"}));
    EXPECT_DOUBLE_EQ(l.rotation, 90);
    const Layer& d = r.value->layers.at(3);
    EXPECT_EQ(d.kind, LayerKind::Difference);
    EXPECT_EQ(d.operands, (std::vector<std::string>{"A", "B"}));
}

TEST(ComparisonScenario, MistakesNameTheirPointer) {
    struct Case {
        std::string layer, lens;
        const char* code;
        const char* where;
        const char* message;
    };
    const Case cases[] = {
        {"",
         R"({"id": "c", "kind": "comparison", "center": [0, 0], "radius": 5, "inside": ["Bee"]})",
         "SCENARIO_UNKNOWN_REFERENCE", "/lenses/0/inside/0", "unknown layer \"Bee\""},
        {"", R"({"id": "c", "kind": "comparison", "center": [0, 0], "radius": 5, "inside": ["B"],
                 "outside": ["A", "B"]})",
         "SCENARIO_CONFLICT", "/lenses/0/outside/1", "on both sides"},
        {"", R"({"id": "c", "kind": "comparison", "shape": "swipe", "center": [0, 0], "radius": 5,
                 "inside": ["B"]})",
         "SCENARIO_CONFLICT", "/lenses/0", "a swipe lens is a line"},
        {"", R"({"id": "c", "kind": "comparison", "center": [0, 0], "radius": 5})",
         "SCENARIO_MISSING", "/lenses/0", "needs \"inside\""},
        {"", R"({"id": "c", "kind": "comparison", "center": [0, 0], "radius": 5, "inside": "B"})",
         "SCENARIO_TYPE", "/lenses/0/inside", "expected an array of layer ids"},
        {"", R"({"id": "c", "kind": "comparison", "shape": "swipe", "center": [0, 0],
                 "inside": ["B"], "keys": [{"time": "2026-03-14T00:00:00Z", "radius": 3}]})",
         "SCENARIO_CONFLICT", "/lenses/0/keys/0", "no radius"},
        {R"({"id": "d", "kind": "difference", "of": ["A", "C"], "transfer": "t"})", kGoodLens,
         "SCENARIO_UNKNOWN_REFERENCE", "/layers/3/of/1", "unknown layer \"C\""},
        {R"({"id": "d", "kind": "difference", "of": ["A", "hill"], "transfer": "t"})", kGoodLens,
         "SCENARIO_UNKNOWN_REFERENCE", "/layers/3/of/1", "unknown scalar layer"},
        {R"({"id": "d", "kind": "difference", "of": ["A"], "transfer": "t"})", kGoodLens,
         "SCENARIO_BAD_VALUE", "/layers/3/of", "two layer ids"},
        {R"({"id": "d", "kind": "difference", "of": ["A", "B"]})", kGoodLens, "SCENARIO_MISSING",
         "/layers/3", "needs \"transfer\""},
        {R"({"id": "d", "kind": "difference", "of": ["A", "B"], "transfer": "t",
             "source": {"store": "a", "sequence": "run"}})",
         kGoodLens, "SCENARIO_CONFLICT", "/layers/3/source", "no \"source\""},
        {R"({"id": "d", "kind": "difference", "of": ["A", "d"], "transfer": "t"})", kGoodLens,
         "SCENARIO_BAD_VALUE", "/layers/3/of/1", "cannot subtract itself"},
        {R"({"id": "d", "kind": "data", "source": {"store": "a", "layer": "x"}, "transfer": "t",
             "of": ["A", "B"]})",
         kGoodLens, "SCENARIO_CONFLICT", "/layers/3/of", "difference layers only"},
    };
    for (const auto& c : cases) {
        auto r = parseScenario(scenario(c.layer, c.lens), "c.json");
        ASSERT_FALSE(r.ok()) << c.where;
        EXPECT_TRUE(test::isOneErrorLine(r.diagnostics, c.code, c.where, c.message));
    }
}

}  // namespace
}  // namespace kiosk::config
