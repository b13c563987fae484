// The "product" object of the derived-product layers (maximum, arrival, duration, hazard):
// which options each kind takes and what each requires (docs/products.md). Compiled into
// kiosk_config (config/CMakeLists.txt): every built-in kind's section reads it
// (layers/SourcedSection.h), refusing it on the kinds that are not products.
#include "layers/SourcedSection.h"

namespace kiosk::config::reader {
namespace {

const EnumTable<std::string> kTimeUnits = {{"h", "h"}, {"min", "min"}, {"s", "s"}};

}  // namespace

void productOptions(Ctx& c, const Obj& layer, Layer& l) {
    const LayerKind kind = l.kind;
    const json* j = layer.get("product");
    l.product.pointer = j ? layer.at("product") : l.pointer;
    if (!isProductKind(kind)) {
        if (j)
            c.error("SCENARIO_CONFLICT", layer.at("product"),
                    std::string("\"product\" applies to the product kinds (maximum, arrival, "
                                "duration, hazard), not to a ") +
                        layerKindName(kind) + " layer");
        return;
    }
    const bool thresholded = kind == LayerKind::Arrival || kind == LayerKind::Duration;
    if (!j) {
        if (thresholded)
            c.error("SCENARIO_MISSING", l.pointer,
                    std::string(kind == LayerKind::Arrival ? "an " : "a ") + layerKindName(kind) +
                        " layer needs \"product\": {\"threshold\": ...} (in the sequence's units)");
        return;
    }
    Obj o(c, *j, layer.at("product"), "Product");
    if (!o.valid()) return;
    auto only = [&](const char* key, bool allowed, const char* kinds) {
        if (o.has(key) && !allowed)
            c.error("SCENARIO_CONFLICT", o.at(key),
                    std::string("\"") + key + "\" applies to " + kinds + " layers only");
    };
    only("threshold", thresholded, "arrival and duration");
    only("units", thresholded, "arrival and duration");
    only("timeUnits", thresholded, "arrival and duration");
    only("isochrones", kind == LayerKind::Arrival, "arrival");
    only("velocity", kind == LayerKind::Hazard, "hazard");
    if (thresholded) {
        if (auto t = o.num("threshold", kDataValue, true)) {
            l.product.threshold = *t;
            l.product.hasThreshold = true;
        }
        assign(l.product.units, o.name("units"));
        assign(l.product.timeUnits, o.oneOf("timeUnits", kTimeUnits));
    }
    if (kind == LayerKind::Arrival) assign(l.product.isochrones, o.num("isochrones", kDataStep));
    if (kind == LayerKind::Hazard) assign(l.product.velocity, o.name("velocity"));
}

}  // namespace kiosk::config::reader
