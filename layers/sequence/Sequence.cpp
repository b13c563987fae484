#include "layers/sequence/Sequence.h"

#include "layers/ScalarSource.h"

#include <string>

namespace kiosk::layers {
namespace {

class SequenceShader : public LayerShader {
public:
    explicit SequenceShader(bool arrival) : mArrival(arrival) {}
    int textures() const override { return mArrival ? 3 : 2; }
    bool usesLut() const override { return true; }
    bool coloursData() const override { return true; }
    void sample(std::ostream& s, int i, int lut) const override {
        s << "    vec2 d" << i << " = texture(uLayer" << i << ", uv" << i << ").rg;\n";
        // Interpolate DATA values, then colour (issue 6): never blend two colours.
        s << "    vec2 e" << i << " = texture(uLayerB" << i << ", uv" << i << ").rg;\n";
        if (mArrival) {
            // Arrival: each pixel switches class when alpha passes its threshold.
            s << "    vec2 t" << i << " = texture(uLayerT" << i << ", (vScenePos - uLayerRectT" << i
              << ".xy) * uLayerRectT" << i << ".zw).rg;\n    d" << i << " = uLayerParam" << i
              << ".y >= t" << i << ".r / max(t" << i << ".g, 1e-6) ? e" << i << " : d" << i
              << ";\n";
        } else {
            s << "    d" << i << " = mix(d" << i << ", e" << i << ", uLayerParam" << i << ".y);\n";
        }
        ScalarSource::appendColour(s, i, lut);
    }

private:
    bool mArrival;
};

}  // namespace

std::string SequenceKind::plan(const config::Layer& layer, const StoreView& store,
                               SourcePlan& out) const {
    if (std::string problem = ScalarSource::plan(layer, store, out); !problem.empty())
        return problem;
    out.framePair = true;
    switch (layer.interpolate) {
        case config::SequenceInterpolation::None:
            out.interpolation = anim::Interpolation::None;
            break;
        case config::SequenceInterpolation::Arrival:
            out.interpolation = anim::Interpolation::Arrival;
            out.thresholds = true;
            break;
        case config::SequenceInterpolation::Data:
            // Class data (burn state) is never blended, whatever the author asked.
            out.interpolation = out.sequence->categorical ? anim::Interpolation::Categorical
                                                          : anim::Interpolation::Data;
            break;
    }
    return {};
}

std::shared_ptr<const LayerShader> SequenceKind::shader(const SourcePlan& plan) const {
    static const auto blended = std::make_shared<SequenceShader>(false);
    static const auto arrival = std::make_shared<SequenceShader>(true);
    return plan.thresholds ? arrival : blended;
}

}  // namespace kiosk::layers
