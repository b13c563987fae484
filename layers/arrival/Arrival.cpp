#include "layers/arrival/Arrival.h"

#include "layers/ScalarSource.h"
#include "layers/products/Derivations.h"
#include "layers/products/ProductSource.h"

namespace kiosk::layers {
namespace {

class ArrivalShader : public LayerShader {
public:
    ArrivalShader(double threshold, double isochrones)
        : mThreshold(products::ProductSource::literal(threshold)),
          mIsochrones(isochrones > 0 ? products::ProductSource::literal(isochrones) : "") {}
    bool usesLut() const override { return true; }
    bool coloursData() const override { return true; }
    bool productUniform() const override { return true; }
    void sample(std::ostream& s, int i, int lut) const override {
        products::ProductSource::sampleProduct(s, i);
        // Arrived by the pair's first frame: the loader's time. Else, when the value on screen
        // has reached the threshold, the crossing interpolated between the two frames (the
        // loader's rule, so the time does not jump when the next frame becomes the first).
        const std::string& t = mThreshold;
        s << "    vec2 d" << i << " = vec2(0.0);\n"
          << "    if (sv" << i << ") {\n"
          << "        d" << i << " = vec2(S" << i << ", 1.0);\n"
          << "    } else if (cv" << i << ") {\n"
          << "        float f = (" << t << " - v0_" << i << ") / (v1_" << i << " - v0_" << i
          << ");\n"
          << "        if (v0_" << i << " < " << t << " && v1_" << i << " >= " << t << " && f <= al"
          << i << ")\n"
          << "            d" << i << " = vec2(uLayerProduct" << i << ".x + f * uLayerProduct" << i
          << ".y, 1.0);\n"
          << "    }\n";
        if (!mIsochrones.empty()) {
            // Lines where the arrival time crosses a multiple of the interval, about one pixel
            // wide whatever the zoom (screen-space derivative, outside any branch).
            s << "    {\n        float q = d" << i << ".x / " << mIsochrones
              << ";\n        float w = fwidth(q);\n"
              << "        if (abs(fract(q + 0.5) - 0.5) > w) d" << i << " = vec2(0.0);\n    }\n";
        }
        ScalarSource::appendColour(s, i, lut);
    }

private:
    std::string mThreshold, mIsochrones;
};

}  // namespace

std::string ArrivalKind::plan(const config::Layer& layer, const StoreView& store,
                              SourcePlan& out) const {
    if (std::string problem = products::ProductSource::plan(layer, store, out); !problem.empty())
        return problem;
    out.frames = std::make_shared<products::ArrivalTime>(
        layer.product.threshold, products::TimeAxis{out.timeOrigin, out.timeUnit}, layer.nodataAs,
        out.sequence->categorical);
    out.productClock = true;
    out.piece = std::make_shared<ArrivalShader>(layer.product.threshold, layer.product.isochrones);
    return {};
}

std::string ArrivalKind::legendTitle(const config::Layer& layer, const SourcePlan& plan) const {
    return "Arrival (" + products::ProductSource::thresholdText(layer, plan) + "), since start";
}

std::shared_ptr<const LayerShader> ArrivalKind::shader(const SourcePlan& plan) const {
    return plan.piece;
}

}  // namespace kiosk::layers
