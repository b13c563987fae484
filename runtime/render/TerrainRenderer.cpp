#include "runtime/render/TerrainRenderer.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "runtime/gl/ProgramBuilder.h"
#include "runtime/render/Textures.h"

namespace kiosk::render {

glm::vec3 sunDirection(double azimuthDeg, double altitudeDeg) {
    const double az = glm::radians(azimuthDeg), alt = glm::radians(altitudeDeg);
    return glm::vec3(glm::normalize(glm::dvec3(std::sin(az) * std::cos(alt),
                                               std::cos(az) * std::cos(alt), std::sin(alt))));
}

Result<TerrainRenderer> TerrainRenderer::create(const CompositeProgramDesc& desc,
                                                int maxTextureUnits, const char* vertexShader) {
    auto fragment = generateCompositeShader(desc, maxTextureUnits);
    if (!fragment) return fragment.diagnostics;
    auto program = gl::buildProgramWithFragmentText(vertexShader, "terrain(generated).frag",
                                                    *fragment);
    if (!program) return program.diagnostics;
    TerrainRenderer r;
    r.mDesc = desc;
    r.mProgram = std::move(*program.value);
    const GLuint p = r.mProgram.id();
    auto loc = [p](const std::string& name) { return glGetUniformLocation(p, name.c_str()); };
    r.mLocMvp = loc("uModelViewProj");
    r.mLocOrigin = loc("uOrigin");
    r.mLocVScale = loc("uVerticalScale");
    r.mLocElevLut = loc("uElevLut");
    r.mLocElevLutSize = loc("uElevLutSize");
    r.mLocElevDomain = loc("uElevLutDomain");
    r.mLocElevWeight = loc("uElevLutWeight");
    r.mLocBase = loc("uBaseColor");
    r.mLocLight = loc("uLightDir");
    r.mLocAmbient = loc("uAmbient");
    r.mLocGeomLight = loc("uGeometryLighting");
    r.mLocClip = loc("uClip");
    r.mLocTauTex = loc("uTauTex");
    r.mLocMapList = loc("uMapList");
    r.mLocMapListCount = loc("uMapListCount");
    r.mLocHole = loc("uHole");
    for (std::size_t i = 0; i < desc.layers.size(); ++i) {
        const std::string n = std::to_string(i);
        r.mLayerLocs.push_back({loc("uLayer" + n), loc("uLayerB" + n), loc("uLayerRect" + n),
                                loc("uLayerParam" + n)});
        if (shaderOf(desc.layers[i])->textures() >= 3) {
            r.mLayerLocs.back().texT = loc("uLayerT" + n);
            r.mLayerLocs.back().rectT = loc("uLayerRectT" + n);
        }
        if (shaderOf(desc.layers[i])->productUniform())
            r.mLayerLocs.back().product = loc("uLayerProduct" + n);
    }
    for (int k = 0; k < desc.lutCount; ++k) {
        const std::string n = std::to_string(k);
        r.mLutLocs.push_back({loc("uLut" + n), loc("uLutDomain" + n), loc("uLutSize" + n),
                              loc("uLutBelow" + n), loc("uLutAbove" + n)});
    }
    r.mLuts.resize(std::size_t(desc.lutCount));
    // Unit layout: 0 elevation LUT, 1..lutCount transfer LUTs, then layers (each takes its
    // kind's texture count of consecutive units). A layer's LUT is its rank among LUT layers.
    int unit = 1 + desc.lutCount, lutRank = 0;
    for (const auto& l : desc.layers) {
        const auto piece = shaderOf(l);
        r.mLayerSlots.push_back({unit, piece->usesLut() ? lutRank : 0});
        unit += piece->textures();
        lutRank += piece->usesLut() ? 1 : 0;
    }
    for (std::size_t j = 0; j < desc.lenses.size(); ++j)
        r.mLensLocs.push_back({loc("uLens" + std::to_string(j)), loc("uLensParam" + std::to_string(j)),
                               loc("uLensRot" + std::to_string(j))});
    r.mLenses.resize(desc.lenses.size());
    const std::uint8_t grey[8] = {180, 180, 180, 255, 180, 180, 180, 255};
    r.setElevationLut(2, grey, 0.0f, 1.0f);
    const std::uint8_t clear[4] = {0, 0, 0, 0};
    r.mNeutral = makeRgbaTexture(1, 1, clear, false);
    return r;
}

void TerrainRenderer::setElevationLut(int size, const std::uint8_t* rgba, float domainMin,
                                      float domainMax) {
    mElevLut = makeLutTexture(size, rgba);
    mElevLutSize = float(size);
    mElevDomain = glm::vec2(domainMin, domainMax);
}

void TerrainRenderer::setLut(int index, const LutBinding& lut) {
    if (index >= 0 && index < int(mLuts.size())) mLuts[std::size_t(index)] = lut;
}

void TerrainRenderer::setLens(int index, const LensBinding& lens) {
    if (index >= 0 && index < int(mLenses.size())) mLenses[std::size_t(index)] = lens;
}

void TerrainRenderer::begin(const math::Camera& camera, const glm::dvec3& sceneOrigin,
                            const TerrainStyle& style) {
    mCamera = &camera;
    mSceneOrigin = sceneOrigin;
    mProjection = camera.projection();
    glUseProgram(mProgram.id());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    // Skirts face outwards and hang below the surface; culling would save little on a height
    // field seen from above and risks dropping skirt faces, so it stays off.
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, mElevLut.id());
    glUniform1i(mLocElevLut, 0);
    glUniform1f(mLocElevLutSize, mElevLutSize);
    glUniform2f(mLocElevDomain, mElevDomain.x, mElevDomain.y);
    glUniform1f(mLocElevWeight, style.elevationLutWeight);
    glUniform4f(mLocBase, style.baseColor.r, style.baseColor.g, style.baseColor.b, style.baseColor.a);
    glUniform3f(mLocLight, style.lightDir.x, style.lightDir.y, style.lightDir.z);
    glUniform1f(mLocAmbient, style.ambient);
    glUniform1f(mLocGeomLight, style.geometryLighting);
    glUniform1f(mLocVScale, style.verticalScale);
    if (mLocTauTex >= 0) glUniform1f(mLocTauTex, style.tauTex);
    glUniform4f(mLocHole, float(mHoleMin.x - sceneOrigin.x), float(mHoleMin.y - sceneOrigin.y),
                float(mHoleMax.x - sceneOrigin.x), float(mHoleMax.y - sceneOrigin.y));
    for (std::size_t k = 0; k < mLuts.size(); ++k) {
        const auto& lut = mLuts[k];
        const auto& l = mLutLocs[k];
        glActiveTexture(GLenum(GL_TEXTURE1 + k));
        glBindTexture(GL_TEXTURE_2D, lut.texture ? lut.texture : mNeutral.id());
        glUniform1i(l.tex, GLint(1 + k));
        glUniform2f(l.domain, lut.domainMin, lut.domainMax);
        glUniform1f(l.size, float(lut.size));
        glUniform4fv(l.below, 1, glm::value_ptr(lut.below));
        glUniform4fv(l.above, 1, glm::value_ptr(lut.above));
    }
    for (std::size_t j = 0; j < mLenses.size(); ++j) {
        const auto& lens = mLenses[j];
        const glm::dvec2 c = lens.centre - glm::dvec2(sceneOrigin);
        glUniform4f(mLensLocs[j][0], float(c.x), float(c.y), float(lens.radii.x), float(lens.radii.y));
        glUniform4f(mLensLocs[j][1], lens.softEdge, lens.insideGain, lens.outsideGain,
                    lens.enabled ? 1.0f : 0.0f);
        const double a = glm::radians(lens.rotationDeg);
        glUniform2f(mLensLocs[j][2], float(std::cos(a)), float(std::sin(a)));
    }
    for (int i = 0; i < int(mDesc.layers.size()); ++i) setLayer(i, {});
    if (mDesc.mappingCapacity > 0 && mMappings) {
        // The last two units (LayerStack's textureUnitsNeeded): data and LUT arrays.
        const int units = textureUnitsNeeded(mDesc);
        mMappings->bind(mProgram.id(), units - 2, units - 1);
        glUniform1i(mLocMapListCount, -1);
    }
}

