// The kinds a scenario layer may name, each with its own reader (config/KindSection.h): the
// built-in kinds here, one line each; a kind registered at run time through layers::Registry.
#include "config/KindSection.h"
#include "layers/SourcedSection.h"

#include <algorithm>

namespace kiosk::config {

void KindSections::add(std::string name, std::shared_ptr<const KindSection> section) {
    if (!mSections.count(name)) mNames.push_back(name);
    mSections[std::move(name)] = std::move(section);
}

const KindSection* KindSections::find(std::string_view name) const {
    auto it = mSections.find(name);
    return it == mSections.end() ? nullptr : it->second.get();
}

KindSections& kindSections() {
    using reader::sourcedSection;
    using reader::SourcedValues;
    // In the order messages list them ("expected one of thematic, luminance, ...").
    static KindSections s = [] {
        KindSections k;
        k.add("thematic", sourcedSection(SourcedValues::Imagery, false));
        k.add("luminance", sourcedSection(SourcedValues::Imagery, false));
        k.add("topographic", sourcedSection(SourcedValues::OptionalImagery, false));
        k.add("visibility", sourcedSection(SourcedValues::Imagery, false));
        k.add("data", sourcedSection(SourcedValues::Imagery, true));
        k.add("sequence", sourcedSection(SourcedValues::Sequence, true));
        k.add("normals", sourcedSection(SourcedValues::Imagery, false));
        k.add("maximum", sourcedSection(SourcedValues::Product, true));
        k.add("arrival", sourcedSection(SourcedValues::Product, true));
        k.add("duration", sourcedSection(SourcedValues::Product, true));
        k.add("hazard", sourcedSection(SourcedValues::Product, true));
        k.add("difference", reader::differenceSection());
        return k;
    }();
    return s;
}

std::string scenarioSchema(const std::string& schemaText) {
    using nlohmann::json;
    json schema = json::parse(schemaText, nullptr, false, false);
    if (!schema.is_object() || !schema.contains("$defs") || !schema["$defs"].contains("Layer"))
        return schemaText;
    json& layer = schema["$defs"]["Layer"];
    for (const std::string& name : kindSections().names()) {
        json& kinds = layer["properties"]["kind"]["enum"];
        if (std::find(kinds.begin(), kinds.end(), json(name)) != kinds.end()) continue;
        kinds.push_back(name);
        const std::string text = kindSections().find(name)->schema();
        json fragment = text.empty() ? json::object() : json::parse(text, nullptr, false);
        if (!fragment.is_object()) fragment = json::object();
        json own = json::array();
        if (fragment.contains("properties")) {
            for (auto it = fragment["properties"].begin(); it != fragment["properties"].end();
                 ++it) {
                layer["properties"][it.key()] = it.value();
                own.push_back({{"required", json::array({it.key()})}});
            }
            fragment.erase("properties");
        }
        // The kind's own properties belong to layers of that kind only.
        json entry = {
            {"if",
             {{"properties", {{"kind", {{"const", name}}}}}, {"required", json::array({"kind"})}}},
            {"then", fragment}};
        if (!own.empty()) entry["else"] = {{"not", {{"anyOf", own}}}};
        layer["allOf"].push_back(entry);
    }
    return schema.dump(2);
}

}  // namespace kiosk::config
