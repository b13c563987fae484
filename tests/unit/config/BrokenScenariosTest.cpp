// scenarios/broken/: every file must be reported precisely (code, line:col, message) and never
// crash; expected.tsv holds the table, and no broken file may be missing from it.
#include "config/ScenarioReader.h"
#include "tests/unit/config/ConfigTestSupport.h"

#include <gtest/gtest.h>

#include <set>
#include <sstream>

namespace kiosk::config {
namespace {

struct Expected {
    std::string file, code, lineCol, message;
};

std::vector<Expected> loadTable() {
    std::vector<Expected> rows;
    std::istringstream in(test::slurp("scenarios/broken/expected.tsv"));
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> cols;
        std::size_t start = 0;
        for (std::size_t tab; (tab = line.find('\t', start)) != std::string::npos; start = tab + 1)
            cols.push_back(line.substr(start, tab - start));
        cols.push_back(line.substr(start));
        EXPECT_EQ(cols.size(), 4u) << line;
        if (cols.size() == 4) rows.push_back({cols[0], cols[1], cols[2], cols[3]});
    }
    return rows;
}

TEST(BrokenScenarios, EveryFileIsListed) {
    const auto rows = loadTable();
    std::set<std::string> listed;
    for (const auto& r : rows) listed.insert(r.file);
    std::size_t files = 0;
    for (const auto& e : std::filesystem::directory_iterator("scenarios/broken")) {
        if (e.path().extension() != ".json") continue;
        ++files;
        EXPECT_TRUE(listed.count(e.path().filename().string()))
            << e.path() << " has no row in scenarios/broken/expected.tsv";
    }
    EXPECT_GE(files, 10u);
    EXPECT_EQ(files, rows.size());
}

TEST(BrokenScenarios, EachGivesItsExpectedDiagnostic) {
    for (const auto& row : loadTable()) {
        const std::string path = "scenarios/broken/" + row.file;
        auto r = readScenario(path);
        ASSERT_FALSE(r.ok()) << path << " was accepted";
        const Diagnostic* e = r.diagnostics.firstError();
        ASSERT_NE(e, nullptr) << path;
        EXPECT_EQ(e->code, row.code) << path << ": " << r.diagnostics.format();
        EXPECT_EQ(std::to_string(e->line) + ":" + std::to_string(e->column), row.lineCol)
            << path << ": " << e->format();
        const std::string text = e->format();
        EXPECT_NE(text.find(row.message), std::string::npos) << path << ": " << text;
        EXPECT_EQ(text.rfind("scenarios/broken/", 0), 0u) << text;
        // One precise error per defect: no cascades of follow-on noise.
        std::size_t errors = 0;
        for (const auto& d : r.diagnostics.items()) errors += d.severity == Severity::Error;
        EXPECT_EQ(errors, 1u) << path << ":\n" << r.diagnostics.format();
    }
}

}  // namespace
}  // namespace kiosk::config
