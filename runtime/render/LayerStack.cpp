#include "runtime/render/LayerStack.h"

#include "layers/Registry.h"
#include "runtime/gl/ShaderLibrary.h"
#include "runtime/render/ProceduralDetailGlsl.h"

#include <algorithm>
#include <cstdio>
#include <set>
#include <sstream>

namespace kiosk::render {
namespace {

// Text shared by every generated program: inputs, lighting and LUT helpers. Kept here rather
// than in runtime/shaders because it is spliced around generated code.
constexpr const char* kPrelude = R"(precision highp float;
precision highp sampler2D;

in vec3 vNormal;
in float vElevation;
in vec2 vScenePos;

uniform vec3 uLightDir;
uniform float uAmbient;
uniform float uVerticalScale;     // shared with the vertex shader (normal maps, detail)
uniform float uGeometryLighting;  // 1: Lambert from mesh normals; 0: shading comes from layers
uniform vec4 uBaseColor;
uniform sampler2D uElevLut;
uniform vec2 uElevLutDomain;
uniform float uElevLutSize;
uniform float uElevLutWeight;      // 0: uBaseColor, 1: hypsometric tint
uniform vec4 uClip;
uniform vec4 uHole;  // scene rectangle drawn by the warped detail grid instead (empty: none)

out vec4 fragColor;

float lensMask(vec4 lens, vec2 rotation, float softEdge, vec2 p) {
    vec2 q = p - lens.xy;
    // Into the ellipse's frame: rotation = (cos, sin) of its counter-clockwise angle.
    q = vec2(rotation.x * q.x + rotation.y * q.y, -rotation.y * q.x + rotation.x * q.y);
    vec2 d = q / max(lens.zw, vec2(1e-6));
    float r = length(d);
    float edge = max(softEdge, 1e-6);
    return 1.0 - smoothstep(1.0 - edge, 1.0, r);
}
)";

// Swipe lens: the half-plane the unit `normal` points into, blended over `softEdge` metres.
constexpr const char* kSwipeMask =
    R"(float swipeMask(vec4 lens, vec2 normal, float softEdge, vec2 p) {
    float e = 0.5 * max(softEdge, 1e-6);
    return smoothstep(-e, e, dot(p - lens.xy, normal));
}
)";

// A double as a GLSL float literal that keeps its value (locale-independent).
std::string glslFloat(double v) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "float(%.9g)", v);
    return buf;
}

bool contains(const std::vector<int>& v, int i) {
    return std::find(v.begin(), v.end(), i) != v.end();
}

const char* builtinKindName(LayerKind k) {
    // Names only (the kinds are in layers/): descriptions built without a scene use them.
    static constexpr const char* kNames[] = {"thematic", "luminance", "topographic", "visibility",
                                             "data",     "sequence",  "normals"};
    return kNames[static_cast<int>(k)];
}

}  // namespace

std::shared_ptr<const layers::LayerShader> shaderOf(const CompositeLayer& l) {
    if (l.shader) return l.shader;
    const layers::Kind* kind = layers::registry().find(builtinKindName(l.kind));
    layers::SourcePlan plan;
    plan.source = l.fromElevation ? layers::SourceKind::MeshElevation : layers::SourceKind::Imagery;
    plan.framePair = l.kind == LayerKind::Sequence;
    plan.thresholds = l.arrival;
    return kind->shader(plan);
}

int lutIndexOf(const CompositeProgramDesc& desc, int layer) {
    if (layer < 0 || layer >= int(desc.layers.size())) return -1;
    const auto scalar = [](const CompositeLayer& l) { return shaderOf(l)->usesLut(); };
    if (!scalar(desc.layers[std::size_t(layer)])) return -1;
    int rank = 0;
    for (int i = 0; i < layer; ++i) rank += scalar(desc.layers[std::size_t(i)]) ? 1 : 0;
    return rank;
}

int textureUnitsNeeded(const CompositeProgramDesc& desc) {
    int units = 1 + desc.lutCount;  // elevation LUT + transfer-function LUTs
    for (const auto& l : desc.layers) units += shaderOf(l)->textures();
    if (desc.mappingCapacity > 0) units += 2;  // mapping data + LUT arrays
    return units;
}