void TerrainRenderer::setMappingList(const int* indices, int count) {
    if (mDesc.mappingCapacity <= 0 || mLocMapListCount < 0) return;
    count = std::clamp(count, 0, mDesc.mappingCapacity);
    std::vector<GLint> packed(std::size_t(mDesc.mappingCapacity / 4 + 1) * 4, 0);
    for (int j = 0; j < count; ++j) packed[std::size_t(j)] = indices[j];
    glUniform4iv(mLocMapList, GLsizei(packed.size() / 4), packed.data());
    glUniform1i(mLocMapListCount, count);
}

void TerrainRenderer::setLayer(int index, const LayerBinding& b) {
    if (index < 0 || index >= int(mLayerLocs.size())) return;
    const auto& l = mLayerLocs[std::size_t(index)];
    const int unit = mLayerSlots[std::size_t(index)].unit;
    glActiveTexture(GLenum(GL_TEXTURE0 + unit));
    glBindTexture(GL_TEXTURE_2D, b.valid && b.texture ? b.texture : mNeutral.id());
    glUniform1i(l.tex, unit);
    if (l.texB >= 0) {
        glActiveTexture(GLenum(GL_TEXTURE0 + unit + 1));
        glBindTexture(GL_TEXTURE_2D, b.valid && b.textureB ? b.textureB : mNeutral.id());
        glUniform1i(l.texB, unit + 1);
    }
    if (l.texT >= 0) {
        glActiveTexture(GLenum(GL_TEXTURE0 + unit + 2));
        glBindTexture(GL_TEXTURE_2D, b.valid && b.textureT ? b.textureT : mNeutral.id());
        glUniform1i(l.texT, unit + 2);
        glUniform4f(l.rectT, float(b.westT - mSceneOrigin.x), float(b.northT - mSceneOrigin.y),
                    float(1.0 / b.widthT), float(-1.0 / b.heightT));
    }
    if (l.product >= 0) glUniform4f(l.product, b.product.x, b.product.y, b.product.z, b.product.w);
    // uv = (scenePos - (west, north)) * (1/width, -1/height): row 0 of a texture is its north edge.
    glUniform4f(l.rect, float(b.west - mSceneOrigin.x), float(b.north - mSceneOrigin.y),
                float(1.0 / b.width), float(-1.0 / b.height));
    glUniform4f(l.param, b.strength, b.alpha, float(mLayerSlots[std::size_t(index)].lut),
                b.valid ? 1.0f : 0.0f);
}

