#include "layers/ImageryKind.h"

#include <string>

namespace kiosk::layers {

std::string ImageryKind::plan(const config::Layer& layer, const StoreView& store,
                              SourcePlan& out) const {
    const io::LayerInfo* li = store.info.findLayer(layer.source.layer);
    if (!li || li->kind != io::LayerKind::Imagery)
        return "store has no imagery layer \"" + layer.source.layer + "\"";
    out.source = SourceKind::Imagery;
    out.table = li->name;
    out.maxLevel = li->levels - 1;
    return {};
}

void ExpressionShader::sample(std::ostream& s, int i, int) const {
    const std::string n = std::to_string(i);
    const std::string tex = "texture(uLayer" + n + ", uv" + n + ")";
    std::string e = mExpr;
    for (auto p = e.find("$T"); p != std::string::npos; p = e.find("$T", p + tex.size()))
        e.replace(p, 2, tex);
    s << "    vec4 L" << n << " = " << e << ";\n";
}

}  // namespace kiosk::layers
