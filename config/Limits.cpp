#include "config/Limits.h"

#include <nlohmann/json.hpp>

#include <string>

namespace kiosk::config {

namespace {

using nlohmann::json;

class LimitCheck {
public:
    LimitCheck(const SourceMap& map, Diagnostics& diags) : mMap(map), mDiags(diags) {}

    // `what` names the items, e.g. "lenses"; `ptr` is where the over-full array or object is.
    void count(const json* j, const std::string& ptr, std::size_t limit, const char* what) {
        if (!j || !(j->is_array() || j->is_object()) || j->size() <= limit) return;
        report(ptr, std::to_string(j->size()) + " " + what + " exceed the limit of " +
                        std::to_string(limit));
    }

    void report(const std::string& ptr, std::string message) {
        const Location l = mMap.value(ptr);
        auto& d = mDiags.error("SCENARIO_LIMIT", l.file, ptr, std::move(message));
        d.line = l.line;
        d.column = l.column;
        d.hint = "see \"Limits\" in docs/scenario-format.md";
    }

private:
    const SourceMap& mMap;
    Diagnostics& mDiags;
};

const json* member(const json& j, const char* key) {
    if (!j.is_object()) return nullptr;
    auto it = j.find(key);
    return it == j.end() ? nullptr : &*it;
}

std::string stringOf(const json* j) {
    return j && j->is_string() ? j->get<std::string>() : "";
}

}  // namespace

int textureUnitsNeeded(const json& doc) {
    const json* layers = member(doc, "layers");
    int units = 1;  // elevation LUT
    if (layers && layers->is_array()) {
        for (const auto& l : *layers) {
            const std::string kind = stringOf(member(l, "kind"));
            if (kind == "data")
                units += 2;
            else if (kind == "sequence")
                units += stringOf(member(l, "interpolate")) == "arrival" ? 4 : 3;
            else
                units += 1;
        }
    }
    const json* mappings = member(doc, "projectiveMappings");
    if (mappings && mappings->is_array() && !mappings->empty()) units += 2;
    return units;
}

void checkLimits(const json& doc, const SourceMap& map, Diagnostics& diags) {
    if (!doc.is_object()) return;
    LimitCheck c(map, diags);
    const json* layers = member(doc, "layers");
    c.count(layers, "/layers", kMaxLayers, "layers");
    if (layers && layers->is_array() && layers->size() <= kMaxLayers) {
        const int units = textureUnitsNeeded(doc);
        if (units > kMaxTextureUnits)
            c.report("/layers",
                     "the layers need " + std::to_string(units) + " texture units; the limit is " +
                         std::to_string(kMaxTextureUnits) + " (what OpenGL ES 3.0 guarantees)");
    }
    c.count(member(doc, "lenses"), "/lenses", kMaxLenses, "lenses");
    c.count(member(doc, "projectiveMappings"), "/projectiveMappings", kMaxMappings,
            "projective mappings");
    for (const char* named : {"stores", "transferFunctions", "viewpoints", "cameraPaths"})
        c.count(member(doc, named), std::string("/") + named, kMaxNamedEntries, "entries");

    // Keys and points inside array items / named entries.
    const auto keysIn = [&](const json* container, const std::string& ptr) {
        if (!container) return;
        if (container->is_array()) {
            for (std::size_t i = 0; i < container->size() && i <= kMaxNamedEntries; ++i)
                c.count(member((*container)[i], "keys"), childPointer(ptr, i) + "/keys", kMaxKeys,
                        "keys");
        } else if (container->is_object() && container->size() <= kMaxNamedEntries) {
            for (auto it = container->begin(); it != container->end(); ++it)
                c.count(member(*it, "keys"), childPointer(ptr, it.key()) + "/keys", kMaxKeys,
                        "keys");
        }
    };
    keysIn(member(doc, "lenses"), "/lenses");
    keysIn(member(doc, "projectiveMappings"), "/projectiveMappings");
    keysIn(member(doc, "cameraPaths"), "/cameraPaths");
    if (const json* lighting = member(doc, "lighting"))
        c.count(member(*lighting, "keys"), "/lighting/keys", kMaxKeys, "keys");
    if (const json* ms = member(doc, "projectiveMappings"); ms && ms->is_array())
        for (std::size_t i = 0; i < ms->size() && i <= kMaxMappings; ++i)
            if (const json* route = member((*ms)[i], "route"))
                c.count(member(*route, "points"),
                        childPointer("/projectiveMappings", i) + "/route/points", kMaxPoints,
                        "points");
    if (const json* tfs = member(doc, "transferFunctions");
        tfs && tfs->is_object() && tfs->size() <= kMaxNamedEntries)
        for (auto it = tfs->begin(); it != tfs->end(); ++it)
            for (const char* list : {"stops", "classes", "opacity"})
                c.count(member(*it, list),
                        childPointer(childPointer("/transferFunctions", it.key()), list),
                        kMaxPoints, "entries");
}

}  // namespace kiosk::config
