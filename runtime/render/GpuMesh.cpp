#include "runtime/render/GpuMesh.h"

#include <algorithm>
#include <vector>

namespace kiosk::render {

GpuMesh GpuMesh::upload(const MeshData& mesh) {
    return upload(mesh.vertices.data(), mesh.vertices.size(), mesh.indices.data(),
                  mesh.indices.size());
}

GpuMesh GpuMesh::upload(const float* vertices, std::size_t floatCount,
                        const std::uint32_t* indices, std::size_t indexCount) {
    GpuMesh m;
    m.mVao = gl::VertexArray::create();
    m.mVertices = gl::Buffer::create();
    m.mIndices = gl::Buffer::create();
    glBindVertexArray(m.mVao.id());
    glBindBuffer(GL_ARRAY_BUFFER, m.mVertices.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(floatCount * sizeof(float)), vertices,
                 GL_STATIC_DRAW);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.mIndices.id());
    const std::size_t vertexCount = floatCount / MeshData::kFloatsPerVertex;
    if (vertexCount <= 65536) {
        // Most LOD tiles fit 16-bit indices: half the index memory and bandwidth.
        const std::vector<std::uint16_t> shortIndices(indices, indices + indexCount);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indexCount * sizeof(std::uint16_t)),
                     shortIndices.data(), GL_STATIC_DRAW);
        m.mIndexType = GL_UNSIGNED_SHORT;
        m.mIndexSize = 2;
    } else {
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indexCount * sizeof(std::uint32_t)),
                     indices, GL_STATIC_DRAW);
    }
    constexpr GLsizei stride = MeshData::kFloatsPerVertex * sizeof(float);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(3 * sizeof(float)));
    glBindVertexArray(0);
    m.mIndexCount = GLsizei(indexCount);
    m.mBytes = floatCount * sizeof(float) + indexCount * m.mIndexSize;
    return m;
}

void GpuMesh::draw() const {
    if (!valid()) return;  // an invalid resource is skipped, never drawn (sokol rule)
    glBindVertexArray(mVao.id());
    glDrawElements(GL_TRIANGLES, mIndexCount, mIndexType, nullptr);
}

void GpuMesh::drawRange(std::uint32_t firstIndex, std::uint32_t indexCount) const {
    if (!valid() || firstIndex >= std::uint32_t(mIndexCount)) return;
    const std::uint32_t count = std::min(indexCount, std::uint32_t(mIndexCount) - firstIndex);
    if (count == 0) return;
    glBindVertexArray(mVao.id());
    glDrawElements(GL_TRIANGLES, GLsizei(count), mIndexType,
                   reinterpret_cast<const void*>(std::uintptr_t(firstIndex) * mIndexSize));
}

}  // namespace kiosk::render
