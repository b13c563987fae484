// Hostile and careless scenarios (issue 13): limits, the path rule, encodings and messages that
// stay one short line. The same cases run end to end through the CLI in tests/hostile/corpus.py.
#include "config/Limits.h"
#include "config/PathPolicy.h"
#include "config/ScenarioReader.h"
#include "tests/unit/config/ConfigTestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>

namespace kiosk::config {
namespace {

using test::TempDir;

std::string base(const std::string& extra = {}) {
    return R"({"version": 1, "stores": {"s": "s.gpkg"}, "terrain": {"store": "s"},
               "layers": [{"id": "a", "kind": "thematic", "source": {"store": "s", "layer": "i"}}])" +
           extra + "}";
}

const Diagnostic& firstError(const Result<Scenario>& r) {
    EXPECT_FALSE(r.ok());
    static const Diagnostic none{};
    return r.diagnostics.firstError() ? *r.diagnostics.firstError() : none;
}

TEST(HostileInput, IncludeBombStopsAtTheLimitWithThePointer) {
    TempDir dir("bomb");
    // Ten includes per level, five levels: 10^5 loads without the limit.
    for (int level = 0; level < 5; ++level) {
        std::string inc = "[";
        for (int i = 0; i < 10 && level < 4; ++i)
            inc += std::string(i ? "," : "") + "\"b" + std::to_string(level + 1) + ".json\"";
        dir.write("b" + std::to_string(level) + ".json", R"({"include": )" + inc + "]}");
    }
    const auto main = dir.write("main.json", base(R"(, "include": ["b0.json", "b0.json"])"));
    std::vector<std::filesystem::path> files;
    auto r = readScenario(main, &files);
    const Diagnostic& e = firstError(r);
    EXPECT_EQ(e.code, "SCENARIO_LIMIT");
    EXPECT_NE(e.message.find("more than 64 included files"), std::string::npos) << e.format();
    EXPECT_EQ(r.diagnostics.size(), 1u) << r.diagnostics.format();
    EXPECT_LE(files.size(), std::size_t(kMaxIncludeFiles) + 1);
    // Named where it happened: a nested include's /include/N with file:line:col.
    EXPECT_NE(e.format().find(".json:1:"), std::string::npos) << e.format();
    EXPECT_NE(e.where.find("/include/"), std::string::npos);
}

TEST(HostileInput, IncludeDepthLimit) {
    TempDir dir("deep");
    for (int i = 0; i < 12; ++i)
        dir.write("c" + std::to_string(i) + ".json",
                  i < 11 ? R"({"include": ["c)" + std::to_string(i + 1) + R"(.json"]})" : "{}");
    auto r = readScenario(dir.write("main.json", base(R"(, "include": ["c0.json"])")));
    EXPECT_EQ(firstError(r).code, "SCENARIO_LIMIT");
    EXPECT_NE(firstError(r).message.find("nested deeper than 8"), std::string::npos);
    // Eight levels are fine.
    TempDir ok("deep-ok");
    for (int i = 0; i < 7; ++i)
        ok.write("c" + std::to_string(i) + ".json",
                 i < 6 ? R"({"include": ["c)" + std::to_string(i + 1) + R"(.json"]})" : "{}");
    auto fine = readScenario(ok.write("main.json", base(R"(, "include": ["c0.json"])")));
    EXPECT_TRUE(fine.ok()) << fine.diagnostics.format();
}

TEST(HostileInput, CountLimitsNameThePointer) {
    std::string lenses = R"(, "lenses": [)";
    for (int i = 0; i < 17; ++i)
        lenses += std::string(i ? "," : "") + R"({"id": "l)" + std::to_string(i) +
                  R"(", "kind": "highlight", "center": [0, 0], "radius": 1})";
    auto r = parseScenario(base(lenses + "]"), "l.json");
    EXPECT_EQ(firstError(r).code, "SCENARIO_LIMIT");
    EXPECT_EQ(firstError(r).where, "/lenses");
    EXPECT_NE(firstError(r).format().find("l.json:2:"), std::string::npos)
        << firstError(r).format();

    // Six arrival sequences need 1 + 6 * 4 = 25 texture units; the layer count is fine.
    std::string layers = R"({"version": 1, "stores": {"s": "s.gpkg"}, "terrain": {"store": "s"},
        "transferFunctions": {"t": {"preset": "viridis", "domain": [0, 1]}}, "layers": [)";
    for (int i = 0; i < 6; ++i)
        layers += std::string(i ? "," : "") + R"({"id": "q)" + std::to_string(i) +
                  R"(", "kind": "sequence", "transfer": "t", "interpolate": "arrival",
                    "source": {"store": "s", "sequence": "d"}})";
    auto t = parseScenario(layers + "]}", "t.json");
    EXPECT_EQ(firstError(t).code, "SCENARIO_LIMIT");
    EXPECT_NE(firstError(t).message.find("need 25 texture units"), std::string::npos)
        << firstError(t).format();
}

