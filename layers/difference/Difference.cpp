#include "layers/difference/Difference.h"

#include "layers/ScalarSource.h"

#include <string>

namespace kiosk::layers {
namespace {

class DifferenceShader : public LayerShader {
public:
    bool usesLut() const override { return true; }
    bool coloursData() const override { return true; }
    int operands() const override { return 2; }
    void sample(std::ostream& s, int i, int lut) const override {
        // Without operands there is nothing to subtract: transparent (never reached through
        // the compositor, which refuses a difference without its two layers).
        s << "    vec2 d" << i << " = vec2(0.0);\n";
        ScalarSource::appendColour(s, i, lut);
    }
    void sampleFrom(std::ostream& s, int i, int lut, const int* operand) const override {
        // The operands' `vec2 d<j>` = (value x validity, validity), as their kinds sampled them
        // (a sequence already interpolated to the data time). A tile without the operand's
        // texture (uLayerParam.w = 0) has no value either.
        const int a = operand[0], b = operand[1];
        if (a < 0 || b < 0) {  // an operand is not drawn (the scene marks this layer FAILED)
            s << "    vec4 L" << i << " = vec4(0.0);\n";
            return;
        }
        s << "    vec2 d" << i << ";\n    {\n"
          << "        float ok = (d" << a << ".g >= 0.5 && d" << b << ".g >= 0.5 && uLayerParam"
          << a << ".w > 0.5 && uLayerParam" << b << ".w > 0.5) ? 1.0 : 0.0;\n"
          << "        float va = d" << a << ".r / max(d" << a << ".g, 1e-6);\n"
          << "        float vb = d" << b << ".r / max(d" << b << ".g, 1e-6);\n"
          << "        d" << i << " = vec2((va - vb) * ok, ok);\n    }\n";
        ScalarSource::appendColour(s, i, lut);
    }
};

}  // namespace

std::string DifferenceKind::plan(const config::Layer& layer, const StoreView&,
                                 SourcePlan& out) const {
    if (layer.operands.size() != 2) return "a difference needs two layers in \"of\"";
    out.source = SourceKind::None;  // computed from A and B in the compositor
    out.transfer = layer.transfer;
    return {};
}

std::string DifferenceKind::legendTitle(const config::Layer& layer, const SourcePlan&) const {
    if (layer.operands.size() != 2) return {};
    return "Difference " + layer.operands[0] + " - " + layer.operands[1];
}

std::shared_ptr<const LayerShader> DifferenceKind::shader(const SourcePlan&) const {
    static const auto piece = std::make_shared<DifferenceShader>();
    return piece;
}

}  // namespace kiosk::layers
