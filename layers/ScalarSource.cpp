#include "layers/ScalarSource.h"

#include <string>

namespace kiosk::layers {

std::string ScalarSource::plan(const config::Layer& layer, const StoreView& store,
                               SourcePlan& out) {
    out.sequence = store.info.findSequence(layer.source.sequence);
    if (!out.sequence) return "store has no sequence \"" + layer.source.sequence + "\"";
    out.source = SourceKind::Sequence;
    out.table = out.sequence->name;
    out.maxLevel = out.sequence->levels - 1;
    out.transfer = layer.transfer;
    return {};
}

void ScalarSource::appendColour(std::ostream& s, int i, int lut) {
    s << "    vec4 L" << i << " = vec4(0.0);\n"
      << "    {\n        float v = d" << i << ".r / max(d" << i << ".g, 1e-6);\n";
    // The LUT index is a per-layer constant baked in by the generator: llvmpipe runs both
    // sides of a branch under a mask, so a run-time `if (k == ...)` chain sampled every LUT for
    // every data layer (docs/terrain.md §6).
    if (lut >= 0) {
        const int k = lut;
        // Out of the domain or without data the coordinate moves onto the LUT's below, above or
        // nodata texel: a scalar select, where selecting the colour costs llvmpipe ~0.7-1.6 ms
        // a layer at 720p (docs/products.md).
        s << "        {\n"
          << "            float x = lutCoordEdged(v, uLutDomain" << k << ", uLutSize" << k << ");\n"
          << "            x = v < uLutDomain" << k << ".x && uLutBelow" << k
          << ".a >= 0.0 ? 0.0 : x;\n"
          << "            x = v > uLutDomain" << k << ".y && uLutAbove" << k
          << ".a >= 0.0 ? lutAboveCoord(uLutSize" << k << ") : x;\n"
          << "            x = d" << i << ".g >= 0.5 ? x : 1.0;\n"
          << "            L" << i << " = texture(uLut" << k << ", vec2(x, 0.5));\n        }\n";
    }
    s << "    }\n";
}

}  // namespace kiosk::layers
