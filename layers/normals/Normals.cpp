#include "layers/normals/Normals.h"

#include <string>

namespace kiosk::layers {
namespace {

// Kept in step with its C++ mirror render::hybridGeometryWeight (NormalShadingGLTest checks
// the two agree on rendered pixels).
constexpr const char* kHelpers = R"(uniform float uTauTex;

// Mean encoded normal of the valid texels under the filter: nodata texels are all zero, so the
// filtered rgb is premultiplied by the filtered alpha.
vec3 decodeNormalTexel(vec4 t) {
    vec3 n = t.rgb / max(t.a, 1.0 / 255.0) * 2.0 - 1.0;
    n.xy *= uVerticalScale;
    return normalize(n + vec3(0.0, 0.0, 1e-6));
}

// Texels of level 0 per screen pixel, from the derivatives of the texel coordinate.
float texelsPerPixel(vec2 texelCoord) {
    return max(length(dFdx(texelCoord)), length(dFdy(texelCoord)));
}

// 0: texture shading; 1: geometry shading, over one octave of texel magnification.
float hybridGeometryWeight(float texelsPerPx, float tau) {
    if (tau <= 0.0 || texelsPerPx <= 0.0) return 0.0;
    return smoothstep(0.0, 1.0, log2(1.0 / (texelsPerPx * tau)));
}

// Magnified (level 0): bilinear filtering in float from four fetches, because 8-bit texture
// filtering (llvmpipe, many GPUs) rounds the filtered normal to 8 bits, which alone costs up
// to 1.5 DN of Lambert. Minified: the mipmapped hardware filter, sampled before the branch
// (uniform control flow, so implicit derivatives are valid): llvmpipe runs both sides of the
// branch anyway, and its implicit-derivative path picks one mip level per quad where
// textureGrad picked one per pixel (the normals layer was 40 % of the demo's frame).
vec4 sampleNormalMap(sampler2D s, vec2 uv, float texelsPerPx) {
    vec4 minified = texture(s, uv);
    if (texelsPerPx > 1.0) return minified;
    ivec2 size = textureSize(s, 0);
    vec2 f = uv * vec2(size) - 0.5;
    vec2 i0 = floor(f);
    vec2 a = f - i0;
    ivec2 p0 = clamp(ivec2(i0), ivec2(0), size - 1);
    ivec2 p1 = clamp(ivec2(i0) + 1, ivec2(0), size - 1);
    vec4 t00 = texelFetch(s, p0, 0), t10 = texelFetch(s, ivec2(p1.x, p0.y), 0);
    vec4 t01 = texelFetch(s, ivec2(p0.x, p1.y), 0), t11 = texelFetch(s, p1, 0);
    return mix(mix(t00, t10, a.x), mix(t01, t11, a.x), a.y);
}
)";

class NormalsShader : public LayerShader {
public:
    const char* helpers() const override { return kHelpers; }
    void sample(std::ostream& s, int i, int) const override {
        const std::string n = std::to_string(i), uv = "uv" + n, tex = "uLayer" + n;
        s << "    vec4 L" << n << ";\n    {\n"
          << "        float tpp = texelsPerPixel(" << uv << " * vec2(textureSize(" << tex
          << ", 0)));\n"
          << "        vec4 t = sampleNormalMap(" << tex << ", " << uv << ", tpp);\n"
          << "        float sT = lambert(decodeNormalTexel(t), uLightDir, uAmbient);\n"
          << "        float sG = lambert(vNormal, uLightDir, uAmbient);\n"
          << "        float g = hybridGeometryWeight(tpp, uTauTex);\n"
          << "        L" << n << " = vec4(vec3(mix(sT, sG, g)), t.a);\n    }\n";
    }
};

}  // namespace

std::shared_ptr<const LayerShader> NormalsKind::shader(const SourcePlan&) const {
    static const auto piece = std::make_shared<NormalsShader>();
    return piece;
}

}  // namespace kiosk::layers
