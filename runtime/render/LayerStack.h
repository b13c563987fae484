#pragma once

#include "layers/LayerShader.h"
#include "runtime/core/Result.h"

#include <memory>
#include <string>
#include <vector>

namespace kiosk::render {

/**
 * @brief The built-in kinds by name, for descriptions built without a scene (tests, tools):
 * a layer whose `shader` is empty takes the registered kind of this name (layers/Registry.cpp).
 * What each kind samples lives in its folder under layers/; the compositor only applies the
 * operations, lenses and mappings to the `vec4 L<i>` a kind defines.
 */
enum class LayerKind { Thematic, Luminance, Topographic, Visibility, Data, Sequence, Normals };

/**
 * @brief How a layer's colour L combines with the colour C accumulated so far (chained in
 * stack order: each result feeds the next layer).
 * - Over:     C = mix(C, L.rgb, L.a * opacity)
 * - Blend:    C = mix(C, L.rgb, V * opacity), V from the referenced visibility layer
 * - Add:      C = C + L.rgb * L.a * weight
 * - Modulate: C = C * mix(1, L.rgb, weight)
 * - Mask:     C = mix(background, C, L.a)   (L from a visibility or any layer's alpha)
 */
enum class LayerOp { Over, Blend, Add, Modulate, Mask };

struct CompositeLayer {
    LayerKind kind = LayerKind::Thematic;
    LayerOp op = LayerOp::Over;
    int visibilityLayer = -1;  ///< index into the stack for Blend
    /**
     * @brief Data layer whose value is the terrain's own elevation (interpolated per fragment
     * from the mesh): hypsometric tinting without a texture. Its uLayer sampler is unused.
     */
    bool fromElevation = false;
    /**
     * @brief Sequence of class data with `interpolate: "arrival"`: a third texture (uLayerT,
     * placed by uLayerRectT) holds per-pixel thresholds in [0, 1] and the value is
     * `alpha >= threshold ? v1 : v0` (the front sweeps across; classes are never blended).
     */
    bool arrival = false;
    /**
     * @brief The kind's GLSL piece (layers/LayerShader.h); empty: the built-in `kind` planned
     * from `fromElevation` / `arrival` (shaderOf()). A scene sets it from the layer's kind.
     */
    std::shared_ptr<const layers::LayerShader> shader{};
    /**
     * @brief Kinds computed from other layers (LayerShader::operands(), e.g. a difference A - B):
     * the stack indices of those layers, sampled before this one.
     */
    std::vector<int> operands{};
};

/** @brief The piece that samples layer `l`: its own, or the built-in kind's. Never null. */
std::shared_ptr<const layers::LayerShader> shaderOf(const CompositeLayer& l);

/**
 * @brief Lens kinds of Döllner §5 / Trapp's focus+context. Comparison: two layer stacks, one
 * drawn only inside the lens (run B, a difference), one only outside (run A).
 */
enum class LensKind { Highlight, Visibility, Comparison };
/** @brief Round: circle or ellipse (uLens = centre, radii); Swipe: the half-plane on one side of
 * a line through the centre (uLensRot = the unit normal pointing inside, uLensParam.x = soft
 * edge in metres). */
enum class LensShape { Round, Swipe };

struct CompositeLens {
    LensKind kind = LensKind::Highlight;
    int insideLayer = -1;   ///< Visibility lens: layer shown inside
    int outsideLayer = -1;  ///< Visibility lens: layer shown outside
    LensShape shape = LensShape::Round;
    std::vector<int> insideLayers{};   ///< Comparison: the stack drawn inside
    std::vector<int> outsideLayers{};  ///< Comparison: the stack drawn outside
};

struct CompositeProgramDesc {
    std::vector<CompositeLayer> layers;
    std::vector<CompositeLens> lenses;
    int lutCount = 0;  ///< distinct LUTs referenced by layers whose kind uses one
    /**
     * @brief Write (scene x, scene y, elevation, 2.0) instead of a colour, into a float target:
     * the fidelity tests measure the rendered surface against the full-resolution data.
     */
    bool outputPosition = false;
    /**
     * @brief Projective mappings the program evaluates per fragment (0: none). When > 0 the
     * shader includes common/mappings.glsl with this capacity: after the layer stack, before
     * lighting and lenses, `C = applyMappings(C, (scenePos, elevation))`. Two more texture units
     * (data array, LUT array); block "Mappings" (see render/MappingSet).
     */
    int mappingCapacity = 0;
    /**
     * @brief false: the base colour is uBaseColor alone and uElevLutWeight is ignored, which
     * saves the elevation LUT fetch per pixel (llvmpipe samples it even at weight 0).
     */
    bool elevationTint = true;
    /**
     * @brief The program of the warped detail grid (render/WarpedGridRenderer, vertex shader
     * warpgrid.vert): procedural bump and texture detail, never where a data layer is valid
     * (render/ProceduralDetailGlsl.h).
     */
    bool proceduralDetail = false;
    /**
     * @brief The quadtree's program when the scene has procedural detail: fragments inside
     * uHole are discarded unless a data layer shows colour there (the detail grid draws the
     * rest; data stays drawn by the data surface, exactly as without detail).
     */
    bool detailHole = false;
};

/**
 * @brief Generate the terrain fragment shader for a layer stack: every layer sampled and
 * combined in ONE pass (no GL calls here; unit-tested on the text, compiled in GL tests).
 * Uniform interface (set by TerrainRenderer per frame / per tile):
 *   uLayer[i]          sampler2D of layer i's texture for the current tile
 *   uLayerB[i]         second texture of kinds sampling a frame pair (LayerShader::textures)
 *   uLayerRect[i]      vec4(originX, originY, 1/sizeX, 1/sizeY): scene metres -> uv
 *   uLayerParam[i]     vec4(opacity or weight, sequence alpha, lut index, valid 0/1)
 *   uLut[k], uLutDomain[k]
 *   uLens[j]           vec4(centreX, centreY, radiusX, radiusY); uLensParam[j] vec4(softEdge,
 *                      inside gain, outside gain, enabled)
 *   uClip              vec4(minX, minY, maxX, maxY) scene metres: fragments outside are
 *                      discarded (an ancestor's mesh drawn for one quadrant while it loads)
 * Fails (RENDER_TOO_MANY_LAYERS) when samplers exceed `maxTextureUnits`; the caller then
 * splits the stack (documented fallback: extra passes).
 */
Result<std::string> generateCompositeShader(const CompositeProgramDesc& desc, int maxTextureUnits);

/** @brief Texture units the program needs (each kind's textures, LUTs, lighting). */
int textureUnitsNeeded(const CompositeProgramDesc& desc);

/**
 * @brief The LUT (uLut[k]) of layer `layer`: its rank among the layers whose kind colours
 * through a LUT, baked into the generated shader as a constant; -1 for other kinds or an index
 * out of range. The
 * program samples no LUT for a layer whose rank is >= lutCount (its colour stays transparent).
 */
int lutIndexOf(const CompositeProgramDesc& desc, int layer);

}  // namespace kiosk::render
