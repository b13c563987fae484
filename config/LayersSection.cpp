// The "layers" section: the stack, each layer's kind, source and operation.
#include "config/KindSection.h"
#include "config/ScenarioSections.h"
#include "layers/SourcedSection.h"

#include <algorithm>

namespace kiosk::config::reader {

std::optional<SourceRef> Reader::source(const json& j, const std::string& ptr) {
    Obj o(mC, j, ptr, "Source");
    if (!o.valid()) return std::nullopt;
    SourceRef s;
    assign(s.store, o.name("store", true));
    assign(s.layer, o.name("layer"));
    assign(s.sequence, o.name("sequence"));
    if (!s.layer.empty() && !s.sequence.empty())
        mC.error("SCENARIO_CONFLICT", ptr, "give either \"layer\" or \"sequence\", not both");
    return s;
}

void Reader::layers(const json& arr) {
    // A layer's kind is a name the kinds' registry knows; the kind's own section reads the rest.
    const KindSections& kinds = kindSections();
    EnumTable<std::string> kindNames;
    for (const auto& n : kinds.names()) kindNames.emplace_back(n, n);
    for (std::size_t i = 0; i < arr.size(); ++i) {
        const std::string ptr = childPointer("/layers", i);
        const KindSection* section = nullptr;
        if (arr[i].is_object())
            if (auto k = arr[i].find("kind"); k != arr[i].end() && k->is_string())
                section = kinds.find(k->get<std::string>());
        std::vector<std::string> keys = propertyTable().at("Layer");
        if (section)
            for (const auto& p : section->properties())
                if (std::find(keys.begin(), keys.end(), p) == keys.end()) keys.push_back(p);
        Obj o(mC, arr[i], ptr, keys);
        if (!o.valid()) continue;
        Layer l;
        l.pointer = ptr;
        assign(l.id, o.name("id", true));
        auto kind = o.oneOf("kind", kindNames, true);
        if (kind) {
            l.kindName = *kind;
            l.kind = LayerKind::Registered;
            for (const auto& [name, k] : kLayerKinds)
                if (name == *kind) l.kind = k;
        }
        if (const json* s = o.get("source")) assign(l.source, source(*s, o.at("source")));
        assign(l.transfer, o.name("transfer"));
        assign(l.enabled, o.boolean("enabled"));
        if (const json* op = o.get("operation")) {
            if (op->is_string()) {
                assign(l.operation.type, o.oneOf("operation", kOperations));
            } else {
                Obj oo(mC, *op, o.at("operation"), "Operation");
                if (oo.valid()) {
                    assign(l.operation.type, oo.oneOf("type", kOperations, true));
                    assign(l.operation.weight, oo.num("weight", Range{0, 16}));
                    assign(l.operation.opacity, oo.num("opacity", kUnit));
                    assign(l.operation.visibility, oo.name("visibility"));
                }
            }
        }
        assign(l.interpolate, o.oneOf("interpolate", kInterpolations));
        if (auto v = o.num("nodataAs", kDataValue)) l.nodataAs = v;
        l.operands = layerIds(o, "of");
        if (kind && section)
            section->read(mC, o, l);
        else
            refuseOperands(mC, o);
        if (l.operation.type == OperationType::Blend && l.operation.visibility.empty())
            mC.error("SCENARIO_MISSING", o.at("operation"),
                     "a blend operation needs \"visibility\" (a visibility layer id)");
        mS.layers.push_back(std::move(l));
    }
}

}  // namespace kiosk::config::reader
