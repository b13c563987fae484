#pragma once

#include "runtime/mapping/MappingModel.h"
#include "runtime/math/Camera.h"
#include "runtime/math/Frustum.h"

#include <cstdint>
#include <vector>

namespace kiosk::mapping {

/** @brief Why a mapping is or is not evaluated this frame. */
enum class CullResult { Active, Disabled, Frustum, Size, Degenerate };

/** @brief Per-frame counts (docs/cli.md --stats "mappings"). */
struct MappingCounts {
    std::uint32_t active = 0;
    std::uint32_t culledFrustum = 0;
    std::uint32_t culledSize = 0;
    std::uint32_t disabled = 0;      ///< enabled false, zero opacity or degenerate axes
    std::uint32_t overCapacity = 0;  ///< active but beyond what the GPU layout holds
    void clear() { *this = {}; }
    void add(CullResult r);
};

/**
 * @brief The box the mapping can colour: its rectangle swept along N over the terrain's height
 * range [zMin, zMax] (the projector is orthographic and unbounded along N, so whatever terrain
 * lies under the rectangle is covered). For steep planes (|N̂.z| < 0.1) the sweep spans `reach`
 * metres both ways.
 */
math::Aabb footprint(const MappingState& s, double zMin, double zMax, double reach);

/**
 * @brief Trapp & Döllner §4.3 screen-space size: rho = (w / phi) * (|U| |V|) / |O - COP|,
 * with w the horizontal resolution in pixels, phi the horizontal field of view in DEGREES and
 * lengths in the paper's normalised scene ([-1, 1]^3): metres are divided by `sceneScale` (half
 * the scene's largest extent), so the paper's thresholds keep their meaning at any map size.
 */
double screenSizeRho(const MappingState& s, const math::Camera& camera, double sceneScale);

/** @brief Options of the per-frame cull. */
struct CullOptions {
    /** @brief rho below this disables the mapping. The paper suggests ~0.02 for a normalised
     * scene; geokiosk defaults lower so that only mappings of about a pixel drop. */
    double sizeThreshold = 1e-4;
    double zMin = 0.0, zMax = 0.0;  ///< terrain height range
    double sceneScale = 1.0;        ///< half the largest horizontal extent, metres
};

/** @brief Frustum test first, then rho < t (the paper's order). Pure; any thread. */
CullResult cull(const MappingState& s, const math::Camera& camera, const math::Frustum& frustum,
                const CullOptions& options);

}  // namespace kiosk::mapping
