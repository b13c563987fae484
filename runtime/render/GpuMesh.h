#pragma once

#include "runtime/gl/GlObject.h"
#include "runtime/render/MeshData.h"

namespace kiosk::render {

/** @brief A MeshData uploaded to GL (VAO + vertex + index buffers). Render thread only. */
class GpuMesh {
public:
    GpuMesh() = default;
    static GpuMesh upload(const MeshData& mesh);
    /** @brief Interleaved float3 position + float3 normal vertices, uint32 triangle indices. */
    static GpuMesh upload(const float* vertices, std::size_t floatCount,
                          const std::uint32_t* indices, std::size_t indexCount);

    void draw() const;
    bool valid() const noexcept { return static_cast<bool>(mVao) && mIndexCount > 0; }
    std::size_t triangleCount() const noexcept { return std::size_t(mIndexCount) / 3; }
    std::size_t gpuBytes() const noexcept { return mBytes; }

private:
    gl::VertexArray mVao;
    gl::Buffer mVertices;
    gl::Buffer mIndices;
    GLsizei mIndexCount = 0;
    std::size_t mBytes = 0;
};

}  // namespace kiosk::render
