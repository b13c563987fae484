#include "runtime/render/OcclusionQueries.h"

#include "runtime/gl/ProgramBuilder.h"

namespace kiosk::render {

Result<OcclusionQueries> OcclusionQueries::create() {
    auto program = gl::buildProgram("occlusion.vert", "occlusion.frag");
    if (!program) return program.diagnostics;
    OcclusionQueries q;
    q.mProgram = std::move(*program.value);
    q.mVao = gl::VertexArray::create();
    q.mLocMvp = glGetUniformLocation(q.mProgram.id(), "uModelViewProj");
    q.mLocMin = glGetUniformLocation(q.mProgram.id(), "uBoxMin");
    q.mLocMax = glGetUniformLocation(q.mProgram.id(), "uBoxMax");
    return q;
}

void OcclusionQueries::begin(const math::Camera& camera) {
    mCamera = &camera;
    mProjection = camera.projection();
    mUsed = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &mPrevProgram);
    glGetBooleanv(GL_COLOR_WRITEMASK, mPrevColorMask);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &mPrevDepthMask);
    glUseProgram(mProgram.id());
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);  // a box must not occlude the tiles drawn after it
    glBindVertexArray(mVao.id());
}

std::size_t OcclusionQueries::query(const math::Aabb& box) {
    if (mUsed == mQueries.size()) mQueries.push_back(gl::Query::create());
    const std::size_t slot = mUsed++;
    // Relative to the box's minimum corner: float precision holds for kilometre boxes.
    const glm::mat4 mvp(mProjection * mCamera->view(box.min));
    const glm::vec3 size(box.max - box.min);
    glUniformMatrix4fv(mLocMvp, 1, GL_FALSE, glm::value_ptr(mvp));
    glUniform3f(mLocMin, 0.0f, 0.0f, 0.0f);
    glUniform3f(mLocMax, size.x, size.y, size.z);
    glBeginQuery(GL_ANY_SAMPLES_PASSED_CONSERVATIVE, mQueries[slot].id());
    glDrawArrays(GL_TRIANGLES, 0, 36);
    glEndQuery(GL_ANY_SAMPLES_PASSED_CONSERVATIVE);
    return slot;
}

void OcclusionQueries::end() {
    glBindVertexArray(0);
    glColorMask(mPrevColorMask[0], mPrevColorMask[1], mPrevColorMask[2], mPrevColorMask[3]);
    glDepthMask(mPrevDepthMask);
    glUseProgram(GLuint(mPrevProgram));
    mCamera = nullptr;
}

bool OcclusionQueries::passed(std::size_t slot) const {
    if (slot >= mUsed) return true;  // never asked: draw it
    GLuint any = 1;
    glGetQueryObjectuiv(mQueries[slot].id(), GL_QUERY_RESULT, &any);
    return any != 0;
}

}  // namespace kiosk::render
