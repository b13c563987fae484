// Checks across sections once all are read: references by name, key order, the path rule.
#include "config/PathPolicy.h"
#include "config/ScenarioSections.h"

namespace kiosk::config::reader {

void Reader::checkKeyOrder() {
    for (const auto& [ptr, keys] : mKeyLists) {
        for (std::size_t i = 1; i < keys.size(); ++i) {
            const TimeSpec &a = keys[i - 1].first, &b = keys[i].first;
            if ((a.isOffset || b.isOffset) && !mS.clock) {
                mC.error("SCENARIO_MISSING", keys[i].second + "/time",
                         "time offsets need a \"clock\" with a start");
                break;
            }
            const double start = mS.clock ? mS.clock->start : 0.0;
            if (b.resolve(start) < a.resolve(start)) {
                mC.error("SCENARIO_RANGE", keys[i].second + "/time",
                         "keys must be in time order (this key is earlier than the one before)");
                break;
            }
        }
        if (keys.size() == 1 && keys[0].first.isOffset && !mS.clock)
            mC.error("SCENARIO_MISSING", keys[0].second + "/time",
                     "time offsets need a \"clock\" with a start");
    }
}

void Reader::reference(const std::string& ptr, const std::string& what, const std::string& name,
                       const std::vector<std::string>& candidates) {
    // Without a "stores" object that error already says it all; no per-reference echo.
    if (what == "store" && (!mStoresGiven || mRefusedStores.count(name))) return;
    if (std::find(candidates.begin(), candidates.end(), name) != candidates.end()) return;
    auto& e = mC.error("SCENARIO_UNKNOWN_REFERENCE", ptr, "unknown " + what + " " + quote(name));
    mC.didYouMean(e, name, candidates);
}

void Reader::crossReferences() {
    const auto storeIds = keysOf(mS.stores);
    const auto tfNames = keysOf(mS.transferFunctions);
    // Transfer functions that failed to read still exist by name: do not also report every
    // reference to them as unknown.
    std::vector<std::string> tfDeclared = tfNames;
    tfDeclared.insert(tfDeclared.end(), mDeclaredTransfers.begin(), mDeclaredTransfers.end());
    if (!mS.terrain.store.empty()) reference("/terrain/store", "store", mS.terrain.store, storeIds);

    std::vector<std::string> layerIds, visibilityIds;
    std::set<std::string> seen;
    for (const auto& l : mS.layers) {
        if (l.id.empty()) continue;
        if (!seen.insert(l.id).second)
            mC.error("SCENARIO_DUPLICATE_ID", l.pointer + "/id",
                     "layer id " + quote(l.id) + " is used twice");
        layerIds.push_back(l.id);
        if (l.kind == LayerKind::Visibility) visibilityIds.push_back(l.id);
    }
    for (const auto& l : mS.layers) {
        if (!l.source.store.empty())
            reference(l.pointer + "/source/store", "store", l.source.store, storeIds);
        if (!l.transfer.empty())
            reference(l.pointer + "/transfer", "transfer function", l.transfer, tfDeclared);
        if (!l.operation.visibility.empty())
            reference(l.pointer + "/operation/visibility", "visibility layer",
                      l.operation.visibility, visibilityIds);
    }
    seen.clear();
    for (const auto& lens : mS.lenses) {
        if (!lens.id.empty() && !seen.insert(lens.id).second)
            mC.error("SCENARIO_DUPLICATE_ID", lens.pointer + "/id",
                     "lens id " + quote(lens.id) + " is used twice");
        if (!lens.inside.empty())
            reference(lens.pointer + "/inside", "layer", lens.inside, layerIds);
        if (!lens.outside.empty())
            reference(lens.pointer + "/outside", "layer", lens.outside, layerIds);
    }
    comparisonReferences(layerIds);
    mappingLayerReferences(layerIds);
    seen.clear();
    for (const auto& m : mS.projectiveMappings) {
        if (!m.id.empty() && !seen.insert(m.id).second)
            mC.error("SCENARIO_DUPLICATE_ID", m.pointer + "/id",
                     "projective mapping id " + quote(m.id) + " is used twice");
        if (!m.data.store.empty())
            reference(m.pointer + "/data/store", "store", m.data.store, storeIds);
        if (!m.transfer.empty())
            reference(m.pointer + "/transfer", "transfer function", m.transfer, tfDeclared);
    }
    const auto viewpointNames = keysOf(mS.viewpoints);
    const auto pathNames = keysOf(mS.cameraPaths);
    if (!mS.camera.viewpoint.empty())
        reference("/camera/viewpoint", "viewpoint", mS.camera.viewpoint, viewpointNames);
    if (!mS.camera.path.empty())
        reference("/camera/path", "camera path", mS.camera.path, pathNames);
    for (auto& [name, path] : mS.cameraPaths) {
        for (auto& key : path.keys) {
            if (key.viewpoint.empty()) continue;
            auto it = mS.viewpoints.find(key.viewpoint);
            if (it == mS.viewpoints.end())
                reference(key.pointer + "/viewpoint", "viewpoint", key.viewpoint, viewpointNames);
            else
                key.view = it->second;
        }
    }
    for (auto& legend : mS.overlays.legends) checkLegend(legend, layerIds, tfDeclared);
    checkKeyOrder();
}

void Reader::checkLegend(LegendOverlay& legend, const std::vector<std::string>& layerIds,
                         const std::vector<std::string>& tfDeclared) {
    const std::string& at = legend.pointer;
    if (!legend.layer.empty()) {
        // A layer's own legend: its transfer function, the title its kind gives.
        const Layer* shown = nullptr;
        for (const auto& l : mS.layers)
            if (l.id == legend.layer) shown = &l;
        if (!shown)
            reference(at + "/layer", "layer", legend.layer, layerIds);
        else if (shown->transfer.empty())
            mC.error("SCENARIO_BAD_VALUE", at + "/layer",
                     "layer \"" + legend.layer + "\" has no transfer function to show");
        else if (!legend.transfer.empty() && legend.transfer != shown->transfer)
            mC.error("SCENARIO_CONFLICT", at + "/transfer",
                     "give either \"layer\" or \"transfer\": layer \"" + legend.layer +
                         "\" uses \"" + shown->transfer + "\"");
        else
            legend.transfer = shown->transfer;
    }
    if (legend.enabled && legend.transfer.empty()) {
        for (const auto& l : mS.layers)
            if (!l.transfer.empty()) {
                legend.transfer = l.transfer;
                break;
            }
        if (legend.transfer.empty())
            mC.error("SCENARIO_MISSING", at,
                     "the legend needs \"transfer\" (no layer uses a transfer function)");
    } else if (!legend.transfer.empty()) {
        reference(at + "/transfer", "transfer function", legend.transfer, tfDeclared);
    }
}

// The path rule of config/PathPolicy.h; the file's name is quoted only as given.
bool Reader::contained(const std::filesystem::path& file, const std::string& ptr) {
    if (mRoots.empty()) mRoots = allowedRoots(mS.sourceFiles.front());
    auto why = checkContained(file, mRoots);
    if (!why) return true;
    mC.error("SCENARIO_PATH", ptr, "file " + quote(file.string()) + " " + *why);
    return false;
}

}  // namespace kiosk::config::reader
