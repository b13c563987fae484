#include "runtime/render/WarpedGridRenderer.h"

#include <algorithm>

namespace kiosk::render {

Result<WarpedGridRenderer> WarpedGridRenderer::create(CompositeProgramDesc desc,
                                                      int maxTextureUnits) {
    desc.proceduralDetail = true;
    desc.detailHole = false;
    auto program = TerrainRenderer::create(desc, maxTextureUnits, "warpgrid.vert");
    if (!program) return program.diagnostics;
    WarpedGridRenderer r;
    r.mProgram = std::move(*program.value);
    r.mLocFreq = glGetUniformLocation(r.mProgram.programId(), "uDetailFreq");
    r.mLocTau = glGetUniformLocation(r.mProgram.programId(), "uDetailTauTex");
    r.mVao = gl::VertexArray::create();
    r.mVertices = gl::Buffer::create();
    r.mIndices = gl::Buffer::create();
    glBindVertexArray(r.mVao.id());
    glBindBuffer(GL_ARRAY_BUFFER, r.mVertices.id());
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r.mIndices.id());
    constexpr GLsizei stride = terrain::WarpedGridMesh::kFloatsPerVertex * sizeof(float);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(3 * sizeof(float)));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(6 * sizeof(float)));
    glBindVertexArray(0);
    return r;
}

void WarpedGridRenderer::upload(const terrain::WarpedGridMesh& mesh) {
    glBindVertexArray(mVao.id());
    glBindBuffer(GL_ARRAY_BUFFER, mVertices.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(mesh.vertices.size() * sizeof(float)),
                 mesh.vertices.data(), GL_DYNAMIC_DRAW);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
                 mesh.indices.data(), GL_DYNAMIC_DRAW);
    glBindVertexArray(0);
    mRowStart = mesh.rowStart;
    mIndexCount = std::uint32_t(mesh.indices.size());
    mOrigin = mesh.origin;
}

void WarpedGridRenderer::setDetail(double postSpacing, double tauTex) {
    glUniform1f(mLocFreq, float(1.0 / std::max(postSpacing, 1e-6)));
    glUniform1f(mLocTau, float(tauTex));
}

void WarpedGridRenderer::draw(int firstRow, int lastRow, const glm::dvec2& clipMin,
                              const glm::dvec2& clipMax) {
    if (!valid() || mRowStart.empty()) return;
    const int rows = int(mRowStart.size()) - 1;
    firstRow = std::clamp(firstRow, 0, rows);
    lastRow = std::clamp(lastRow, firstRow, rows);
    const std::uint32_t a = mRowStart[std::size_t(firstRow)], b = mRowStart[std::size_t(lastRow)];
    const std::uint32_t skirt = mRowStart.back();
    mProgram.beginExternalDraw(glm::dvec3(mOrigin, 0.0), clipMin, clipMax,
                               (b - a + mIndexCount - skirt) / 3);
    glBindVertexArray(mVao.id());
    if (b > a)
        glDrawElements(GL_TRIANGLES, GLsizei(b - a), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(std::uintptr_t(a) * sizeof(std::uint32_t)));
    glDrawElements(GL_TRIANGLES, GLsizei(mIndexCount - skirt), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(std::uintptr_t(skirt) * sizeof(std::uint32_t)));
}

}  // namespace kiosk::render