TEST(HostileInput, TextureUnitsCountedLikeTheRenderer) {
    const auto doc = nlohmann::json::parse(R"({"layers": [{"kind": "thematic"}, {"kind": "data"},
        {"kind": "sequence"}, {"kind": "sequence", "interpolate": "arrival"}],
        "projectiveMappings": [{}]})");
    EXPECT_EQ(textureUnitsNeeded(doc), 1 + 1 + 2 + 3 + 4 + 2);
}

TEST(HostileInput, ShippedScenariosAreWithinTheLimits) {
    for (const char* f : {"scenarios/demo/rainier.json", "scenarios/mappings/route.json",
                          "scenarios/mappings/symbols.json", "scenarios/mappings/focus.json"}) {
        auto r = readScenario(f);
        EXPECT_FALSE(r.diagnostics.has("SCENARIO_LIMIT")) << r.diagnostics.format();
        EXPECT_FALSE(r.diagnostics.has("SCENARIO_PATH")) << r.diagnostics.format();
    }
}

TEST(HostileInput, PathsOutsideTheScenarioFolderAreRefused) {
    TempDir dir("paths");
    const auto sub = dir.path() / "a" / "b";
    std::filesystem::create_directories(sub);
    const auto cwd = std::filesystem::current_path();
    std::filesystem::current_path(sub);  // the working directory is an allowed root too
    ::unsetenv("GEOKIOSK_ALLOW_PATHS");
    clearAllowedPaths();
    const auto check = [&](const std::string& extra, const std::string& where) {
        auto r = readScenario(dir.write("a/b/main.json", base(extra)));
        EXPECT_EQ(firstError(r).code, "SCENARIO_PATH") << r.diagnostics.format();
        EXPECT_EQ(firstError(r).where, where);
        EXPECT_EQ(r.diagnostics.format().find("root:"), std::string::npos);
    };
    check(R"(, "include": ["/etc/passwd"])", "/include/0");
    check(R"(, "include": ["../../x.json"])", "/include/0");
    dir.write("x.json", "{}");
    dir.write("a/b/ok.json", "{}");
    check(R"(, "include": ["ok.json", "../../x.json"])", "/include/1");
    check(R"(, "stores": {"s": "/proc/self/environ"})", "/stores/s");
    check(R"(, "transferFunctions": {"t": {"gdal": "../r.clr"}})", "/transferFunctions/t/gdal");
    // A symbolic link inside the folder that points out is followed, and refused.
    std::filesystem::create_symlink("/etc", sub / "etc");
    check(R"(, "include": ["etc/passwd"])", "/include/0");

    // The allow-list widens it: environment and --allow-path (allowPath).
    ::setenv("GEOKIOSK_ALLOW_PATHS", (dir.path().string() + ":/nonexistent").c_str(), 1);
    auto env = readScenario(dir.write("a/b/main.json", base(R"(, "include": ["../../x.json"])")));
    EXPECT_TRUE(env.ok()) << env.diagnostics.format();
    ::unsetenv("GEOKIOSK_ALLOW_PATHS");
    allowPath(dir.path());
    auto cli = readScenario(dir.path() / "a/b/main.json");
    EXPECT_TRUE(cli.ok()) << cli.diagnostics.format();
    clearAllowedPaths();
    std::filesystem::current_path(cwd);
}

