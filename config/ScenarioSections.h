#pragma once

// Internal to config/: the scenario reader, one member function per section. The definitions
// are split by seam: ScenarioReader.cpp (root, stores, terrain), LayersSection.cpp,
// TransferSection.cpp, AnimationSections.cpp (clock, lenses, mappings), ViewSections.cpp
// (viewpoints, camera, overlays, lighting, governor), ScenarioChecks.cpp (references, key order,
// paths).
#include "config/ReaderEnums.h"
#include "config/ReaderSupport.h"

#include <filesystem>
#include <set>
#include <utility>

namespace kiosk::config::reader {

class Reader {
public:
    Reader(Ctx& c, Scenario& s) : mC(c), mS(s) {}
    void root(const json& doc);

private:
    void stores(const json& j);
    void terrain(const json& j);
    std::optional<SourceRef> source(const json& j, const std::string& ptr);
    void layers(const json& arr);
    void transferFunctions(const json& j);
    void reemit(const Diagnostics& d, const std::string& ptr, const std::string& prefix);
    std::optional<TransferFunctionDef> transfer(const json& j, const std::string& ptr,
                                                const std::string& name);
    std::size_t errorCount() const;
    bool fileExists(const std::filesystem::path& file, const std::string& ptr);
    void clock(const json& j);
    void lenses(const json& arr);
    /** @brief `key` as an array of layer ids (comparison sides, difference "of"). */
    std::vector<std::string> layerIds(const Obj& o, const std::string& key);
    void mappings(const json& arr);
    MappingRoute route(const json& j, const std::string& ptr);
    std::optional<Viewpoint> viewpoint(const Obj& o, bool targetRequired);
    void viewpoints(const json& j);
    void cameraPaths(const json& j);
    void camera(const json& j);
    void simpleOverlay(const json& j, const std::string& ptr, SimpleOverlay& out);
    void overlays(const json& j);
    static std::optional<int> parseZone(const std::string& tz);
    void governor(const json& j);
    void lighting(const json& j);
    // Keys must not go back in time; offsets are compared with offsets (and with absolute times
    // once a clock gives them a start).
    template <class Key>
    void keyOrder(const std::vector<Key>& keys, const std::string& ptr) {
        mKeyLists.push_back({ptr, {}});
        for (const auto& k : keys) mKeyLists.back().second.push_back({k.time, k.pointer});
    }
    void checkKeyOrder();
    void reference(const std::string& ptr, const std::string& what, const std::string& name,
                   const std::vector<std::string>& candidates);
    template <class Map>
    static std::vector<std::string> keysOf(const Map& m) {
        std::vector<std::string> out;
        for (const auto& kv : m) out.push_back(kv.first);
        return out;
    }
    void crossReferences();
    /** @brief A legend's layer or transfer function (its transfer from the layer when named). */
    void checkLegend(LegendOverlay& legend, const std::vector<std::string>& layerIds,
                     const std::vector<std::string>& tfDeclared);
    /** @brief Difference operands and comparison-lens sides (ComparisonChecks.cpp). */
    void comparisonReferences(const std::vector<std::string>& layerIds);
    void liveLayerMapping(const Obj& o, const ProjectiveMapping& m);
    void mappingLayerReferences(const std::vector<std::string>& layerIds);
    // The path rule of config/PathPolicy.h; the file's name is quoted only as given.
    bool contained(const std::filesystem::path& file, const std::string& ptr);

public:
    std::vector<std::filesystem::path> mFiles;
    std::vector<std::string> mDeclaredTransfers;

private:
    Ctx& mC;
    Scenario& mS;
    std::vector<std::pair<std::string, std::vector<std::pair<TimeSpec, std::string>>>> mKeyLists;
    bool mStoresGiven = false;
    std::vector<std::filesystem::path> mRoots;
    std::set<std::string> mRefusedStores;
};

}  // namespace kiosk::config::reader
