#pragma once

#include "runtime/gl/GlObject.h"
#include "runtime/render/MeshData.h"

namespace kiosk::render {

/** @brief A run of a mesh's indices: [first, first + count). */
struct IndexRun {
    std::uint32_t first = 0;
    std::uint32_t count = 0;
};

/** @brief A MeshData uploaded to GL (VAO + vertex + index buffers). Render thread only. */
class GpuMesh {
public:
    GpuMesh() = default;
    static GpuMesh upload(const MeshData& mesh);
    /** @brief Interleaved float3 position + float3 normal vertices, uint32 triangle indices.
     * Meshes with at most 65536 vertices are stored with 16-bit indices (half the bytes). */
    static GpuMesh upload(const float* vertices, std::size_t floatCount,
                          const std::uint32_t* indices, std::size_t indexCount);

    void draw() const;
    /** @brief Draw `indexCount` indices starting at index `firstIndex` (a run of triangles);
     * a range outside the buffer is clamped to it. */
    void drawRange(std::uint32_t firstIndex, std::uint32_t indexCount) const;
    std::size_t indexCount() const noexcept { return std::size_t(mIndexCount); }
    bool valid() const noexcept { return static_cast<bool>(mVao) && mIndexCount > 0; }
    std::size_t triangleCount() const noexcept { return std::size_t(mIndexCount) / 3; }
    std::size_t gpuBytes() const noexcept { return mBytes; }

private:
    gl::VertexArray mVao;
    gl::Buffer mVertices;
    gl::Buffer mIndices;
    GLsizei mIndexCount = 0;
    GLenum mIndexType = GL_UNSIGNED_INT;
    std::uint32_t mIndexSize = 4;
    std::size_t mBytes = 0;
};

}  // namespace kiosk::render
