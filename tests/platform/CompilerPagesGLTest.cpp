// platform::releaseCompilerPages (issue 14): after llvmpipe compiled a shader, libLLVM's code
// pages this process alone maps go back to the kernel; the next compile still works.
#include "runtime/platform/CompilerPages.h"
#include "tests/support/EglTestContext.h"

#include <GLES3/gl3.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

namespace kiosk::platform {
namespace {

// Private_Clean kB of libLLVM's executable mappings: the code pages only this process maps
// (pages a concurrent GL process shares are Shared_Clean and the kernel leaves them alone).
long llvmPrivateCodeKb() {
    std::ifstream smaps("/proc/self/smaps");
    std::string line;
    bool inLlvmCode = false;
    long kb = 0;
    while (std::getline(smaps, line)) {
        unsigned long b = 0, e = 0;
        char perms[8] = {};
        if (std::sscanf(line.c_str(), "%lx-%lx %7s", &b, &e, perms) == 3) {
            inLlvmCode = perms[2] == 'x' && line.find("/libLLVM") != std::string::npos;
            continue;
        }
        long v = 0;
        if (inLlvmCode && std::sscanf(line.c_str(), "Private_Clean: %ld kB", &v) == 1) kb += v;
    }
    return kb;
}

// Compiles and draws a fresh program (llvmpipe compiles its variant with LLVM at draw time).
void drawWithNewShader(float red) {
    const std::string fs =
        "#version 300 es\nprecision mediump float;\nout vec4 c;\nvoid main() "
        "{ c = vec4(" +
        std::to_string(red) + ", gl_FragCoord.x * 0.01, 0.5, 1.0); }\n";
    const char* vs =
        "#version 300 es\nvoid main() { vec2 p[3] = vec2[3](vec2(-1,-1), "
        "vec2(3,-1), vec2(-1,3)); gl_Position = vec4(p[gl_VertexID], 0, 1); }\n";
    const char* fsrc = fs.c_str();
    GLuint v = glCreateShader(GL_VERTEX_SHADER), f = glCreateShader(GL_FRAGMENT_SHADER);
    glShaderSource(v, 1, &vs, nullptr);
    glShaderSource(f, 1, &fsrc, nullptr);
    glCompileShader(v);
    glCompileShader(f);
    GLuint prog = glCreateProgram();
    glAttachShader(prog, v);
    glAttachShader(prog, f);
    glLinkProgram(prog);
    GLint linked = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &linked);
    ASSERT_EQ(linked, GL_TRUE);
    glUseProgram(prog);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glFinish();
    glDeleteProgram(prog);
    glDeleteShader(v);
    glDeleteShader(f);
}

class CompilerPagesGLTest : public test::EglTest {};

TEST_F(CompilerPagesGLTest, LlvmCodeGoesBackAndTheNextCompileStillWorks) {
    auto target = makeTarget(64, 64);
    drawWithNewShader(0.25f);
    const long before = llvmPrivateCodeKb();
    EXPECT_TRUE(releaseCompilerPages(2.0));
    const CompilerPagesStats s = compilerPagesStats();
    if (s.mappedBytes == 0) GTEST_SKIP() << "the GL driver maps no libLLVM (not llvmpipe)";
    EXPECT_EQ(s.releases, 1u);
    EXPECT_FALSE(releaseCompilerPages(2.0)) << "rate limit: not again within 2 s";
    const long after = llvmPrivateCodeKb();
    // What only this process mapped is gone (a few pages may fault back in between).
    EXPECT_LE(after, before / 4 + 512) << "libLLVM private code kB before " << before;

    // A new shader compiles and draws (the code faults back as LLVM needs it).
    drawWithNewShader(1.0f);
    const gl::Image img = target.readColor();
    EXPECT_EQ(img.pixel(0, 0)[0], 255);
    EXPECT_EQ(img.pixel(0, 0)[2], 128);
    EXPECT_TRUE(releaseCompilerPages(0.0));
    EXPECT_EQ(compilerPagesStats().releases, 2u);
}

}  // namespace
}  // namespace kiosk::platform
