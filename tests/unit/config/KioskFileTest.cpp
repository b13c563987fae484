// Kiosk files: the reader's messages (file:line:col: /pointer), defaults, and the JSON Schema in
// config/schema/kiosk.schema.json kept identical to the reader's property table.
#include "config/KioskFile.h"
#include "tests/unit/config/ConfigTestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <set>

namespace kiosk::config {
namespace {

class KioskFileTest : public ::testing::Test {
protected:
    std::filesystem::path write(const std::string& text) {
        const auto dir = std::filesystem::path(testing::TempDir()) / "kiosk-file-test";
        std::filesystem::create_directories(dir);
        const auto p = dir / "kiosk.json";
        std::ofstream(p) << text;
        return p;
    }
};

TEST_F(KioskFileTest, ReadsEntriesWithDefaults) {
    const auto p = write(R"({
  // comments are fine, as in scenarios
  "playlist": [
    { "scenario": "a.json", "duration": "1h30m" },
    { "scenario": "/abs/b.json", "loops": 2, "window": { "from": "22:00", "to": "06:00" } },
    { "scenario": "c.json" }
  ],
  "transition": { "kind": "fade" },
  "listen": "127.0.0.1:9100",
  "tokenFile": "token",
  "budgets": { "cacheBytes": 67108864 }
})");
    auto k = readKioskFile(p);
    ASSERT_TRUE(k) << k.diagnostics.format();
    ASSERT_EQ(k->playlist.size(), 3u);
    EXPECT_EQ(k->playlist[0].scenario, p.parent_path() / "a.json");
    EXPECT_DOUBLE_EQ(*k->playlist[0].durationSeconds, 5400.0);
    EXPECT_FALSE(k->playlist[0].loops);
    EXPECT_EQ(k->playlist[1].scenario, "/abs/b.json");
    EXPECT_EQ(*k->playlist[1].loops, 2);
    ASSERT_TRUE(k->playlist[1].window);
    EXPECT_EQ(k->playlist[1].window->fromSeconds, 22 * 3600);
    EXPECT_EQ(k->playlist[1].window->toSeconds, 6 * 3600);
    EXPECT_EQ(*k->playlist[2].loops, 1);  // neither duration nor loops: one pass
    EXPECT_EQ(k->transition, TransitionKind::Fade);
    EXPECT_DOUBLE_EQ(k->transitionSeconds, 1.0);
    EXPECT_EQ(*k->listen, "127.0.0.1:9100");
    EXPECT_EQ(*k->tokenFile, p.parent_path() / "token");
    EXPECT_EQ(*k->cacheBytes, 67108864);
    EXPECT_FALSE(k->gpuBytes);
}

TEST_F(KioskFileTest, ErrorsNameFileLineColumnAndPointer) {
    const auto p = write(R"({
  "playlist": [
    { "scenario": "a.json" },
    { "scenario": "b.json", "duraton": 10 },
    { "scenario": "c.json", "window": { "from": "25:00", "to": "06:00" } },
    { "scenario": "d.json", "duration": 5, "loops": 2 }
  ],
  "transition": { "kind": "wipe" }
})");
    auto k = readKioskFile(p);
    ASSERT_FALSE(k);
    const std::string text = k.diagnostics.format();
    const std::string f = p.string();
    EXPECT_NE(text.find(f + ":4:29: /playlist/1/duraton: unknown property \"duraton\""),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("did you mean \"duration\"?"), std::string::npos) << text;
    EXPECT_NE(text.find(f + ":5:49: /playlist/2/window/from: expected a local time"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("/playlist/3/loops: give \"duration\" or \"loops\", not both"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find(f + ":8:27: /transition/kind: expected \"cut\" or \"fade\""),
              std::string::npos)
        << text;
    EXPECT_TRUE(k.diagnostics.has("KIOSK_UNKNOWN_PROPERTY"));
}

TEST_F(KioskFileTest, MemoryBudgetsKeepWhereTheyWereSet) {
    const auto p = write(R"({
  "playlist": [ { "scenario": "a.json" } ],
  "budgets": { "lutBytes": 16384, "mappingBytes": 8388608,
               "fontAtlasBytes": 65536, "sqlitePageCacheBytes": 131072 }
})");
    auto k = readKioskFile(p);
    ASSERT_TRUE(k) << k.diagnostics.format();
    const MemoryBudgets& m = k->memory;
    EXPECT_EQ(m.luts.bytes, 16384);
    EXPECT_EQ(m.luts.file, p.string());
    EXPECT_EQ(m.luts.line, 3);
    EXPECT_EQ(m.luts.column, 28);
    EXPECT_EQ(m.luts.pointer, "/budgets/lutBytes");
    EXPECT_EQ(m.mappings.bytes, 8388608);
    EXPECT_EQ(m.fontAtlas.bytes, 65536);
    EXPECT_EQ(m.fontAtlas.line, 4);
    EXPECT_EQ(m.sqlitePageCache.bytes, 131072);
    EXPECT_EQ(m.sqlitePageCache.pointer, "/budgets/sqlitePageCacheBytes");

    auto unset = readKioskFile(write(R"({ "playlist": [ { "scenario": "a.json" } ] })"));
    ASSERT_TRUE(unset);
    EXPECT_FALSE(unset->memory.luts.set());
    EXPECT_FALSE(unset->memory.sqlitePageCache.set());

    auto small = readKioskFile(write(R"({ "playlist": [ { "scenario": "a.json" } ],
  "budgets": { "lutBytes": 100, "sqlitePageCacheBytes": 1.5 } })"));
    ASSERT_FALSE(small);
    const std::string text = small.diagnostics.format();
    EXPECT_NE(text.find(":2:28: /budgets/lutBytes: expected a whole number of bytes from 4096"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("/budgets/sqlitePageCacheBytes: expected a whole number of bytes from "
                        "65536 to 1 TiB"),
              std::string::npos)
        << text;
}

TEST_F(KioskFileTest, ParseErrorsAndMissingPlaylist) {
    auto bad = readKioskFile(write("{ \"playlist\": [ }"));
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.diagnostics.format().find("kiosk.json:1:"), std::string::npos)
        << bad.diagnostics.format();
    auto empty = readKioskFile(write(R"({ "playlist": [] })"));
    ASSERT_FALSE(empty);
    EXPECT_NE(empty.diagnostics.format().find("/playlist: expected a non-empty array"),
              std::string::npos);
    auto missing = readKioskFile("/nonexistent/kiosk.json");
    ASSERT_FALSE(missing);
    EXPECT_TRUE(missing.diagnostics.has("KIOSK_FILE"));
}

TEST_F(KioskFileTest, KioskFilesAreToldFromScenarios) {
    EXPECT_TRUE(isKioskFile(write(R"({ "playlist": [ { "scenario": "a.json" } ] })")));
    EXPECT_FALSE(isKioskFile(write(R"({ "version": 1, "layers": [] })")));
    EXPECT_FALSE(isKioskFile(write("not json")));
    EXPECT_FALSE(isKioskFile("/nonexistent/kiosk.json"));
}

TEST(KioskTimeOfDay, Parse) {
    EXPECT_EQ(parseTimeOfDay("00:00"), 0);
    EXPECT_EQ(parseTimeOfDay("06:30"), 6 * 3600 + 30 * 60);
    EXPECT_EQ(parseTimeOfDay("23:59:59"), 86399);
    EXPECT_EQ(parseTimeOfDay("24:00"), 86400);
    EXPECT_FALSE(parseTimeOfDay("24:01"));
    EXPECT_FALSE(parseTimeOfDay("6:30"));
    EXPECT_FALSE(parseTimeOfDay("06:60"));
    EXPECT_FALSE(parseTimeOfDay("06"));
    EXPECT_FALSE(parseTimeOfDay("06:30:00:00"));
}

TEST(KioskSchema, PropertiesMatchTheReaderBothWays) {
    using nlohmann::json;
    const json schema =
        json::parse(test::slurp("config/schema/kiosk.schema.json"), nullptr, false, false);
    ASSERT_TRUE(schema.is_object()) << "config/schema/kiosk.schema.json is not valid JSON";
    EXPECT_EQ(schema.value("$schema", ""), "https://json-schema.org/draft/2020-12/schema");
    const auto& table = kioskProperties();
    auto keys = [](const json& props) {
        std::set<std::string> out;
        for (auto it = props.begin(); it != props.end(); ++it) out.insert(it.key());
        return out;
    };
    for (const auto& [kind, props] : table) {
        const json& obj = kind == "Kiosk" ? schema : schema["$defs"][kind];
        ASSERT_TRUE(obj.is_object()) << kind << " missing from the schema's $defs";
        EXPECT_EQ(obj.value("additionalProperties", true), false) << kind;
        EXPECT_EQ(keys(obj["properties"]), std::set<std::string>(props.begin(), props.end()))
            << kind;
    }
    EXPECT_EQ(schema["$defs"].size(), table.size() - 1);
}

}  // namespace
}  // namespace kiosk::config
