#include "runtime/render/TerrainRenderer.h"

#include <cmath>

#include "runtime/gl/ProgramBuilder.h"
#include "runtime/render/Textures.h"

namespace kiosk::render {

glm::vec3 sunDirection(double azimuthDeg, double altitudeDeg) {
    const double az = glm::radians(azimuthDeg), alt = glm::radians(altitudeDeg);
    return glm::vec3(glm::normalize(glm::dvec3(std::sin(az) * std::cos(alt),
                                               std::cos(az) * std::cos(alt), std::sin(alt))));
}

Result<TerrainRenderer> TerrainRenderer::create() {
    auto program = gl::buildProgram("terrain.vert", "terrain.frag");
    if (!program) return program.diagnostics;
    TerrainRenderer r;
    r.mProgram = std::move(*program.value);
    const GLuint p = r.mProgram.id();
    r.mLocMvp = glGetUniformLocation(p, "uModelViewProj");
    r.mLocOrigin = glGetUniformLocation(p, "uOrigin");
    r.mLocExtentMin = glGetUniformLocation(p, "uExtentMin");
    r.mLocExtentSize = glGetUniformLocation(p, "uExtentSize");
    r.mLocVScale = glGetUniformLocation(p, "uVerticalScale");
    r.mLocLut = glGetUniformLocation(p, "uLut");
    r.mLocLutSize = glGetUniformLocation(p, "uLutSize");
    r.mLocLutDomain = glGetUniformLocation(p, "uLutDomain");
    r.mLocDrape = glGetUniformLocation(p, "uDrape");
    r.mLocDrapeWeight = glGetUniformLocation(p, "uDrapeWeight");
    r.mLocLight = glGetUniformLocation(p, "uLightDir");
    r.mLocAmbient = glGetUniformLocation(p, "uAmbient");
    // Neutral defaults so a renderer without LUT or drape still draws grey shaded terrain.
    const std::uint8_t grey[8] = {180, 180, 180, 255, 180, 180, 180, 255};
    r.setLut(2, grey, 0.0f, 1.0f);
    r.setDrape(1, 1, grey, glm::dvec2(0.0), glm::dvec2(1.0));
    return r;
}

void TerrainRenderer::setLut(int size, const std::uint8_t* rgba, float domainMin,
                             float domainMax) {
    mLut = makeLutTexture(size, rgba);
    mLutSize = float(size);
    mLutDomain = glm::vec2(domainMin, domainMax);
}

void TerrainRenderer::setDrape(int width, int height, const std::uint8_t* rgba,
                               glm::dvec2 extentMin, glm::dvec2 extentMax) {
    mDrape = makeRgbaTexture(width, height, rgba, true);
    mExtentMin = extentMin;
    mExtentMax = extentMax;
}

void TerrainRenderer::begin(const math::Camera& camera, const TerrainStyle& style) {
    mCamera = &camera;
    mProjection = camera.projection();
    glUseProgram(mProgram.id());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, mLut.id());
    glUniform1i(mLocLut, 0);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, mDrape.id());
    glUniform1i(mLocDrape, 1);
    glUniform1f(mLocLutSize, mLutSize);
    glUniform2f(mLocLutDomain, mLutDomain.x, mLutDomain.y);
    glUniform1f(mLocDrapeWeight, style.drapeWeight);
    glUniform3f(mLocLight, style.lightDir.x, style.lightDir.y, style.lightDir.z);
    glUniform1f(mLocAmbient, style.ambient);
    glUniform1f(mLocVScale, style.verticalScale);
    const glm::dvec2 size = glm::max(mExtentMax - mExtentMin, glm::dvec2(1e-9));
    glUniform2f(mLocExtentMin, float(mExtentMin.x), float(mExtentMin.y));
    glUniform2f(mLocExtentSize, float(size.x), float(size.y));
}

void TerrainRenderer::draw(const GpuMesh& mesh, const glm::dvec3& origin, bool fromAncestor) {
    if (!mCamera || !mesh.valid()) return;
    const glm::mat4 mvp(mProjection * mCamera->view(origin));
    glUniformMatrix4fv(mLocMvp, 1, GL_FALSE, glm::value_ptr(mvp));
    glUniform3f(mLocOrigin, float(origin.x), float(origin.y), float(origin.z));
    mesh.draw();
    ++mCounters.tilesDrawn;
    mCounters.triangles += mesh.triangleCount();
    if (fromAncestor) ++mCounters.tilesFromAncestor;
}

void TerrainRenderer::end() {
    glBindVertexArray(0);
    mCamera = nullptr;
}

}  // namespace kiosk::render
