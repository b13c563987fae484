#pragma once

#include "runtime/core/Result.h"
#include "runtime/gl/GlObject.h"
#include "runtime/math/Camera.h"
#include "runtime/math/Frustum.h"

#include <cstddef>
#include <vector>

namespace kiosk::render {

/**
 * @brief Batches of GLES3 occlusion queries (GL_ANY_SAMPLES_PASSED_CONSERVATIVE) on world
 * boxes against the depth buffer as it is (docs/terrain.md §10). Render thread only.
 *
 * begin() switches to the box program with colour and depth writes off (the depth test and its
 * function stay as the caller set them), query() draws one box inside its own query, end()
 * restores the caller's program and write masks. passed() waits for a result: on llvmpipe the
 * first one flushes and rasterises everything drawn so far.
 */
class OcclusionQueries {
public:
    static Result<OcclusionQueries> create();

    void begin(const math::Camera& camera);
    /** @brief Query the box (world metres, z as drawn); returns its slot in this batch. */
    std::size_t query(const math::Aabb& box);
    void end();
    /** @brief Whether any sample of slot `slot`'s box passed the depth test (waits). */
    bool passed(std::size_t slot) const;
    std::size_t batchSize() const noexcept { return mUsed; }

private:
    gl::Program mProgram;
    gl::VertexArray mVao;             ///< empty: the box comes from gl_VertexID
    std::vector<gl::Query> mQueries;  ///< grows to the largest batch, reused
    std::size_t mUsed = 0;
    const math::Camera* mCamera = nullptr;
    glm::dmat4 mProjection{1.0};
    GLint mLocMvp = -1, mLocMin = -1, mLocMax = -1;
    GLint mPrevProgram = 0;
    GLboolean mPrevColorMask[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
    GLboolean mPrevDepthMask = GL_TRUE;
};

}  // namespace kiosk::render
