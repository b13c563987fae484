#pragma once

#include "runtime/core/Result.h"

#include <string>
#include <vector>

namespace kiosk::render {

struct CompositeProgramDesc;

/**
 * @brief The pieces generateCompositeShader splices into the program of the warped detail grid
 * (CompositeProgramDesc::proceduralDetail; docs/terrain.md §7). The layer stack is the same as
 * the quadtree's; what differs:
 *  - where a data or sequence layer shows colour (`dataCover`: its alpha times opacity > 0) the
 *    quadtree (CompositeProgramDesc::detailHole) draws the fragment from the data surface,
 *    exactly as without detail; the grid's fragment there is pushed behind it in depth
 *    (gl_FragDepth) and only fills what the quadtree leaves at a data edge;
 *  - elsewhere the shading normal `vNormal` is a variable: the vertex stage's detailed normal
 *    plus a bump from the octaves the grid does not carry;
 *  - before lighting, texture detail (noise octaves above the data's texel frequency, faded in
 *    where a data texel is larger than tauTex on screen and out near the pixel frequency)
 *    modulates the colour;
 *  - position output writes the displaced elevation.
 * Uniforms: uDetailFreq (1 / post spacing), uDetailTauTex.
 */
struct ProceduralDetailGlsl {
    /** @brief Before the shared prelude: its `in vec3 vNormal` becomes the detailed normal input.
     */
    static std::string beforePrelude();
    /** @brief After the prelude: inputs, uniforms, the noise library and the texture detail. */
    static Result<std::string> declarations(const CompositeProgramDesc& desc);
    /**
     * @brief The order in which the generator emits the layers' samples: data and sequence
     * layers (except the hypsometric tint from the mesh's own elevation) first when
     * `desc.proceduralDetail`, else the stack order.
     */
    static std::vector<int> sampleOrder(const CompositeProgramDesc& desc);
    /** @brief How many layers sampleOrder() puts first (0 without procedural detail). */
    static std::size_t dataLayerCount(const CompositeProgramDesc& desc);
    /**
     * @brief After the data layers' samples, before the others: `dataCover` (how much any
     * data layer colours this fragment); the quadtree's hole test, or the grid's discard and
     * shading normal `vNormal`.
     */
    static std::string afterDataSamples(const CompositeProgramDesc& desc);
    /** @brief Before lighting: the texture detail on the composited colour C. */
    static std::string beforeLighting();
};

}  // namespace kiosk::render
