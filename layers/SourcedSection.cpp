// The scenario section of the kinds that read a store table or sequence: the built-in imagery,
// data, sequence and product kinds (config/KindSections.cpp registers one per kind).
#include "layers/SourcedSection.h"

namespace kiosk::config::reader {
namespace {

class SourcedSection : public KindSection {
public:
    SourcedSection(SourcedValues values, bool transfer) : mValues(values), mTransfer(transfer) {}
    void read(Ctx& c, const Obj& o, Layer& l) const override {
        refuseOperands(c, o);
        productOptions(c, o, l);
        checkSourced(c, o, l, mValues, mTransfer);
    }

private:
    SourcedValues mValues;
    bool mTransfer;
};

}  // namespace

std::string kindNameOf(const Layer& l) {
    return l.kindName.empty() ? layerKindName(l.kind) : l.kindName;
}

void refuseOperands(Ctx& c, const Obj& o) {
    if (o.has("of"))
        c.error("SCENARIO_CONFLICT", o.at("of"), "\"of\" applies to difference layers only");
}

void checkSourced(Ctx& c, const Obj& o, const Layer& l, SourcedValues values, bool transfer) {
    const bool isSeq = values == SourcedValues::Sequence || values == SourcedValues::Product;
    const std::string& ptr = o.ptr();
    if (!isSeq && (o.has("interpolate") || o.has("nodataAs")))
        c.error("SCENARIO_CONFLICT", ptr,
                "\"interpolate\" and \"nodataAs\" apply to sequence layers only");
    if (values == SourcedValues::Product && o.has("interpolate"))
        c.error("SCENARIO_CONFLICT", o.at("interpolate"),
                "\"interpolate\" applies to sequence layers only (a product follows its "
                "sequence's data between steps)");
    if (!o.has("source") && values != SourcedValues::OptionalImagery)
        c.error("SCENARIO_MISSING", ptr, "missing required property \"source\"");
    if (o.has("source") && isSeq && l.source.sequence.empty())
        c.error("SCENARIO_MISSING", o.at("source"),
                "a " + kindNameOf(l) + " layer needs \"sequence\" (the store's sequence name)");
    if (o.has("source") && !isSeq && l.source.layer.empty() && !l.source.store.empty())
        c.error("SCENARIO_MISSING", o.at("source"), "missing required property \"layer\"");
    if (transfer && l.transfer.empty() && !o.has("transfer"))
        c.error("SCENARIO_MISSING", ptr,
                "a " + kindNameOf(l) + " layer needs \"transfer\" (a transfer function name)");
}

std::shared_ptr<const KindSection> sourcedSection(SourcedValues values, bool transfer) {
    return std::make_shared<SourcedSection>(values, transfer);
}

}  // namespace kiosk::config::reader
