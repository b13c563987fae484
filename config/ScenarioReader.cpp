#include "config/ScenarioReader.h"

#include "config/BriefingReader.h"
#include "config/DocumentLoader.h"
#include "config/Limits.h"
#include "config/PathPolicy.h"
#include "config/ScenarioSections.h"

#include <algorithm>

namespace kiosk::config {

namespace reader {

void Reader::root(const json& doc) {
    Obj o(mC, doc, "", "Scenario");
    if (!o.valid()) return;
    if (const json* v = o.get("version", true)) {
        if (!v->is_number_integer() && !v->is_number_unsigned()) {
            mC.error("SCENARIO_TYPE", "/version", "expected integer, got " + typeName(*v));
        } else if (v->get<std::int64_t>() != kScenarioVersion) {
            mC.error("SCENARIO_VERSION", "/version",
                     "unsupported version " + v->dump() + " (this geokiosk reads version " +
                         std::to_string(kScenarioVersion) + ")");
            return;  // a different version's other properties would only add noise
        } else {
            mS.version = kScenarioVersion;
        }
    }
    o.str("$schema");
    assign(mS.title, o.str("title"));
    assign(mS.caption, o.str("caption"));
    if (const json* j = o.object("stores", true)) {
        stores(*j);
        mStoresGiven = true;
    }
    if (const json* j = o.object("transferFunctions")) transferFunctions(*j);
    if (const json* j = o.get("terrain", true)) terrain(*j);
    if (const json* j = o.object("clock")) clock(*j);
    if (const json* j = o.array("layers", true)) layers(*j);
    if (const json* j = o.array("lenses")) lenses(*j);
    if (const json* j = o.array("projectiveMappings")) mappings(*j);
    if (const json* j = o.object("viewpoints")) viewpoints(*j);
    if (const json* j = o.object("cameraPaths")) cameraPaths(*j);
    if (const json* j = o.get("camera")) camera(*j);
    if (const json* j = o.get("overlays")) overlays(*j);
    if (const json* j = o.get("lighting")) lighting(*j);
    if (const json* j = o.get("governor")) governor(*j);
    crossReferences();
}

void Reader::stores(const json& j) {
    if (j.empty()) mC.error("SCENARIO_MISSING", "/stores", "declare at least one store");
    for (auto it = j.begin(); it != j.end(); ++it) {
        const std::string ptr = childPointer("/stores", it.key());
        if (!it->is_string() || it->get<std::string>().empty()) {
            mC.error("SCENARIO_TYPE", ptr,
                     "expected a store file path (string), got " + typeName(*it));
            continue;
        }
        auto path = mC.resolve(ptr, it->get<std::string>());
        if (contained(path, ptr))
            mS.stores[it.key()] = StoreRef{it.key(), path, ptr};
        else
            mRefusedStores.insert(it.key());  // already reported: no "unknown store" echo
    }
}

void Reader::terrain(const json& j) {
    Obj o(mC, j, "/terrain", "Terrain");
    if (!o.valid()) return;
    Terrain& t = mS.terrain;
    assign(t.store, o.name("store", true));
    assign(t.elevation, o.name("elevation"));
    const Range tau{0, 64, true, false};
    assign(t.tauGeom, o.num("tauGeom", tau));
    assign(t.tauTex, o.num("tauTex", tau));
    assign(t.verticalExaggeration, o.num("verticalExaggeration", Range{0, 100, true, false}));
    assign(t.reference, o.oneOf("reference", kTerrainReferences));
    if (const json* b = o.get("cacheBytes"))
        assign(t.cacheBytes, readBytes(mC, *b, o.at("cacheBytes")));
    if (const json* b = o.get("gpuBytes")) assign(t.gpuBytes, readBytes(mC, *b, o.at("gpuBytes")));
    assign(t.proceduralDetail, o.boolean("proceduralDetail"));
    assign(t.occlusionCulling, o.boolean("occlusionCulling"));
    assign(t.textureCompression, o.oneOf("textureCompression", kTextureCompressions));
}

}  // namespace reader

namespace {

using namespace reader;

Result<Scenario> build(LoadedDocument doc, Diagnostics diags,
                       std::vector<std::filesystem::path>* filesRead) {
    Scenario s;
    s.sourceFiles = doc.files;
    if (diags.hasErrors() || doc.value.is_null()) {
        if (filesRead) *filesRead = s.sourceFiles;
        return diags;
    }
    s.sourceMap = std::move(doc.sourceMap);
    checkLimits(doc.value, s.sourceMap, diags);
    if (diags.hasErrors()) {
        if (filesRead) *filesRead = s.sourceFiles;
        return diags;
    }
    Ctx ctx(s.sourceMap, diags);
    Reader reader(ctx, s);
    if (const auto tfs = doc.value.find("transferFunctions");
        tfs != doc.value.end() && tfs->is_object())
        for (auto it = tfs->begin(); it != tfs->end(); ++it)
            reader.mDeclaredTransfers.push_back(it.key());
    reader.root(doc.value);
    readBriefing(doc.value, s, diags);  // config/BriefingReader.cpp
    for (auto& f : reader.mFiles)
        if (std::find(s.sourceFiles.begin(), s.sourceFiles.end(), f) == s.sourceFiles.end())
            s.sourceFiles.push_back(f);
    if (filesRead) *filesRead = s.sourceFiles;
    if (diags.hasErrors()) return diags;
    return {std::move(s), std::move(diags)};
}

}  // namespace

const std::map<std::string, std::vector<std::string>>& acceptedProperties() {
    return propertyTable();
}

const char* layerKindName(LayerKind k) noexcept {
    if (k == LayerKind::Registered) return "registered";  // its name: Layer::kindName
    for (const auto& [name, kind] : kLayerKinds)
        if (kind == k) return name.c_str();
    return "thematic";
}

const char* operationName(OperationType t) noexcept {
    for (const auto& [name, type] : kOperations)
        if (type == t) return name.c_str();
    return "opacity";
}

Result<Scenario> parseScenario(std::string_view text, const std::filesystem::path& name,
                               std::vector<std::filesystem::path>* filesRead) {
    try {
        Diagnostics diags;
        LoadedDocument doc = loadDocument(text, name, diags);
        return build(std::move(doc), std::move(diags), filesRead);
    } catch (const std::exception& e) {
        // Allocation failure or a library bug: still a message, never a crash.
        Diagnostics d;
        d.error("SCENARIO_INTERNAL", name.string(), "", std::string("internal error: ") + e.what());
        return d;
    }
}

Result<Scenario> readScenario(const std::filesystem::path& file,
                              std::vector<std::filesystem::path>* filesRead) {
    if (filesRead) *filesRead = {file};
    std::string why;
    auto text = readTextFile(file, kMaxScenarioFileBytes, why);
    if (!text) {
        Diagnostics d;
        d.error("SCENARIO_FILE", file.string(), "", "scenario file " + why);
        return d;
    }
    return parseScenario(*text, file, filesRead);
}

}  // namespace kiosk::config
