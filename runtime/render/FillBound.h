#pragma once

#include "runtime/core/Result.h"
#include "runtime/gl/GlObject.h"

namespace kiosk::render {

/**
 * @brief The llvmpipe fill-rate bound used by every benchmark: a full-screen quad whose
 * fragments do `fetches` dependent texture reads, i.e. the per-pixel work of the terrain pass
 * with no geometry. Frame time / this = how far from the fill bound a renderer is.
 */
class FillBound {
public:
    static Result<FillBound> create(int fetches);
    void draw();

private:
    gl::Program mProgram;
    gl::Texture mTexture;
    gl::VertexArray mVao;
};

}  // namespace kiosk::render
