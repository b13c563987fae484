#include "config/DataUnits.h"

#include "runtime/core/Units.h"

#include <map>
#include <optional>

namespace kiosk::config {

std::string storedUnits(const SourceRef& src, const StoreLookup& lookup) {
    const io::StoreInfo* info = lookup ? lookup(src.store) : nullptr;
    if (!info) return "";
    std::string units;
    if (!src.sequence.empty()) {
        if (const auto* s = info->findSequence(src.sequence)) units = s->units;
    } else if (!src.layer.empty()) {
        if (const auto* l = info->findLayer(src.layer))
            if (l->kind != io::LayerKind::Imagery) units = l->units;
    }
    // "class" (categorical data) names no unit a legend should print.
    return units == "class" ? "" : units;
}

void adoptDataUnits(Scenario& scenario, const StoreLookup& lookup) {
    // Per unit-less transfer function: the data's units, or nullopt once two disagree.
    std::map<std::string, std::optional<std::string>> found;
    auto visit = [&](const SourceRef& src, const std::string& transfer) {
        if (transfer.empty()) return;
        const TransferFunctionDef* def = scenario.findTransfer(transfer);
        if (!def || !def->function.units.empty()) return;
        const std::string units = storedUnits(src, lookup);
        if (units.empty()) return;
        auto [it, fresh] = found.emplace(transfer, units);
        if (!fresh && it->second && !sameUnits(*it->second, units)) it->second.reset();
    };
    for (const Layer& l : scenario.layers) {
        // Arrival and duration colour times; hazard colours classes (docs/products.md).
        if (l.kind == LayerKind::Arrival || l.kind == LayerKind::Duration) {
            const TransferFunctionDef* def = scenario.findTransfer(l.transfer);
            if (!def || !def->function.units.empty()) continue;
            auto [it, fresh] = found.emplace(l.transfer, l.product.timeUnits);
            if (!fresh && it->second && !sameUnits(*it->second, l.product.timeUnits))
                it->second.reset();
            continue;
        }
        if (l.kind == LayerKind::Hazard) continue;
        visit(l.source, l.transfer);
    }
    for (const ProjectiveMapping& m : scenario.projectiveMappings) visit(m.data, m.transfer);
    for (const auto& [name, units] : found)
        if (units) scenario.transferFunctions[name].function.units = *units;
}

}  // namespace kiosk::config
