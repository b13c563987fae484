#pragma once

#include "runtime/core/Result.h"
#include "runtime/gl/GlObject.h"
#include "runtime/render/TerrainRenderer.h"
#include "runtime/terrain/WarpedGridMesh.h"

#include <cstdint>

namespace kiosk::render {

/**
 * @brief Draws the importance-warped detail grid (terrain::WarpedGridMesh) with the scene's
 * layer stack: the same generated composite program as the quadtree's, built with
 * CompositeProgramDesc::proceduralDetail and the vertex shader warpgrid.vert (procedural
 * displacement). Layers, LUTs, lenses and begin()/end() go through program(). Render thread only.
 */
class WarpedGridRenderer {
public:
    static Result<WarpedGridRenderer> create(CompositeProgramDesc desc, int maxTextureUnits);

    TerrainRenderer& program() noexcept { return mProgram; }
    /** @brief Replace the grid (a dynamic buffer: the warp changes with the view). */
    void upload(const terrain::WarpedGridMesh& mesh);
    /** @brief After program().begin(): data post spacing and tau_tex of the texture detail. */
    void setDetail(double postSpacing, double tauTex);
    /**
     * @brief Draw rows of cells [firstRow, lastRow) and the skirts, keeping fragments inside
     * [clipMin, clipMax] (the tile whose layer textures are bound).
     */
    void draw(int firstRow, int lastRow, const glm::dvec2& clipMin, const glm::dvec2& clipMax);
    bool valid() const noexcept { return mIndexCount > 0; }

private:
    TerrainRenderer mProgram;
    gl::VertexArray mVao;
    gl::Buffer mVertices, mIndices;
    GLint mLocFreq = -1, mLocTau = -1;
    std::vector<std::uint32_t> mRowStart;
    std::uint32_t mIndexCount = 0;
    glm::dvec2 mOrigin{0.0};
};

}  // namespace kiosk::render
