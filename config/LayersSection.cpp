// The "layers" section: the stack, each layer's kind, source and operation.
#include "config/ScenarioSections.h"

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
    for (std::size_t i = 0; i < arr.size(); ++i) {
        const std::string ptr = childPointer("/layers", i);
        Obj o(mC, arr[i], ptr, "Layer");
        if (!o.valid()) continue;
        Layer l;
        l.pointer = ptr;
        assign(l.id, o.name("id", true));
        auto kind = o.oneOf("kind", kLayerKinds, true);
        assign(l.kind, kind);
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
        if (auto v = o.num("nodataAs")) l.nodataAs = v;
        l.operands = layerIds(o, "of");
        if (kind && *kind == LayerKind::Difference) {
            // A - B of two scalar layers of the stack: no source of its own.
            if (o.has("source"))
                mC.error("SCENARIO_CONFLICT", o.at("source"),
                         "a difference layer has no \"source\": it subtracts the layers in \"of\"");
            if (o.has("of") && l.operands.size() != 2)
                mC.error("SCENARIO_BAD_VALUE", o.at("of"),
                         "\"of\" wants two layer ids [A, B] (drawn as A - B)");
            else if (!o.has("of"))
                mC.error("SCENARIO_MISSING", ptr,
                         "a difference layer needs \"of\": [A, B], two scalar layer ids");
            if (l.transfer.empty() && !o.has("transfer"))
                mC.error("SCENARIO_MISSING", ptr,
                         "a difference layer needs \"transfer\" (a diverging transfer function)");
        } else if (o.has("of")) {
            mC.error("SCENARIO_CONFLICT", o.at("of"), "\"of\" applies to difference layers only");
        }
        if (kind) product(o, l);
        if (kind && *kind != LayerKind::Difference) {
            const bool isSeq = *kind == LayerKind::Sequence || isProductKind(*kind);
            if (!isSeq && (o.has("interpolate") || o.has("nodataAs")))
                mC.error("SCENARIO_CONFLICT", ptr,
                         "\"interpolate\" and \"nodataAs\" apply to sequence layers only");
            if (isProductKind(*kind) && o.has("interpolate"))
                mC.error("SCENARIO_CONFLICT", o.at("interpolate"),
                         "\"interpolate\" applies to sequence layers only (a product follows its "
                         "sequence's data between steps)");
            if (!o.has("source") && *kind != LayerKind::Topographic)
                mC.error("SCENARIO_MISSING", ptr, "missing required property \"source\"");
            if (o.has("source") && isSeq && l.source.sequence.empty())
                mC.error("SCENARIO_MISSING", o.at("source"),
                         std::string("a ") + layerKindName(*kind) +
                             " layer needs \"sequence\" (the store's sequence name)");
            if (o.has("source") && !isSeq && l.source.layer.empty() && !l.source.store.empty())
                mC.error("SCENARIO_MISSING", o.at("source"), "missing required property \"layer\"");
            const bool needsTransfer = isSeq || *kind == LayerKind::Data;
            if (needsTransfer && l.transfer.empty() && !o.has("transfer"))
                mC.error("SCENARIO_MISSING", ptr,
                         std::string("a ") + layerKindName(*kind) +
                             " layer needs \"transfer\" (a transfer function name)");
        }
        if (l.operation.type == OperationType::Blend && l.operation.visibility.empty())
            mC.error("SCENARIO_MISSING", o.at("operation"),
                     "a blend operation needs \"visibility\" (a visibility layer id)");
        mS.layers.push_back(std::move(l));
    }
}

}  // namespace kiosk::config::reader
