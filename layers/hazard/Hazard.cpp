#include "layers/hazard/Hazard.h"

#include "layers/ScalarSource.h"
#include "layers/products/Derivations.h"

namespace kiosk::layers {
namespace {

class HazardShader : public LayerShader {
public:
    bool usesLut() const override { return true; }
    bool coloursData() const override { return true; }
    void sample(std::ostream& s, int i, int lut) const override {
        s << "    vec2 d" << i << " = texture(uLayer" << i << ", uv" << i << ").rg;\n";
        ScalarSource::appendColour(s, i, lut);
    }
};

}  // namespace

std::string HazardKind::plan(const config::Layer& layer, const StoreView& store,
                             SourcePlan& out) const {
    if (std::string problem = ScalarSource::plan(layer, store, out); !problem.empty())
        return problem;
    const std::string& velocity = layer.product.velocity;
    if (!velocity.empty()) {
        const io::SequenceInfo* v = store.info.findSequence(velocity);
        if (!v) return "store has no velocity sequence \"" + velocity + "\"";
        if (v->frameTimes != out.sequence->frameTimes)
            return "velocity sequence \"" + velocity + "\" does not have the frames of \"" +
                   out.sequence->name + "\"";
    }
    out.interpolation = anim::Interpolation::Categorical;
    out.frames = std::make_shared<products::HazardClass>(velocity);
    static const auto piece = std::make_shared<HazardShader>();
    out.piece = piece;
    return {};
}

std::string HazardKind::legendTitle(const config::Layer& layer, const SourcePlan&) const {
    return layer.product.velocity.empty()
               ? "Flood hazard, DEPTH ONLY (no velocity): ARR 2019 depth limits"
               : "Flood hazard ARR 2019 H1-H6 (depth x velocity)";
}

std::shared_ptr<const LayerShader> HazardKind::shader(const SourcePlan& plan) const {
    return plan.piece;
}

}  // namespace kiosk::layers
