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
    int textures() const override { return 3; }
    bool usesLut() const override { return true; }
    bool coloursData() const override { return true; }
    bool productUniform() const override { return true; }
    const char* helpers() const override { return products::ProductSource::helpers(); }
    void sample(std::ostream& s, int i, int lut) const override {
        products::ProductSource::samplePair(s, i);
        // The loader's duration up to the pair's first frame plus the part of [t0, t] the
        // linear value spends at or above the threshold (the loader's rule for whole steps).
        const std::string& t = mThreshold;
        s << "    vec2 d" << i << " = vec2(0.0);\n"
          << "    {\n"
          << "        float dur = prodValid(s" << i << ") ? prodValue(s" << i << ") : 0.0;\n"
          << "        if (prodValid(a" << i << ") && prodValid(b" << i << ")) {\n"
          << "            float v0 = prodValue(a" << i << "), v1 = prodValue(b" << i << ");\n"
          << "            float p = 0.0;\n"
          << "            if (v0 >= " << t << " && v1 >= " << t << ") p = al" << i << ";\n"
          << "            else if ((v0 >= " << t << ") != (v1 >= " << t << ")) {\n"
          << "                float f = (" << t << " - v0) / (v1 - v0);\n"
          << "                p = v0 >= " << t << " ? min(al" << i << ", f) : max(0.0, al" << i
          << " - f);\n"
          << "            }\n"
          << "            dur += p * uLayerProduct" << i << ".y;\n"
          << "        }\n"
          << "        if (prodValid(s" << i << ") || prodValid(a" << i << ")) d" << i
          << " = vec2(dur, 1.0);\n"
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
    out.state = std::make_shared<products::DurationAbove>(layer.product.threshold, out.timeUnit);
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
