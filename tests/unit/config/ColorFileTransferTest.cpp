// A transfer function may name any supported colour-map file as "file": PATH; the format comes
// from the extension and content, and a broken file gives one error with its line.
#include "config/ScenarioReader.h"
#include "tests/unit/config/ConfigTestSupport.h"

#include <gtest/gtest.h>

namespace kiosk::config {
namespace {

std::string scenarioWith(const std::string& transfer) {
    return R"({"version": 1, "stores": {"v": "v.gpkg"}, "terrain": {"store": "v"},
               "layers": [{"id": "d", "kind": "data", "source": {"store": "v", "layer": "e"},
                           "transfer": "t"}],
               "transferFunctions": {"t": )" +
           transfer + "}}";
}

TEST(ColorFileTransfer, CptFloatListAndRulesByFile) {
    test::TempDir dir("colorfile");
    dir.write("relief.cpt", "0 0/0/255 100 255/0/0\nB black\nF white\nN 128\n");
    std::string rgb;
    for (int i = 0; i < 16; ++i) rgb += std::to_string(i / 15.0) + " 0.5 0.25\n";
    dir.write("thermal-rgb.txt", rgb);
    dir.write("depth.rules", "0 blue\n10 0:255:0\ndefault 64:64:64\n");

    auto cpt = readScenario(dir.write("a.json", scenarioWith(R"({"file": "relief.cpt"})")));
    ASSERT_TRUE(cpt.ok()) << cpt.diagnostics.format();
    const auto* t = cpt->findTransfer("t");
    EXPECT_EQ(t->origin, TransferFunctionDef::Origin::File);
    EXPECT_EQ(t->function.domainMax, 100.0);
    EXPECT_EQ(t->function.below.r, 0.0f);  // B black, not the first colour (blue)
    EXPECT_EQ(t->function.below.b, 0.0f);
    EXPECT_EQ(t->function.above.g, 1.0f);    // F white
    EXPECT_EQ(cpt->sourceFiles.size(), 2u);  // the scenario and relief.cpt (hot reload)

    auto list = readScenario(
        dir.write("b.json", scenarioWith(R"({"file": "thermal-rgb.txt", "domain": [0, 5]})")));
    ASSERT_TRUE(list.ok()) << list.diagnostics.format();
    EXPECT_EQ(list->findTransfer("t")->function.stops.size(), 16u);
    EXPECT_EQ(list->findTransfer("t")->function.stops.back().value, 5.0);  // 0..1 rescaled

    auto rules = readScenario(dir.write("c.json", scenarioWith(R"({"file": "depth.rules"})")));
    ASSERT_TRUE(rules.ok()) << rules.diagnostics.format();
    EXPECT_NEAR(rules->findTransfer("t")->function.above.r, 64.0 / 255.0, 1e-6);
}

TEST(ColorFileTransfer, BrokenFileGivesOneErrorWithLineAndPointer) {
    test::TempDir dir("colorfile-bad");
    std::string rgb;
    for (int i = 0; i < 256; ++i) rgb += i == 9 ? "0.1 0.2 two\n" : "0.1 0.2 0.3\n";
    dir.write("bad-rgb.txt", rgb);
    auto r = readScenario(dir.write("a.json", scenarioWith(R"({"file": "bad-rgb.txt"})")));
    ASSERT_FALSE(r.ok());
    std::size_t errors = 0;
    for (const auto& d : r.diagnostics.items()) errors += d.severity == Severity::Error;
    EXPECT_EQ(errors, 1u) << r.diagnostics.format();
    const auto* e = r.diagnostics.firstError();
    EXPECT_EQ(e->code, "COLOR_RGB_SYNTAX");
    EXPECT_EQ(e->where, "/transferFunctions/t/file");
    EXPECT_NE(e->message.find("line 10: bad-rgb.txt"), std::string::npos) << e->message;
    auto both = readScenario(
        dir.write("b.json", scenarioWith(R"({"file": "bad-rgb.txt", "preset": "viridis"})")));
    ASSERT_FALSE(both.ok());
    EXPECT_EQ(both.diagnostics.firstError()->code, "SCENARIO_CONFLICT");
}

}  // namespace
}  // namespace kiosk::config
