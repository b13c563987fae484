// Meaning checks of the comparison pieces (issue 19): a difference layer's operands and a
// comparison lens's two sides name layers of the stack, each side at most once.
#include "config/ScenarioSections.h"

namespace kiosk::config::reader {

void Reader::comparisonReferences(const std::vector<std::string>& layerIds) {
    std::vector<std::string> scalarIds;  // layers with a value per pixel (A - B needs values)
    for (const auto& l : mS.layers)
        if (!l.id.empty() && (l.kind == LayerKind::Sequence || l.kind == LayerKind::Data))
            scalarIds.push_back(l.id);
    for (const auto& l : mS.layers) {
        for (std::size_t k = 0; k < l.operands.size(); ++k) {
            const std::string ptr = childPointer(l.pointer + "/of", k);
            if (l.operands[k] == l.id)
                mC.error("SCENARIO_BAD_VALUE", ptr, "a difference layer cannot subtract itself");
            else if (std::find(layerIds.begin(), layerIds.end(), l.operands[k]) != layerIds.end())
                reference(ptr, "scalar layer (sequence or data)", l.operands[k], scalarIds);
            else
                reference(ptr, "layer", l.operands[k], layerIds);
        }
    }
    for (const auto& lens : mS.lenses) {
        if (lens.kind != LensKind::Comparison) continue;
        for (const auto* side : {&lens.insideStack, &lens.outsideStack}) {
            const std::string base =
                lens.pointer + (side == &lens.insideStack ? "/inside" : "/outside");
            for (std::size_t k = 0; k < side->size(); ++k) {
                const std::string ptr = childPointer(base, k);
                reference(ptr, "layer", (*side)[k], layerIds);
                const auto& other =
                    side == &lens.insideStack ? lens.outsideStack : lens.insideStack;
                if (side == &lens.outsideStack &&
                    std::find(other.begin(), other.end(), (*side)[k]) != other.end())
                    mC.error(
                        "SCENARIO_CONFLICT", ptr,
                        "layer " + quote((*side)[k]) + " is on both sides of the comparison lens");
                if (std::find(side->begin(), side->begin() + std::ptrdiff_t(k), (*side)[k]) !=
                    side->begin() + std::ptrdiff_t(k))
                    mC.error("SCENARIO_DUPLICATE_ID", ptr,
                             "layer " + quote((*side)[k]) + " is listed twice");
            }
        }
    }
}

}  // namespace kiosk::config::reader
