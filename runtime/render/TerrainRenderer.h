#pragma once

#include <cstdint>

#include "runtime/core/Result.h"
#include "runtime/gl/GlObject.h"
#include "runtime/math/Camera.h"
#include "runtime/render/GpuMesh.h"

namespace kiosk::render {

/** @brief Unit vector towards the sun from azimuth (deg clockwise from north) and altitude. */
glm::vec3 sunDirection(double azimuthDeg, double altitudeDeg);

struct TerrainStyle {
    glm::vec3 lightDir{0.0f, 0.0f, 1.0f};  ///< towards the light, unit
    float ambient = 0.3f;
    float verticalScale = 1.0f;
    float drapeWeight = 0.0f;  ///< 0 colour ramp only .. 1 imagery only
};

/** @brief Per-frame counters the stats record reports (docs/cli.md --stats). */
struct DrawCounters {
    std::uint32_t tilesDrawn = 0;
    std::uint64_t triangles = 0;
    std::uint32_t tilesFromAncestor = 0;
    void clear() { *this = {}; }
};

/**
 * @brief Draws terrain meshes coloured by an elevation LUT (and optionally an imagery drape),
 * lit by a directional sun. Render thread only. Each tile's matrix is built in double relative
 * to its origin, so vertex data stays small floats.
 */
class TerrainRenderer {
public:
    static Result<TerrainRenderer> create();

    /** @brief LUT texels whose first/last texel centres map to domainMin/domainMax metres. */
    void setLut(int size, const std::uint8_t* rgba, float domainMin, float domainMax);
    /** @brief Imagery stretched over the scene rectangle [extentMin, extentMax] (metres). */
    void setDrape(int width, int height, const std::uint8_t* rgba, glm::dvec2 extentMin,
                  glm::dvec2 extentMax);

    /** @brief Bind program and state for a frame seen by `camera`. */
    void begin(const math::Camera& camera, const TerrainStyle& style);
    /** @brief Draw one mesh whose vertex positions are relative to `origin` (scene metres). */
    void draw(const GpuMesh& mesh, const glm::dvec3& origin, bool fromAncestor = false);
    void end();

    DrawCounters& counters() noexcept { return mCounters; }

private:
    gl::Program mProgram;
    gl::Texture mLut;
    gl::Texture mDrape;
    float mLutSize = 1.0f;
    glm::vec2 mLutDomain{0.0f, 1.0f};
    glm::dvec2 mExtentMin{0.0}, mExtentMax{1.0};
    glm::dmat4 mProjection{1.0};
    const math::Camera* mCamera = nullptr;
    GLint mLocMvp = -1, mLocOrigin = -1, mLocExtentMin = -1, mLocExtentSize = -1,
          mLocVScale = -1, mLocLut = -1, mLocLutSize = -1, mLocLutDomain = -1, mLocDrape = -1,
          mLocDrapeWeight = -1, mLocLight = -1, mLocAmbient = -1;
    DrawCounters mCounters;
};

}  // namespace kiosk::render
