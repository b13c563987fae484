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
    // One derived tile per frame: the frame pair is inside it (no second texture).
    out.framePair = false;
    // Class data (burn state) switches at the step; values are interpolated as on screen.
    out.interpolation =
        out.sequence->categorical ? anim::Interpolation::Categorical : anim::Interpolation::Data;
    out.timeOrigin =
        std::isnan(store.timeOrigin) ? out.sequence->frameTimes.front() : store.timeOrigin;
    out.timeUnit = layer.product.unitSeconds();
    out.productClock = true;
    return {};
}

void ProductSource::sampleProduct(std::ostream& s, int i) {
    s << "    vec4 p" << i << " = texture(uLayer" << i << ", uv" << i << ");\n"
      << "    bool sv" << i << " = p" << i << ".a >= 0.5;\n"
      << "    float S" << i << " = p" << i << ".r / max(p" << i << ".a, 1e-6);\n"
      << "    float v0_" << i << " = p" << i << ".g, v1_" << i << " = p" << i << ".b;\n"
      << "    float al" << i << " = uLayerParam" << i
      << ".y;\n"
      // Nodata frames hold -60000 (products::Cumulative::kNoValue). Filtered across a data edge
      // a texel mixes it in: only the fraction of a texel at the edge may colour wrongly (none
      // with nodataAs, e.g. depth 0 for dry land).
      << "    bool cv" << i << " = min(v0_" << i << ", v1_" << i << ") > -1.0e3;\n"
      << "    float cur" << i << " = mix(v0_" << i << ", v1_" << i << ", al" << i << ");\n";
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

bool ProductSource::carriesFramesOf(const config::Layer& product, const config::Layer& sequence,
                                    const std::string& terrainStore) {
    using config::LayerKind;
    const auto store = [&](const config::Layer& l) {
        return l.source.store.empty() ? terrainStore : l.source.store;
    };
    const bool cumulative = product.kind == LayerKind::Maximum ||
                            product.kind == LayerKind::Arrival ||
                            product.kind == LayerKind::Duration;
    // Without nodataAs a sequence layer fades its data edges in (validity is filtered), the
    // product's frames hold a nodata sentinel: only with nodataAs do both show the same values.
    return cumulative && product.enabled && sequence.kind == LayerKind::Sequence &&
           sequence.interpolate == config::SequenceInterpolation::Data && sequence.nodataAs &&
           product.nodataAs == sequence.nodataAs && store(product) == store(sequence) &&
           product.source.sequence == sequence.source.sequence;
}

namespace {

class SequenceFromProduct : public LayerShader {
public:
    int textures() const override { return 1; }  // its unit stays unbound: nothing is sampled
    bool usesLut() const override { return true; }
    bool coloursData() const override { return true; }
    int operands() const override { return 1; }
    void sample(std::ostream& s, int i, int lut) const override {
        s << "    vec2 d" << i << " = vec2(0.0);\n";
        ScalarSource::appendColour(s, i, lut);
    }
    void sampleFrom(std::ostream& s, int i, int lut, const int* operand) const override {
        // The product's frames on screen, interpolated in data space (its cur<a>): what the
        // layer's own frame pair would give, from the texel the product already read.
        const int a = operand[0];
        if (a < 0) return sample(s, i, lut);
        s << "    vec2 d" << i << " = (cv" << a << " && uLayerParam" << a << ".w > 0.5) ? vec2(cur"
          << a << ", 1.0) : vec2(0.0);\n";
        ScalarSource::appendColour(s, i, lut);
    }
};

}  // namespace

std::shared_ptr<const LayerShader> ProductSource::sequenceFromProduct() {
    static const auto piece = std::make_shared<SequenceFromProduct>();
    return piece;
}

std::string ProductSource::literal(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "float(%.9g)", v);
    return buf;
}

}  // namespace kiosk::layers::products
