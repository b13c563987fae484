// Deterministic robustness test of the scenario reader: thousands of mutated scenarios (byte
// flips, JSON-token insertions, deletions, duplications, truncations) must each give either a
// scenario or diagnostics -- never a crash, a hang or an exception. The libFuzzer target in
// tests/fuzz/ explores further when clang is available; this one runs everywhere, in ~1 s.
#include "config/ScenarioReader.h"
#include "tests/unit/config/ConfigTestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <random>

namespace kiosk::config {
namespace {

const char* const kTokens[] = {
    "{",
    "}",
    "[",
    "]",
    "\"",
    ",",
    ":",
    "null",
    "true",
    "1e999",
    "-0",
    "1e-400",
    "\"\\u0000\"",
    "\"\\ud800\"",
    "//",
    "/*",
    "*/",
    "\"include\": \"flood.json\"",
    "\"include\": [\"/dev/zero\"]",
    "\"$schema\"",
    "\"version\": 1",
    "[[[[[[[[",
    "]]]]",
    "\"stops\": []",
    "\"domain\": [1, 1]",
    "\"classes\": [{\"from\": 1e308, \"color\": \"red\"}]",
    "\"preset\": \"viridis\"",
    "\"time\": \"+1h\"",
    "\"time\": \"2026-02-31T25:61:00Z\"",
    "\"radius\": -1",
    "\xff\xfe",
    "\"cacheBytes\": \"99999999999 GiB\"",
    "\"gdal\": \"colormaps\"",
    "\"rate\": 1e308",
};

std::string mutate(std::string s, std::mt19937& rng) {
    auto pick = [&](std::size_t n) {
        return std::uniform_int_distribution<std::size_t>(0, n)(rng);
    };
    const int edits = 1 + int(pick(3));
    for (int e = 0; e < edits; ++e) {
        const std::size_t pos = s.empty() ? 0 : pick(s.size() - 1);
        switch (pick(5)) {
            case 0:  // flip a byte to anything
                if (!s.empty()) s[pos] = char(pick(255));
                break;
            case 1: {  // insert a JSON-ish token
                const std::size_t n = sizeof kTokens / sizeof *kTokens;
                s.insert(std::min(pos, s.size()), kTokens[pick(n - 1)]);
                break;
            }
            case 2:  // delete a range
                if (!s.empty()) s.erase(pos, pick(std::min<std::size_t>(40, s.size() - pos)));
                break;
            case 3: {  // duplicate a range elsewhere
                if (s.empty()) break;
                const std::string piece = s.substr(pos, pick(60));
                s.insert(pick(s.size()), piece);
                break;
            }
            case 4:  // truncate
                s.resize(pos);
                break;
            default: {  // swap two bytes
                if (s.size() < 2) break;
                std::swap(s[pos], s[pick(s.size() - 1)]);
                break;
            }
        }
    }
    return s;
}

// Structure-aware mutation: valid JSON whose values, keys and arrays are disturbed, so that the
// typed reader (not only the JSON parser) sees thousands of odd documents.
std::string mutateStructure(const std::string& seed, std::mt19937& rng) {
    using nlohmann::json;
    json doc = json::parse(seed, nullptr, false, true);
    if (doc.is_discarded() || !doc.is_object()) return seed;
    auto pick = [&](std::size_t n) {
        return std::uniform_int_distribution<std::size_t>(0, n)(rng);
    };
    const json replacements[] = {json(nullptr),
                                 json(true),
                                 json(-1),
                                 json(0),
                                 json(1e308),
                                 json(0.5),
                                 json("x"),
                                 json(""),
                                 json("#ff0000"),
                                 json("+1h"),
                                 json("2026-03-14T00:00:00Z"),
                                 json::array(),
                                 json::object(),
                                 json::array({1, 2}),
                                 json::array({0, 0, 0}),
                                 json("viridis"),
                                 json("valley"),
                                 json("depth")};
    const int edits = 1 + int(pick(2));
    for (int e = 0; e < edits; ++e) {
        // Walk down to a random node.
        json* node = &doc;
        for (int depth = 0; depth < 6; ++depth) {
            if (!(node->is_object() || node->is_array()) || node->empty() || pick(3) == 0) break;
            auto it = node->begin();
            std::advance(it, long(pick(node->size() - 1)));
            node = &*it;
        }
        switch (pick(4)) {
            case 0:  // replace the value
                *node = replacements[pick(sizeof replacements / sizeof *replacements - 1)];
                break;
            case 1:  // drop a member or element
                if (node->is_object() && !node->empty()) {
                    auto it = node->begin();
                    std::advance(it, long(pick(node->size() - 1)));
                    node->erase(it);
                } else if (node->is_array() && !node->empty()) {
                    node->erase(pick(node->size() - 1));
                }
                break;
            case 2:  // rename a key (a typo)
                if (node->is_object() && !node->empty()) {
                    auto it = node->begin();
                    std::advance(it, long(pick(node->size() - 1)));
                    std::string key = it.key();
                    json value = it.value();
                    node->erase(it);
                    if (!key.empty()) key[pick(key.size() - 1)] = char('a' + pick(25));
                    (*node)[key] = value;
                }
                break;
            case 3:  // duplicate an array element (duplicate ids, unsorted stops...)
                if (node->is_array() && !node->empty())
                    node->push_back((*node)[pick(node->size() - 1)]);
                break;
            default:  // leave it: exercise the accept path
                break;
        }
    }
    return doc.dump(pick(1) ? 2 : -1);
}

TEST(ScenarioMutation, ThousandsOfMutantsNeverCrash) {
    std::vector<std::string> seeds;
    for (const char* f : {"minimal.json", "flood.json", "common.json"})
        seeds.push_back(test::slurp(test::configData(f)));
    for (const auto& e : std::filesystem::directory_iterator("scenarios/broken"))
        if (e.path().extension() == ".json") seeds.push_back(test::slurp(e.path()));
    ASSERT_GE(seeds.size(), 13u);

    std::mt19937 rng(20260314);
    // Named inside the fixture directory so that mutated includes and colour files resolve to
    // real files and the include/import paths get exercised too.
    const auto name = test::configData("mutant.json");
    int accepted = 0, rejected = 0;
    for (int i = 0; i < 6000; ++i) {
        const std::string& seed = seeds[std::size_t(i) % seeds.size()];
        const std::string text = i % 2 ? mutate(seed, rng) : mutateStructure(seed, rng);
        Result<Scenario> r;
        ASSERT_NO_THROW(r = parseScenario(text, name)) << "mutant " << i;
        ASSERT_EQ(r.ok(), !r.diagnostics.hasErrors()) << "mutant " << i;
        for (const auto& d : r.diagnostics.items()) {
            ASSERT_FALSE(d.code.empty()) << d.format();
            ASSERT_FALSE(d.file.empty()) << d.format();
            ASSERT_TRUE(d.line == 0 || d.column > 0) << d.format();
            ASSERT_FALSE(d.message.empty());
        }
        (r.ok() ? accepted : rejected)++;
    }
    // Both paths exercised: mutants that still parse, and many that do not.
    EXPECT_GT(accepted, 100);  // most seeds are the broken scenarios; 126 with this seed
    EXPECT_GT(rejected, 3000);
}

}  // namespace
}  // namespace kiosk::config
