// A projective mapping whose data is a layer of the stack (docs/projective-mappings.md, "Data
// layers"): the mapping shows that layer's value at each point, live, through its own transfer
// function. Each mistake is one error at its JSON pointer.
#include "config/ScenarioSections.h"

#include <algorithm>

namespace kiosk::config::reader {

void Reader::liveLayerMapping(const Obj& o, const ProjectiveMapping& m) {
    const std::string ptr = o.at("layer");
    for (const char* other : {"data", "image", "route"})
        if (o.has(other))
            mC.error("SCENARIO_CONFLICT", ptr,
                     std::string("give either \"layer\" or \"") + other + "\", not both");
    // The values stay where the layer has them: the rectangle only chooses where they show.
    if (o.has("textureMatrix"))
        mC.error("SCENARIO_CONFLICT", o.at("textureMatrix"),
                 "a mapping of a layer shows the layer's values where they are; it takes no "
                 "\"textureMatrix\"");
    for (const MappingKey& key : m.keys)
        if (key.textureMatrix)
            mC.error("SCENARIO_CONFLICT", key.pointer + "/textureMatrix",
                     "a mapping of a layer shows the layer's values where they are; its keys "
                     "take no \"textureMatrix\"");
    if (!o.has("transfer"))
        mC.error("SCENARIO_MISSING", m.pointer,
                 "a mapping of layer " + quote(m.layer) +
                     " needs \"transfer\" (the colours of the layer's values)");
}

void Reader::mappingLayerReferences(const std::vector<std::string>& layerIds) {
    // Layers with a value per pixel: data, sequences, products and differences.
    std::vector<std::string> scalarIds;
    for (const auto& l : mS.layers)
        if (!l.id.empty() && (l.kind == LayerKind::Sequence || l.kind == LayerKind::Data ||
                              l.kind == LayerKind::Difference || isProductKind(l.kind)))
            scalarIds.push_back(l.id);
    for (const auto& m : mS.projectiveMappings) {
        if (m.layer.empty()) continue;
        const std::string ptr = m.pointer + "/layer";
        const auto it = std::find_if(mS.layers.begin(), mS.layers.end(),
                                     [&](const Layer& l) { return l.id == m.layer; });
        if (it == mS.layers.end() ||
            std::find(layerIds.begin(), layerIds.end(), m.layer) == layerIds.end())
            reference(ptr, "layer", m.layer, layerIds);
        else if (std::find(scalarIds.begin(), scalarIds.end(), m.layer) == scalarIds.end())
            reference(ptr, "scalar layer (data, sequence, product or difference)", m.layer,
                      scalarIds);
        else if (!it->enabled)
            mC.error("SCENARIO_CONFLICT", ptr,
                     "layer " + quote(m.layer) +
                         " is disabled: a mapping shows the values of an enabled layer (give it "
                         "opacity 0 to show it through the mapping only)");
    }
}

}  // namespace kiosk::config::reader
