#include "layers/maximum/Maximum.h"

#include "layers/ScalarSource.h"
#include "layers/products/Derivations.h"
#include "layers/products/ProductSource.h"

namespace kiosk::layers {
namespace {

class MaximumShader : public LayerShader {
public:
    bool usesLut() const override { return true; }
    bool coloursData() const override { return true; }
    void sample(std::ostream& s, int i, int lut) const override {
        products::ProductSource::sampleProduct(s, i);
        // The value on screen (interpolated in data space as the sequence layer does) against
        // the maximum of the frames up to the pair's first.
        s << "    vec2 d" << i << " = vec2(0.0);\n"
          << "    if (sv" << i << " || cv" << i << ")\n"
          << "        d" << i << " = vec2(max(sv" << i << " ? S" << i << " : -3.0e38, cv" << i
          << " ? cur" << i << " : -3.0e38), 1.0);\n";
        ScalarSource::appendColour(s, i, lut);
    }
};

}  // namespace

std::string MaximumKind::plan(const config::Layer& layer, const StoreView& store,
                              SourcePlan& out) const {
    if (std::string problem = products::ProductSource::plan(layer, store, out); !problem.empty())
        return problem;
    out.frames = std::make_shared<products::MaximumSoFar>(layer.nodataAs);
    static const auto piece = std::make_shared<MaximumShader>();
    out.piece = piece;
    return {};
}

std::string MaximumKind::legendTitle(const config::Layer&, const SourcePlan& plan) const {
    return "Maximum " + products::ProductSource::variable(plan) + " so far";
}

std::shared_ptr<const LayerShader> MaximumKind::shader(const SourcePlan& plan) const {
    return plan.piece;
}

}  // namespace kiosk::layers