TEST(HostileInput, CheckContainedIsComponentWise) {
    EXPECT_FALSE(checkContained("/srv/data/x.gpkg", {"/srv/data"}));
    EXPECT_TRUE(checkContained("/srv/database/x.gpkg", {"/srv/data"}));
    EXPECT_TRUE(checkContained("/srv/data/../x.gpkg", {"/srv/data"}));
}

TEST(HostileInput, Encodings) {
    auto bom = parseScenario("\xEF\xBB\xBF{\"version\": 1, \"stores\": 3}", "bom.json");
    EXPECT_EQ(firstError(bom).code, "SCENARIO_TYPE");
    EXPECT_EQ(firstError(bom).line, 1);
    EXPECT_EQ(firstError(bom).column, 26);  // as an editor counts, without the mark
    const std::string utf16("\xFF\xFE{\0\"\0", 6);
    auto r = parseScenario(utf16, "u.json");
    EXPECT_EQ(firstError(r).code, "SCENARIO_ENCODING");
    EXPECT_NE(firstError(r).hint.find("UTF-8"), std::string::npos);
}

TEST(HostileInput, MessagesStayOneShortLine) {
    auto nl = parseScenario(base(R"(, "camera": {"viewpoint": "x\nmain.json:1:1: ok\u001b[2J"})"),
                            "n.json");
    const std::string text = nl.diagnostics.format();
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
    EXPECT_NE(text.find("x\\nmain.json:1:1: ok\\x1b[2J"), std::string::npos) << text;

    const std::string key(4 << 20, 'k');
    auto big = parseScenario(base(", \"" + key + "\": 1"), "k.json");
    EXPECT_LT(big.diagnostics.format().size(), 2000u);
    EXPECT_NE(big.diagnostics.format().find("\u2026"), std::string::npos);

    auto comment = parseScenario("{ \"version\": 1, /* " + std::string(1 << 20, 'c'), "c.json");
    EXPECT_EQ(firstError(comment).code, "SCENARIO_PARSE");
    EXPECT_LT(comment.diagnostics.format().size(), 400u) << comment.diagnostics.format();
}

TEST(HostileInput, ProblemsInsideAnIncludeNameTheIncludingFile) {
    TempDir dir("inc");
    dir.write("common.json", "{ \"title\": \"x\", }");
    auto r = readScenario(dir.write("main.json", base(R"(,
        "include": ["common.json"])")));
    const Diagnostic& e = firstError(r);
    EXPECT_EQ(e.code, "SCENARIO_PARSE");
    EXPECT_NE(e.file.find("common.json"), std::string::npos);
    EXPECT_NE(e.hint.find("included by "), std::string::npos);
    EXPECT_NE(e.hint.find("main.json:3:21 /include/0"), std::string::npos) << e.format();
}

TEST(HostileInput, CalendarAndOffsets) {
    auto feb = parseScenario(base(R"(, "clock": {"start": "2026-02-30T00:00:00Z",
                                                "end": "2026-03-14T00:00:00Z"})"),
                             "f.json");
    EXPECT_EQ(firstError(feb).code, "SCENARIO_BAD_TIME");
    auto leap = parseScenario(base(R"(, "clock": {"start": "2028-02-29T00:00:00Z",
                                                 "end": "2028-03-14T00:00:00Z"})"),
                              "f.json");
    EXPECT_TRUE(leap.ok()) << leap.diagnostics.format();
    auto digits = parseScenario(base(R"(, "clock": {"start": "2026-03-01T00:00:00Z", "end": "+)" +
                                     std::string(400, '9') + R"(s"})"),
                                "o.json");
    EXPECT_FALSE(digits.ok());
    EXPECT_LT(digits.diagnostics.format().size(), 800u);
}

}  // namespace
}  // namespace kiosk::config
