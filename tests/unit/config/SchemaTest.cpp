// The JSON Schema (for editors) and the C++ reader (the authority) must not drift: same object
// kinds, same properties; and the schema must be complete enough for VS Code completion (every
// property described, unknown properties rejected).
#include "config/KindSection.h"
#include "config/ScenarioReader.h"
#include "tests/unit/config/ConfigTestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <set>

namespace kiosk::config {
namespace {

using nlohmann::json;

json loadSchema() {
    // Strict JSON: editors do not all accept comments in schema files.
    return json::parse(test::slurp("config/schema/scenario.schema.json"), nullptr, false, false);
}

std::set<std::string> keysOf(const json& j) {
    std::set<std::string> out;
    for (auto it = j.begin(); it != j.end(); ++it) out.insert(it.key());
    return out;
}

TEST(ScenarioSchema, IsValidDraft202012Json) {
    const json schema = loadSchema();
    ASSERT_FALSE(schema.is_discarded()) << "config/schema/scenario.schema.json is not valid JSON";
    ASSERT_TRUE(schema.is_object());
    EXPECT_EQ(schema.value("$schema", ""), "https://json-schema.org/draft/2020-12/schema");
    EXPECT_EQ(schema["properties"]["version"]["const"], 1);
    EXPECT_TRUE(schema.contains("$defs"));
}

TEST(ScenarioSchema, PropertiesMatchTheReaderBothWays) {
    const json schema = loadSchema();
    ASSERT_TRUE(schema.is_object());
    const auto& table = acceptedProperties();
    std::set<std::string> kinds;
    for (const auto& [kind, keys] : table) {
        kinds.insert(kind);
        const json* def = kind == "Scenario"               ? &schema
                          : schema["$defs"].contains(kind) ? &schema["$defs"][kind]
                                                           : nullptr;
        ASSERT_NE(def, nullptr) << "schema has no $defs/" << kind;
        ASSERT_TRUE(def->contains("properties")) << kind;
        const std::set<std::string> inSchema = keysOf((*def)["properties"]);
        const std::set<std::string> inReader(keys.begin(), keys.end());
        for (const auto& k : inReader)
            EXPECT_TRUE(inSchema.count(k)) << kind << "." << k << " is read but not in the schema";
        for (const auto& k : inSchema)
            EXPECT_TRUE(inReader.count(k)) << kind << "." << k << " is in the schema but not read";
    }
    for (auto it = schema["$defs"].begin(); it != schema["$defs"].end(); ++it)
        EXPECT_TRUE(kinds.count(it.key())) << "$defs/" << it.key() << " is not a reader kind";
}

// Walk every subschema: objects with properties forbid others, every property is described.
void checkNode(const json& node, const std::string& path, int& properties) {
    if (node.is_array()) {
        for (std::size_t i = 0; i < node.size(); ++i)
            checkNode(node[i], path + "/" + std::to_string(i), properties);
        return;
    }
    if (!node.is_object()) return;
    if (node.contains("properties")) {
        EXPECT_EQ(node.value("additionalProperties", json(true)), json(false))
            << path << " must set additionalProperties: false";
        for (auto it = node["properties"].begin(); it != node["properties"].end(); ++it) {
            ++properties;
            const json& p = it.value();
            EXPECT_TRUE(p.contains("description") && p["description"].is_string() &&
                        !p["description"].get<std::string>().empty())
                << path << "/properties/" << it.key() << " has no description";
        }
    }
    for (auto it = node.begin(); it != node.end(); ++it) {
        // Conditions (if/then/else, not, allOf) constrain properties declared beside them;
        // they declare none of their own, so the "closed and described" rule is not theirs.
        static const std::set<std::string> conditions = {"if", "then", "else", "not", "allOf"};
        if (conditions.count(it.key())) continue;
        checkNode(it.value(), path + "/" + it.key(), properties);
    }
}

TEST(ScenarioSchema, EveryPropertyDescribedAndClosed) {
    const json schema = loadSchema();
    ASSERT_TRUE(schema.is_object());
    int properties = 0;
    checkNode(schema, "", properties);
    EXPECT_GT(properties, 120);
}

// The layer kinds the schema lists are those whose scenario sections config registers
// (config/KindSections.cpp), in the same order; composing the schema with the registered kinds'
// fragments adds nothing to the built-in ones.
TEST(ScenarioSchema, LayerKindsAreTheKindsWithASection) {
    const json schema = loadSchema();
    ASSERT_TRUE(schema.is_object());
    std::vector<std::string> listed;
    for (const auto& k : schema["$defs"]["Layer"]["properties"]["kind"]["enum"])
        listed.push_back(k.get<std::string>());
    EXPECT_EQ(listed, kindSections().names());
    EXPECT_EQ(json::parse(scenarioSchema(test::slurp("config/schema/scenario.schema.json"))),
              schema);
}

// Enumerations in the schema are accepted by the reader (a value from the schema's enum put in
// a scenario parses without SCENARIO_BAD_VALUE).
TEST(ScenarioSchema, EnumValuesAreAcceptedByTheReader) {
    const json schema = loadSchema();
    ASSERT_TRUE(schema.is_object());
    const json& layerKinds = schema["$defs"]["Layer"]["properties"]["kind"]["enum"];
    ASSERT_EQ(layerKinds.size(), 12u);
    for (const auto& kind : layerKinds) {
        const std::string k = kind.get<std::string>();
        // Sequences and the products derived from one read a sequence; arrival and duration
        // need their threshold.
        const bool seq = k == "sequence" || k == "maximum" || k == "arrival" || k == "duration" ||
                         k == "hazard";
        const std::string source =
            std::string(seq ? R"({"store": "v", "sequence": "s"})"
                            : R"({"store": "v", "layer": "x"})") +
            (k == "arrival" || k == "duration" ? R"(, "product": {"threshold": 0.1})" : "");
        // A difference has no source: it subtracts two scalar layers of the stack.
        const std::string layer =
            k == "difference"
                ? R"({"id": "p", "kind": "data", "source": {"store": "v", "layer": "x"},
                      "transfer": "t"}, {"id": "a", "kind": "difference", "of": ["p", "p"],
                      "transfer": "t"})"
                : R"({"id": "a", "kind": ")" + k + R"(", "source": )" + source +
                      R"(, "transfer": "t"})";
        const std::string text =
            R"({"version": 1, "stores": {"v": "v.gpkg"}, "terrain": {"store": "v"},
                "transferFunctions": {"t": {"preset": "viridis"}},
                "layers": [)" +
            layer + "]}";
        auto r = parseScenario(text, "e.json");
        EXPECT_TRUE(r.ok()) << k << r.diagnostics.format();
    }
    for (const auto& preset : schema["$defs"]["TransferFunction"]["properties"]["preset"]["enum"]) {
        const std::string text =
            R"({"version": 1, "stores": {"v": "v.gpkg"}, "terrain": {"store": "v"}, "layers": [],
                "transferFunctions": {"t": {"preset": ")" +
            preset.get<std::string>() + R"("}}})";
        auto r = parseScenario(text, "p.json");
        EXPECT_TRUE(r.ok()) << preset << r.diagnostics.format();
    }
}

}  // namespace
}  // namespace kiosk::config
