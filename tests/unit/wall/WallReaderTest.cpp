#include "runtime/wall/WallReader.h"
#include "tests/unit/wall/WallTestFiles.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <set>

namespace kiosk::wall {
namespace {

std::string firstError(const Result<Wall>& r) {
    const Diagnostic* d = r.diagnostics.firstError();
    return d ? d->format() : std::string("(no error)");
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) s.replace(at, from.size(), to);
    return s;
}

TEST(WallReaderTest, ReadsGridPlacementNodesAndSync) {
    auto r = parseWall(
        test::wall2x2(
            R"(, "overlays": {"legend": {"screen": "br"}, "timeLabel": {"canvas": [0.5, 0.1]}})"),
        "wall.json");
    ASSERT_TRUE(r) << r.diagnostics.format();
    const Wall& w = *r;
    EXPECT_EQ(w.rows, 2);
    EXPECT_EQ(w.columns, 2);
    ASSERT_EQ(w.screens.size(), 4u);
    EXPECT_DOUBLE_EQ(w.canvasMmX, 132.0);
    EXPECT_DOUBLE_EQ(w.canvasMmY, 76.0);
    const Screen& br = w.screens[std::size_t(w.findScreen("br"))];
    EXPECT_DOUBLE_EQ(br.xMm, 68.0);
    EXPECT_DOUBLE_EQ(br.yMm, 40.0);
    EXPECT_EQ(br.pixelsX, 64);
    EXPECT_EQ(w.nodes[std::size_t(br.node)].id, "n3");
    EXPECT_EQ(w.leaderScreen(), w.findScreen("tl"));
    EXPECT_EQ(w.sync.stateEndpoint, "ipc:///tmp/kiosk-wall-test-state");
    EXPECT_DOUBLE_EQ(w.sync.deadlineMs, 100.0);
    EXPECT_EQ(w.overlays.legend.screen, w.findScreen("br"));
    ASSERT_TRUE(w.overlays.timeLabel.canvas);
    EXPECT_DOUBLE_EQ((*w.overlays.timeLabel.canvas)[1], 0.1);
    EXPECT_EQ(w.overlays.title.screen, -1);  // not placed: the leader's screen
    EXPECT_FALSE(w.overlays.title.canvas);
}

TEST(WallReaderTest, OverlappingScreensAreNamed) {
    // Two screens in one grid cell.
    auto r = parseWall(replaced(test::wall2x2(), R"("id": "tr", "row": 0, "column": 1)",
                                R"("id": "tr", "row": 0, "column": 0)"),
                       "wall.json");
    ASSERT_FALSE(r);
    EXPECT_TRUE(r.diagnostics.has("WALL_OVERLAP"));
    EXPECT_NE(firstError(r).find("wall.json:6:"), std::string::npos) << firstError(r);
    EXPECT_NE(firstError(r).find("/screens/1"), std::string::npos) << firstError(r);
    EXPECT_NE(firstError(r).find(R"(screens "tl" and "tr" overlap)"), std::string::npos)
        << firstError(r);
    // Explicit positions that collide.
    r = parseWall(replaced(test::wall2x2(), R"("id": "br", "row": 1, "column": 1})",
                           R"("id": "br", "row": 1, "column": 1, "positionMm": [30, 20]})"),
                  "wall.json");
    ASSERT_FALSE(r);
    EXPECT_TRUE(r.diagnostics.has("WALL_OVERLAP")) << r.diagnostics.format();
    EXPECT_NE(firstError(r).find("overlap by 34 x 16 mm"), std::string::npos) << firstError(r);
}

TEST(WallReaderTest, ZeroBezelIsRefused) {
    auto r = parseWall(
        replaced(test::wall2x2(), R"("mullionMm": [4, 4])", R"("mullionMm": [4, 0])"), "w.json");
    ASSERT_FALSE(r);
    EXPECT_TRUE(r.diagnostics.has("WALL_BEZEL"));
    EXPECT_EQ(firstError(r),
              "w.json:4:20: /mullionMm/1: mullion (bezel gap) between rows must be > 0 and <= 1000 "
              "mm, got 0 "
              "[WALL_BEZEL]");
}

TEST(WallReaderTest, UnknownScreenIdSuggestsTheNearest) {
    auto r = parseWall(
        replaced(test::wall2x2(), R"("screens": ["bl", "br"])", R"("screens": ["bl", "brr"])"),
        "w.json");
    ASSERT_FALSE(r);
    EXPECT_TRUE(r.diagnostics.has("WALL_UNKNOWN_SCREEN"));
    EXPECT_NE(
        firstError(r).find(R"(/nodes/2/screens/1: unknown screen id "brr" (did you mean "br"?))"),
        std::string::npos)
        << firstError(r);
    // The screen left without a node is reported too.
    EXPECT_TRUE(r.diagnostics.has("WALL_UNDRIVEN"));
    r = parseWall(test::wall2x2(R"(, "overlays": {"legend": {"screen": "xx"}})"), "w.json");
    ASSERT_FALSE(r);
    EXPECT_NE(firstError(r).find("/overlays/legend/screen: unknown screen id"), std::string::npos)
        << firstError(r);
}

TEST(WallReaderTest, OtherMistakes) {
    struct Case {
        std::string from, to, code;
    };
    const Case cases[] = {
        {R"("leader": "n1")", R"("leader": "n9")", "WALL_UNKNOWN_NODE"},
        {R"("row": 1, "column": 1})", R"("row": 2, "column": 1})", "WALL_RANGE"},
        {R"("ipc:///tmp/kiosk-wall-test-ready")", R"("udp://x")", "WALL_ENDPOINT"},
        {R"("grid")", R"("gird")", "WALL_UNKNOWN_PROPERTY"},
        {R"({"id": "n2", "screens": ["tr"]})", R"({"id": "n1", "screens": ["tr"]})",
         "WALL_DUPLICATE_ID"},
        {R"("pixels": [64, 36])", R"("pixels": [64, 0])", "WALL_RANGE"},
    };
    for (const auto& c : cases) {
        auto r = parseWall(replaced(test::wall2x2(), c.from, c.to), "w.json");
        ASSERT_FALSE(r) << c.to;
        EXPECT_TRUE(r.diagnostics.has(c.code)) << c.to << ": " << r.diagnostics.format();
    }
    auto r = parseWall("{", "w.json");
    EXPECT_FALSE(r);
    auto missing = readWall("/nonexistent/wall.json");
    ASSERT_FALSE(missing);
    EXPECT_TRUE(missing.diagnostics.has("WALL_FILE"));
}

}  // namespace
}  // namespace kiosk::wall

namespace kiosk::wall {
namespace {

// The schema (editor completion and validation) and the reader accept the same properties.
TEST(WallSchemaTest, SchemaMatchesTheReader) {
    std::ifstream in("config/schema/wall.schema.json");
    ASSERT_TRUE(in) << "run from the source root";
    const nlohmann::json schema = nlohmann::json::parse(in, nullptr, false, false);
    ASSERT_FALSE(schema.is_discarded());
    auto keys = [](const nlohmann::json& props) {
        std::set<std::string> out;
        for (auto it = props.begin(); it != props.end(); ++it) out.insert(it.key());
        return out;
    };
    for (const auto& [kind, accepted] : acceptedWallProperties()) {
        const nlohmann::json& node = kind == "Wall" ? schema : schema["$defs"][kind];
        ASSERT_TRUE(node.contains("properties")) << kind;
        EXPECT_EQ(keys(node["properties"]), std::set<std::string>(accepted.begin(), accepted.end()))
            << kind;
        EXPECT_EQ(node.value("additionalProperties", true), false) << kind;
    }
    EXPECT_EQ(schema["$defs"].size() + 1, acceptedWallProperties().size());
}

}  // namespace
}  // namespace kiosk::wall