Result<std::string> generateCompositeShader(const CompositeProgramDesc& desc,
                                            int maxTextureUnits) {
    Diagnostics diags;
    const int units = textureUnitsNeeded(desc);
    if (units > maxTextureUnits) {
        diags.error("RENDER_TOO_MANY_LAYERS", "", "",
                    "layer stack needs " + std::to_string(units) + " texture units, the GPU has " +
                        std::to_string(maxTextureUnits));
        return diags;
    }
    const int n = static_cast<int>(desc.layers.size());
    for (int i = 0; i < n; ++i) {
        const auto& l = desc.layers[std::size_t(i)];
        if (l.op == LayerOp::Blend &&
            (l.visibilityLayer < 0 || l.visibilityLayer >= n || l.visibilityLayer == i)) {
            diags.error("RENDER_BAD_BLEND", "", "layer " + std::to_string(i),
                        "blend needs another layer of the stack as its visibility source");
        }
    }
    for (int i = 0; i < n; ++i) {
        const auto& l = desc.layers[std::size_t(i)];
        const int want = shaderOf(l)->operands();
        bool ok = int(l.operands.size()) == want;
        // -1: an operand that is not in the stack (the layer then draws nothing).
        for (int o : l.operands)
            ok = ok && o >= -1 && o < n && o != i &&
                 (o < 0 || shaderOf(desc.layers[std::size_t(o)])->operands() == 0);
        if (!ok)
            diags.error("RENDER_BAD_OPERANDS", "", "layer " + std::to_string(i),
                        "needs " + std::to_string(want) +
                            " other layers of the stack (not computed ones) as its operands");
    }
    if (diags.hasErrors()) return diags;

    // Shared helpers come from the shader library so the GLSL and its C++ mirror
    // (color::lutCoordinate) have one source of truth.
    std::ostringstream s;
    s << "#version 300 es\n";
    if (desc.proceduralDetail) s << ProceduralDetailGlsl::beforePrelude();
    s << kPrelude;
    if (desc.proceduralDetail) {
        auto detail = ProceduralDetailGlsl::declarations(desc);
        if (!detail) return detail.diagnostics;
        s << *detail;
    }
    for (const char* lib : {"common/encode.glsl", "common/lighting.glsl"}) {
        auto text = gl::ShaderLibrary::source(lib);
        if (!text) return text.diagnostics;
        s << *text << "\n";
    }
    // Each kind's piece, resolved once; helpers shared by several layers of a kind go in once.
    std::vector<std::shared_ptr<const layers::LayerShader>> pieces;
    for (const auto& l : desc.layers) pieces.push_back(shaderOf(l));
    std::set<const char*> helpersDone;
    for (const auto& piece : pieces)
        if (const char* h = piece->helpers(); h && helpersDone.insert(h).second) s << h;
    if (std::any_of(desc.lenses.begin(), desc.lenses.end(),
                    [](const CompositeLens& l) { return l.shape == LensShape::Swipe; }))
        s << kSwipeMask;
    if (desc.mappingCapacity > 0) {
        auto text = gl::ShaderLibrary::source("common/mappings.glsl");
        if (!text) return text.diagnostics;
        s << "#define KIOSK_MAX_MAPPINGS " << desc.mappingCapacity << "\n";
        if (!desc.mappingInputs.empty())
            s << "#define KIOSK_MAP_INPUTS " << desc.mappingInputs.size() << "\n";
        s << *text << "\n";
    }
    for (int i = 0; i < n; ++i) {
        const int textures = pieces[std::size_t(i)]->textures();
        s << "uniform sampler2D uLayer" << i << ";\n";
        if (textures >= 2) s << "uniform sampler2D uLayerB" << i << ";\n";
        if (textures >= 3)
            s << "uniform sampler2D uLayerT" << i << ";\nuniform vec4 uLayerRectT" << i << ";\n";
        s << "uniform vec4 uLayerRect" << i << ";\nuniform vec4 uLayerParam" << i << ";\n";
        if (pieces[std::size_t(i)]->productUniform())
            s << "uniform vec4 uLayerProduct" << i << ";\n";
    }
    for (int k = 0; k < desc.lutCount; ++k) {
        s << "uniform sampler2D uLut" << k << ";\nuniform vec2 uLutDomain" << k
          << ";\nuniform float uLutSize" << k << ";\nuniform vec4 uLutBelow" << k
          << ";\nuniform vec4 uLutAbove" << k << ";\n";
    }
    for (std::size_t j = 0; j < desc.lenses.size(); ++j)
        s << "uniform vec4 uLens" << j << ";\nuniform vec4 uLensParam" << j
          << ";\nuniform vec2 uLensRot" << j << ";\n";

    s << "\nvoid main() {\n"
         "    if (any(lessThan(vScenePos, uClip.xy)) || any(greaterThan(vScenePos, uClip.zw))) "
         "discard;\n"
         << (desc.elevationTint
                 ? "    vec3 C = mix(uBaseColor.rgb, texture(uElevLut, vec2(lutCoord(vElevation, "
                   "uElevLutDomain, uElevLutSize), 0.5)).rgb, uElevLutWeight);\n"
                 : "    vec3 C = uBaseColor.rgb;\n")
         << "    vec3 background = C;\n";
    // Lens masks first: visibility lenses gate whole layers.
    for (std::size_t j = 0; j < desc.lenses.size(); ++j)
        s << "    float lens" << j << " = uLensParam" << j << ".w * "
          << (desc.lenses[j].shape == LensShape::Swipe ? "swipeMask" : "lensMask") << "(uLens" << j
          << ", uLensRot" << j << ", uLensParam" << j << ".x, vScenePos);\n";
    // Every layer's sample is computed up front so Blend can reference any visibility layer.
    // (Procedural detail samples data layers first: the shading normal depends on them.)
    std::vector<int> order = ProceduralDetailGlsl::sampleOrder(desc);
    const std::size_t dataFirst = ProceduralDetailGlsl::dataLayerCount(desc);
    // Layers computed from others (a difference) come after them, within the same part.
    const auto plain = [&](int i) { return pieces[std::size_t(i)]->operands() == 0; };
    std::stable_partition(order.begin(), order.begin() + std::ptrdiff_t(dataFirst), plain);
    std::stable_partition(order.begin() + std::ptrdiff_t(dataFirst), order.end(), plain);
    for (std::size_t o = 0; o < order.size(); ++o) {
        if ((desc.proceduralDetail || desc.detailHole) && o == dataFirst)
            s << ProceduralDetailGlsl::afterDataSamples(desc);
        const int i = order[o];
        s << "    vec2 uv" << i << " = (vScenePos - uLayerRect" << i << ".xy) * uLayerRect" << i
          << ".zw;\n";
        // The kind defines L<i>; a LUT index past lutCount leaves the layer transparent.
        const int k = lutIndexOf(desc, i);
        const auto& piece = *pieces[std::size_t(i)];
        if (piece.operands() > 0)
            piece.sampleFrom(s, i, k < desc.lutCount ? k : -1,
                             desc.layers[std::size_t(i)].operands.data());
        else
            piece.sample(s, i, k < desc.lutCount ? k : -1);
    }
    if ((desc.proceduralDetail || desc.detailHole) && dataFirst == order.size())
        s << ProceduralDetailGlsl::afterDataSamples(desc);
    for (int i = 0; i < n; ++i) {
        const auto& l = desc.layers[std::size_t(i)];
        if (pieces[std::size_t(i)]->maskOnly() && l.op == LayerOp::Over) continue;  // mask source
        s << "    {\n        float w = uLayerParam" << i << ".x * uLayerParam" << i << ".w;\n";
        for (std::size_t j = 0; j < desc.lenses.size(); ++j) {
            const auto& lens = desc.lenses[j];
            if (lens.kind == LensKind::Comparison) {
                // Two stacks, one on each side of the lens at the same data time.
                if (contains(lens.insideLayers, i)) s << "        w *= lens" << j << ";\n";
                if (contains(lens.outsideLayers, i)) s << "        w *= 1.0 - lens" << j << ";\n";
            }
            if (lens.kind != LensKind::Visibility) continue;
            if (lens.insideLayer == i) s << "        w *= lens" << j << ";\n";
            if (lens.outsideLayer == i) s << "        w *= 1.0 - lens" << j << ";\n";
        }
        const std::string L = "L" + std::to_string(i);
        switch (l.op) {
            case LayerOp::Over:
                s << "        C = mix(C, " << L << ".rgb, clamp(" << L << ".a * w, 0.0, 1.0));\n";
                break;
            case LayerOp::Blend:
                s << "        C = mix(C, " << L << ".rgb, clamp(L" << l.visibilityLayer << ".a * "
                  << L << ".a * w, 0.0, 1.0));\n";
                break;
            case LayerOp::Add:
                s << "        C = C + " << L << ".rgb * " << L << ".a * w;\n";
                break;
            case LayerOp::Modulate:
                s << "        C = C * mix(vec3(1.0), " << L << ".rgb, clamp(" << L
                  << ".a * w, 0.0, 1.0));\n";
                break;
            case LayerOp::Mask:
                s << "        C = mix(C, background, clamp((1.0 - " << L
                  << ".a) * w, 0.0, 1.0));\n";
                break;
        }
        s << "    }\n";
    }
    // Mappings draw on the composited stack and are lit with it (docs/projective-mappings.md).
    if (desc.mappingCapacity > 0) {
        // Live mapping inputs: a stack layer's value where it has one, else nodata.
        for (std::size_t k = 0; k < desc.mappingInputs.size(); ++k) {
            const auto& in = desc.mappingInputs[k];
            const bool scalar =
                in.layer >= 0 && in.layer < n && pieces[std::size_t(in.layer)]->usesLut();
            s << "    gMapInput[" << k << "] = ";
            if (scalar)
                s << "mapInputOf(d" << in.layer << ", uLayerParam" << in.layer << ".w, vec2("
                  << glslFloat(in.domainMin) << ", " << glslFloat(in.domainMax) << "));\n";
            else
                s << "vec2(0.0);\n";
        }
        s << "    C = applyMappings(C, vec3(vScenePos, vElevation));\n";
    }
    if (desc.proceduralDetail) s << ProceduralDetailGlsl::beforeLighting();
    s << "    C *= mix(1.0, lambert(vNormal, uLightDir, uAmbient), uGeometryLighting);\n";
    for (std::size_t j = 0; j < desc.lenses.size(); ++j) {
        if (desc.lenses[j].kind != LensKind::Highlight) continue;
        // Highlight lens: luminance raised inside, lowered outside, soft edge.
        s << "    C *= mix(mix(1.0, uLensParam" << j << ".z, uLensParam" << j << ".w), uLensParam"
          << j << ".y, lens" << j << ");\n";
    }
    for (std::size_t j = 0; j < desc.lenses.size(); ++j) {
        if (desc.lenses[j].kind != LensKind::Comparison) continue;
        // Where the two stacks meet: a thin light line about 1.5 pixels wide along the mask's
        // half-way level (screen-space derivative), so a viewer sees where the lens is.
        s << "    C = mix(C, vec3(0.96), 0.85 * uLensParam" << j
          << ".w * (1.0 - smoothstep(0.0, 1.5 * fwidth(lens" << j << ") + 1e-4, abs(lens" << j
          << " - 0.5 * uLensParam" << j << ".w))));\n";
    }
    if (desc.outputPosition && desc.proceduralDetail)  // the displaced surface
        s << "    fragColor = vec4(vScenePos, vElevation + vDetailOffset, 2.0);\n}\n";
    else if (desc.outputPosition)
        s << "    fragColor = vec4(vScenePos, vElevation, 2.0);\n}\n";
    else
        s << "    fragColor = vec4(clamp(C, 0.0, 1.0), 1.0);\n}\n";
    return s.str();
}

}  // namespace kiosk::render
