#include "layers/duration/Duration.h"

#include "layers/ScalarSource.h"
#include "layers/products/Derivations.h"
#include "layers/products/ProductSource.h"

namespace kiosk::layers {
namespace {

class DurationShader : public LayerShader {
public:
    explicit DurationShader(double threshold)
        : mThreshold(products::ProductSource::literal(threshold)) {}
    bool usesLut() const override { return true; }
    bool coloursData() const override { return true; }
    bool productUniform() const override { return true; }
    void sample(std::ostream& s, int i, int lut) const override {
        products::ProductSource::sampleProduct(s, i);
        // The loader's duration up to the pair's first frame plus the part of [t0, t] the
        // linear value spends at or above the threshold (the loader's rule for whole steps).
        const std::string& t = mThreshold;
        const std::string n = std::to_string(i);
        const std::string v0 = "v0_" + n, v1 = "v1_" + n, al = "al" + n;
        s << "    vec2 d" << n << " = vec2(0.0);\n"
          << "    {\n"
          << "        float dur = sv" << n << " ? S" << n << " : 0.0;\n"
          << "        if (cv" << n << ") {\n"
          << "            float p = 0.0;\n"
          << "            if (" << v0 << " >= " << t << " && " << v1 << " >= " << t
          << ") p = " << al << ";\n"
          << "            else if ((" << v0 << " >= " << t << ") != (" << v1 << " >= " << t
          << ")) {\n"
          << "                float f = (" << t << " - " << v0 << ") / (" << v1 << " - " << v0
          << ");\n"
          << "                p = " << v0 << " >= " << t << " ? min(" << al << ", f) : max(0.0, "
          << al << " - f);\n"
          << "            }\n"
          << "            dur += p * uLayerProduct" << n << ".y;\n"
          << "        }\n"
          << "        if (sv" << n << " || cv" << n << ") d" << n << " = vec2(dur, 1.0);\n"
          << "    }\n";
        ScalarSource::appendColour(s, i, lut);
    }

private:
    std::string mThreshold;
};

}  // namespace

std::string DurationKind::plan(const config::Layer& layer, const StoreView& store,
                               SourcePlan& out) const {
    if (std::string problem = products::ProductSource::plan(layer, store, out); !problem.empty())
        return problem;
    out.frames = std::make_shared<products::DurationAbove>(
        layer.product.threshold, out.timeUnit, layer.nodataAs, out.sequence->categorical);
    out.productClock = true;
    out.piece = std::make_shared<DurationShader>(layer.product.threshold);
    return {};
}

std::string DurationKind::legendTitle(const config::Layer& layer, const SourcePlan& plan) const {
    return "Time with " + products::ProductSource::thresholdText(layer, plan);
}

std::shared_ptr<const LayerShader> DurationKind::shader(const SourcePlan& plan) const {
    return plan.piece;
}

}  // namespace kiosk::layers
