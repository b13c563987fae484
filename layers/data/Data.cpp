#include "layers/data/Data.h"

#include "layers/ScalarSource.h"

#include <string>

namespace kiosk::layers {
namespace {

class DataShader : public LayerShader {
public:
    explicit DataShader(bool fromElevation) : mFromElevation(fromElevation) {}
    bool usesLut() const override { return true; }
    // The elevation tint is the terrain itself, not data lying on it: detail may decorate it.
    bool coloursData() const override { return !mFromElevation; }
    void sample(std::ostream& s, int i, int lut) const override {
        if (mFromElevation)
            s << "    vec2 d" << i << " = vec2(vElevation, 1.0);\n";
        else
            s << "    vec2 d" << i << " = texture(uLayer" << i << ", uv" << i << ").rg;\n";
        ScalarSource::appendColour(s, i, lut);
    }

private:
    bool mFromElevation;
};

}  // namespace

std::string DataKind::plan(const config::Layer& layer, const StoreView& store,
                           SourcePlan& out) const {
    if (layer.source.sequence.empty() && layer.source.layer == store.elevation) {
        out.source = SourceKind::MeshElevation;
        out.transfer = layer.transfer;
        return {};
    }
    out.interpolation = anim::Interpolation::None;  // a data layer shows the raw step
    return ScalarSource::plan(layer, store, out);
}

std::shared_ptr<const LayerShader> DataKind::shader(const SourcePlan& plan) const {
    static const auto texture = std::make_shared<DataShader>(false);
    static const auto elevation = std::make_shared<DataShader>(true);
    return plan.source == SourceKind::MeshElevation ? elevation : texture;
}

}  // namespace kiosk::layers
