#include "runtime/render/ProceduralDetailGlsl.h"

#include "runtime/gl/ShaderLibrary.h"
#include "runtime/render/LayerStack.h"

#include <algorithm>
#include <sstream>

namespace kiosk::render {

std::string ProceduralDetailGlsl::beforePrelude() {
    return "#define vNormal vNormalDetail\n";
}

Result<std::string> ProceduralDetailGlsl::declarations(const CompositeProgramDesc&) {
    auto noise = gl::ShaderLibrary::source("common/detailnoise.glsl");
    if (!noise) return noise.diagnostics;
    std::ostringstream s;
    s << "#undef vNormal\n"
         "vec3 vNormal;  // shading normal, set at the start of main()\n"
         "in vec3 vNormalData;\n"
         "in float vDetailOffset;\n"
         "in vec2 vDetailParam;  // (amplitude, split octave)\n"
         "uniform float uDetailFreq;\n"
         "uniform mat4 uModelViewProj;  // shared with warpgrid.vert\n"
         "uniform vec3 uOrigin;\n"
      << "uniform float uDetailTauTex;\n"
      << *noise << "\n"
      << R"(// Texture detail: octaves from 4 / d0 up, each faded out before it reaches 2 pixels
// (clamping and fading), the whole faded in where a data texel exceeds tauTex on screen.
float detailTexture(vec2 p) {
    float mpp = max(length(fwidth(p)), 1e-4);
    float texelPx = 1.0 / (uDetailFreq * mpp);
    float show = clamp((texelPx - uDetailTauTex) / max(uDetailTauTex, 1e-3), 0.0, 1.0);
    float g = 0.0;
    for (int k = 1; k <= kDetailOctaves; ++k) {
        float freq = uDetailFreq * exp2(float(k + 1));
        float fade = clamp((1.0 / (freq * mpp) - 2.0) * 0.5, 0.0, 1.0);
        g += fade * detailOctaveWeight(k) * detailNoise(p * freq + vec2(17.0, 31.0)).x;
    }
    return 1.0 + 0.18 * show * g;
}
)";
    return s.str();
}

namespace {
bool decoratedOver(const CompositeLayer& l) {
    return shaderOf(l)->coloursData();
}
}  // namespace

std::vector<int> ProceduralDetailGlsl::sampleOrder(const CompositeProgramDesc& desc) {
    std::vector<int> order;
    const int n = int(desc.layers.size());
    for (int pass = 0; pass < 2; ++pass)
        for (int i = 0; i < n; ++i) {
            const bool first = (desc.proceduralDetail || desc.detailHole) &&
                               decoratedOver(desc.layers[std::size_t(i)]);
            if ((pass == 0) == first) order.push_back(i);
        }
    return order;
}

std::size_t ProceduralDetailGlsl::dataLayerCount(const CompositeProgramDesc& desc) {
    if (!desc.proceduralDetail && !desc.detailHole) return 0;
    return std::size_t(std::count_if(desc.layers.begin(), desc.layers.end(), decoratedOver));
}

std::string ProceduralDetailGlsl::afterDataSamples(const CompositeProgramDesc& desc) {
    std::ostringstream s;
    s << "    float dataCover = 0.0;\n";
    for (std::size_t i = 0; i < desc.layers.size(); ++i)
        if (decoratedOver(desc.layers[i]))
            s << "    dataCover = max(dataCover, clamp(L" << i << ".a * uLayerParam" << i
              << ".x * uLayerParam" << i << ".w, 0.0, 1.0));\n";
    if (!desc.proceduralDetail) {
        // The quadtree: inside the hole only what a data layer colours (the grid draws the rest).
        s << "    if (all(greaterThan(vScenePos, uHole.xy)) && all(lessThan(vScenePos, uHole.zw)) "
             "&&\n"
             "        dataCover <= 0.0) discard;\n";
        return s.str();
    }
    // The grid, where a data layer shows: the data surface's normal and a depth pushed below the
    // data surface (the decoration's amplitude and a metre), so the quadtree, which draws the
    // data there exactly as without detail, wins the depth test; the grid only fills what the
    // quadtree leaves (where the displaced and the data surfaces part at a data edge).
    s << "    if (dataCover > 0.0) {\n"
         "        vec4 low = uModelViewProj * vec4(vScenePos - uOrigin.xy,\n"
         "            (vElevation - vDetailParam.x - 1.0) * uVerticalScale - uOrigin.z, 1.0);\n"
         "        gl_FragDepth = clamp(0.5 * low.z / low.w + 0.5, 0.0, 1.0);\n"
         "        vNormal = vNormalData;\n"
         "    } else {\n"
         "        gl_FragDepth = gl_FragCoord.z;\n"
         "        vec3 bump = vDetailParam.x * detailSum(vScenePos, uDetailFreq, vDetailParam.y, "
         "false);\n"
         "        vNormal = normalize(vec3(vNormalDetail.xy / max(vNormalDetail.z, 1e-3) - "
         "bump.yz, 1.0));\n"
         "    }\n";
    return s.str();
}

std::string ProceduralDetailGlsl::beforeLighting() {
    return "    C *= mix(detailTexture(vScenePos), 1.0, step(1e-6, dataCover));\n";
}

}  // namespace kiosk::render
