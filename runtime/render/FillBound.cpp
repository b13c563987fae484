#include "runtime/render/FillBound.h"

#include <vector>

#include "runtime/gl/ProgramBuilder.h"
#include "runtime/render/Textures.h"

namespace kiosk::render {

Result<FillBound> FillBound::create(int fetches) {
    auto program = gl::buildProgram("fillbound.vert", "fillbound.frag",
                                    {"FETCHES " + std::to_string(fetches)});
    if (!program) return program.diagnostics;
    FillBound f;
    f.mProgram = std::move(*program.value);
    // A 256x256 noise texture: the dependent reads wander like terrain texture coordinates do.
    std::vector<std::uint8_t> noise(256 * 256 * 4);
    std::uint32_t s = 12345;
    for (auto& b : noise) {
        s = s * 1664525u + 1013904223u;
        b = static_cast<std::uint8_t>(s >> 24);
    }
    f.mTexture = makeRgbaTexture(256, 256, noise.data(), true);
    f.mVao = gl::VertexArray::create();
    return f;
}

void FillBound::draw() {
    glUseProgram(mProgram.id());
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, mTexture.id());
    glUniform1i(glGetUniformLocation(mProgram.id(), "uTex"), 0);
    glBindVertexArray(mVao.id());
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glBindVertexArray(0);
}

}  // namespace kiosk::render
