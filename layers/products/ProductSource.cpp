#include "layers/products/ProductSource.h"

#include "layers/ScalarSource.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace kiosk::layers::products {

std::string ProductSource::plan(const config::Layer& layer, const StoreView& store,
                                SourcePlan& out) {
    if (std::string problem = ScalarSource::plan(layer, store, out); !problem.empty())
        return problem;
    if (out.sequence->frameTimes.empty())
        return "sequence \"" + out.sequence->name + "\" has no frames";
    out.framePair = true;
    // Class data (burn state) switches at the step; values are interpolated as on screen.
    out.interpolation =
        out.sequence->categorical ? anim::Interpolation::Categorical : anim::Interpolation::Data;
    out.timeOrigin =
        std::isnan(store.timeOrigin) ? out.sequence->frameTimes.front() : store.timeOrigin;
    out.timeUnit = layer.product.unitSeconds();
    return {};
}

const char* ProductSource::helpers() {
    return "// Derived products (layers/products/): a (value x validity, validity) texel.\n"
           "bool prodValid(vec2 d) { return d.g >= 0.5; }\n"
           "float prodValue(vec2 d) { return d.r / max(d.g, 1e-6); }\n";
}

void ProductSource::samplePair(std::ostream& s, int i) {
    s << "    vec2 a" << i << " = texture(uLayer" << i << ", uv" << i << ").rg;\n"
      << "    vec2 b" << i << " = texture(uLayerB" << i << ", uv" << i << ").rg;\n"
      << "    vec2 s" << i << " = texture(uLayerT" << i << ", (vScenePos - uLayerRectT" << i
      << ".xy) * uLayerRectT" << i << ".zw).rg;\n"
      << "    float al" << i << " = uLayerParam" << i << ".y;\n";
}

std::string ProductSource::variable(const SourcePlan& plan) {
    if (!plan.sequence) return {};
    return plan.sequence->variable.empty() ? plan.sequence->name : plan.sequence->variable;
}

std::string ProductSource::thresholdText(const config::Layer& layer, const SourcePlan& plan) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%g", layer.product.threshold);
    std::string units = plan.sequence ? plan.sequence->units : std::string();
    if (units == "class") units.clear();
    return variable(plan) + " >= " + buf + (units.empty() ? "" : " " + units);
}

std::string ProductSource::literal(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "float(%.9g)", v);
    return buf;
}

}  // namespace kiosk::layers::products
