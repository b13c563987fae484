// The scenario's "briefing" section (config/BriefingReader.cpp): read into typed chapters, and
// every mistake reported at its JSON pointer in the reader's usual style.
#include "config/ScenarioReader.h"

#include <gtest/gtest.h>

namespace kiosk::config {
namespace {

std::string scenario(const std::string& briefing) {
    return R"({"version": 1, "stores": {"v": "v.gpkg"}, "terrain": {"store": "v"},
      "layers": [{"id": "a", "kind": "thematic", "source": {"store": "v", "layer": "imagery"}},
                 {"id": "off", "kind": "thematic", "source": {"store": "v", "layer": "imagery"},
                  "enabled": false}],
      "clock": {"start": "2026-03-14T00:00:00Z", "end": "2026-03-14T09:00:00Z", "rate": 1200},
      "viewpoints": {"overview": {"target": [0, 0, 0]}, "summit": {"target": [1, 1, 1]}},
      "cameraPaths": {"tour": {"keys": [{"time": "+0s", "viewpoint": "overview"}]}},
      "briefing": )" +
           briefing + "}";
}

TEST(BriefingReader, ReadsChapters) {
    auto r = parseScenario(scenario(R"({"chapters": [
        {"title": "One", "from": "+0s", "to": "+4h", "path": "tour", "duration": 8,
         "caption": "first\nsecond"},
        {"title": "Two", "time": "2026-03-14T09:00:00Z", "viewpoint": "summit", "pause": true,
         "layers": {"a": {"enabled": false, "opacity": 0.5}}}]})"),
                           "b.json");
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    ASSERT_TRUE(r->briefing);
    const auto& c = r->briefing->chapters;
    ASSERT_EQ(c.size(), 2u);
    EXPECT_EQ(c[0].title, "One");
    EXPECT_TRUE(c[0].span);
    EXPECT_TRUE(c[0].from.isOffset);
    EXPECT_DOUBLE_EQ(c[0].to.seconds, 4 * 3600);
    EXPECT_EQ(c[0].path, "tour");
    EXPECT_DOUBLE_EQ(c[0].duration.value_or(0), 8);
    EXPECT_EQ(c[0].caption, "first\nsecond");
    EXPECT_FALSE(c[0].pause);
    EXPECT_FALSE(c[1].span);
    EXPECT_DOUBLE_EQ(c[1].from.seconds, c[1].to.seconds);
    EXPECT_EQ(c[1].viewpoint, "summit");
    EXPECT_TRUE(c[1].pause);
    ASSERT_EQ(c[1].layers.size(), 1u);
    EXPECT_EQ(c[1].layers[0].layer, "a");
    EXPECT_EQ(c[1].layers[0].enabled, std::optional<bool>(false));
    EXPECT_DOUBLE_EQ(c[1].layers[0].opacity.value_or(-1), 0.5);
    EXPECT_EQ(c[1].pointer, "/briefing/chapters/1");
}

struct Bad {
    const char* name;
    const char* briefing;
    const char* code;
    const char* pointer;
    const char* text;
};

TEST(BriefingReader, ReportsMistakesAtTheirPointer) {
    const Bad cases[] = {
        {"no chapters", R"({})", "SCENARIO_MISSING", "/briefing", "\"chapters\""},
        {"empty", R"({"chapters": []})", "SCENARIO_TYPE", "/briefing/chapters", "non-empty"},
        {"unknown member", R"({"chapters": [{"title": "x", "time": "+0s", "captoin": "y"}]})",
         "SCENARIO_UNKNOWN_PROPERTY", "/briefing/chapters/0/captoin", "did you mean \"caption\""},
        {"no title", R"({"chapters": [{"time": "+0s"}]})", "SCENARIO_MISSING",
         "/briefing/chapters/0", "\"title\""},
        {"no time", R"({"chapters": [{"title": "x"}]})", "SCENARIO_MISSING", "/briefing/chapters/0",
         "\"time\" or \"from\" and \"to\""},
        {"time and span",
         R"({"chapters": [{"title": "x", "time": "+0s", "from": "+0s", "to": "+1h"}]})",
         "SCENARIO_CONFLICT", "/briefing/chapters/0", "not both"},
        {"backwards", R"({"chapters": [{"title": "x", "from": "+2h", "to": "+1h"}]})",
         "SCENARIO_RANGE", "/briefing/chapters/0/to", "before"},
        {"bad time", R"({"chapters": [{"title": "x", "time": "noon"}]})", "SCENARIO_BAD_TIME",
         "/briefing/chapters/0/time", "ISO 8601"},
        {"unknown viewpoint",
         R"({"chapters": [{"title": "x", "time": "+0s", "viewpoint": "sumit"}]})",
         "SCENARIO_UNKNOWN_REFERENCE", "/briefing/chapters/0/viewpoint", "did you mean \"summit\""},
        {"unknown path", R"({"chapters": [{"title": "x", "time": "+0s", "path": "toor"}]})",
         "SCENARIO_UNKNOWN_REFERENCE", "/briefing/chapters/0/path", "did you mean \"tour\""},
        {"viewpoint and path",
         R"({"chapters": [{"title": "x", "time": "+0s", "viewpoint": "summit", "path": "tour"}]})",
         "SCENARIO_CONFLICT", "/briefing/chapters/0", "not both"},
        {"unknown layer", R"({"chapters": [{"title": "x", "time": "+0s", "layers": {"b": {}}}]})",
         "SCENARIO_UNKNOWN_REFERENCE", "/briefing/chapters/0/layers/b", "unknown layer"},
        {"disabled layer",
         R"({"chapters": [{"title": "x", "time": "+0s", "layers": {"off": {"opacity": 1}}}]})",
         "SCENARIO_CONFLICT", "/briefing/chapters/0/layers/off", "disabled in /layers/1"},
        {"opacity range",
         R"({"chapters": [{"title": "x", "time": "+0s", "layers": {"a": {"opacity": 2}}}]})",
         "SCENARIO_RANGE", "/briefing/chapters/0/layers/a/opacity", "opacity"},
        {"duration", R"({"chapters": [{"title": "x", "time": "+0s", "duration": 0}]})",
         "SCENARIO_RANGE", "/briefing/chapters/0/duration", "duration"},
        {"pause type", R"({"chapters": [{"title": "x", "time": "+0s", "pause": "yes"}]})",
         "SCENARIO_TYPE", "/briefing/chapters/0/pause", "boolean"},
        {"caption lines",
         R"({"chapters": [{"title": "x", "time": "+0s", "caption": "1\n2\n3\n4\n5\n6\n7\n8\n9\n10\n11\n12\n13"}]})",
         "SCENARIO_RANGE", "/briefing/chapters/0/caption", "12 lines"},
    };
    for (const Bad& c : cases) {
        auto r = parseScenario(scenario(c.briefing), "b.json");
        EXPECT_FALSE(r.ok()) << c.name;
        const Diagnostic* e = r.diagnostics.firstError();
        ASSERT_NE(e, nullptr) << c.name;
        EXPECT_EQ(e->code, c.code) << c.name << ": " << e->format();
        EXPECT_EQ(e->where, c.pointer) << c.name << ": " << e->format();
        EXPECT_NE(e->format().find(c.text), std::string::npos) << c.name << ": " << e->format();
        EXPECT_GT(e->line, 0) << c.name;
    }
}

}  // namespace
}  // namespace kiosk::config