void TerrainRenderer::draw(const GpuMesh& mesh, const glm::dvec3& origin, bool fromAncestor) {
    draw(mesh, origin, fromAncestor, glm::dvec2(-kNoClip), glm::dvec2(kNoClip));
}

void TerrainRenderer::draw(const GpuMesh& mesh, const glm::dvec3& origin, bool fromAncestor,
                           const glm::dvec2& clipMin, const glm::dvec2& clipMax) {
    if (!mCamera || !mesh.valid()) return;
    setTileUniforms(origin, clipMin, clipMax);
    mesh.draw();
    ++mCounters.tilesDrawn;
    ++mCounters.drawCalls;
    mCounters.triangles += mesh.triangleCount();
    if (fromAncestor) ++mCounters.tilesFromAncestor;
}

void TerrainRenderer::setTileUniforms(const glm::dvec3& origin, const glm::dvec2& clipMin,
                                      const glm::dvec2& clipMax) {
    const glm::dvec2 o(mSceneOrigin);
    glUniform4f(mLocClip, float(clipMin.x - o.x), float(clipMin.y - o.y), float(clipMax.x - o.x),
                float(clipMax.y - o.y));
    const glm::mat4 mvp(mProjection * mCamera->view(origin));
    glUniformMatrix4fv(mLocMvp, 1, GL_FALSE, glm::value_ptr(mvp));
    const glm::dvec3 rel = origin - mSceneOrigin;
    glUniform3f(mLocOrigin, float(rel.x), float(rel.y), float(origin.z));
}

void TerrainRenderer::drawRanges(const GpuMesh& mesh, const glm::dvec3& origin, bool fromAncestor,
                                 const glm::dvec2& clipMin, const glm::dvec2& clipMax,
                                 const IndexRun* ranges, std::size_t count) {
    if (!mCamera || !mesh.valid()) return;
    setTileUniforms(origin, clipMin, clipMax);
    for (std::size_t i = 0; i < count; ++i) {
        mesh.drawRange(ranges[i].first, ranges[i].count);
        ++mCounters.drawCalls;
        mCounters.triangles += ranges[i].count / 3;
    }
    ++mCounters.tilesDrawn;
    if (fromAncestor) ++mCounters.tilesFromAncestor;
}

void TerrainRenderer::end() {
    glBindVertexArray(0);
    mCamera = nullptr;
}

}  // namespace kiosk::render
