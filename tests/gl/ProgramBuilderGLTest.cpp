// gl::buildProgram against Mesa's compiler: a program that links and draws, and failures that
// name the shader file and line (through the library's #line mapping), include files too.
#include "runtime/gl/ProgramBuilder.h"
#include "tests/support/EglTestContext.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <unistd.h>

namespace kiosk::gl {
namespace {

namespace fs = std::filesystem;

// A full-screen triangle from gl_VertexID: no vertex buffers needed.
constexpr const char* kTriangleVert = R"(#version 300 es
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

constexpr const char* kColourGlsl = R"(#ifndef COLOUR
#define COLOUR vec4(1.0, 0.0, 0.0, 1.0)
#endif
)";

constexpr const char* kSolidFrag = R"(#version 300 es
precision mediump float;
// #pragma include "test/colour.glsl"
out vec4 fragColor;
void main() { fragColor = COLOUR; }
)";

// Line 6 uses an undeclared identifier.
constexpr const char* kBrokenFrag = R"(#version 300 es
precision mediump float;
// #pragma include "test/colour.glsl"
out vec4 fragColor;
void main() {
    fragColor = kioskUndeclared;
}
)";

// The error sits on line 2 of an included file, included from line 3.
constexpr const char* kBadGlsl = "float good() { return 1.0; }\nfloat bad() { return nope; }\n";
constexpr const char* kIncludesBadFrag = R"(#version 300 es
precision mediump float;
// #pragma include "test/bad.glsl"
out vec4 fragColor;
void main() { fragColor = vec4(good()); }
)";

constexpr const char* kLinkVert = R"(#version 300 es
out float vOnlyHere;
void main() { vOnlyHere = 1.0; gl_Position = vec4(0.0); }
)";
constexpr const char* kLinkFrag = R"(#version 300 es
precision mediump float;
in float vMissing;
out vec4 fragColor;
void main() { fragColor = vec4(vMissing); }
)";

class ProgramBuilderGLTest : public test::EglTest {
protected:
    void SetUp() override {
        test::EglTest::SetUp();
        if (IsSkipped() || HasFatalFailure()) return;
        if (const char* old = std::getenv("GEOKIOSK_SHADER_DIR")) mOld = old;
        mDir = fs::temp_directory_path() / ("kiosk-programs-" + std::to_string(getpid()));
        fs::remove_all(mDir);
        write("test/triangle.vert", kTriangleVert);
        write("test/colour.glsl", kColourGlsl);
        write("test/solid.frag", kSolidFrag);
        write("test/broken.frag", kBrokenFrag);
        write("test/bad.glsl", kBadGlsl);
        write("test/includes-bad.frag", kIncludesBadFrag);
        write("test/link.vert", kLinkVert);
        write("test/link.frag", kLinkFrag);
        setenv("GEOKIOSK_SHADER_DIR", mDir.c_str(), 1);
    }
    void TearDown() override {
        if (mOld)
            setenv("GEOKIOSK_SHADER_DIR", mOld->c_str(), 1);
        else
            unsetenv("GEOKIOSK_SHADER_DIR");
        std::error_code ec;
        if (!mDir.empty()) fs::remove_all(mDir, ec);
        test::EglTest::TearDown();
    }
    void write(const std::string& name, const char* text) {
        fs::create_directories((mDir / name).parent_path());
        std::ofstream(mDir / name) << text;
    }
    /** @brief Draw the full-screen triangle with `program` into a 4x4 target; centre pixel. */
    std::array<std::uint8_t, 4> drawCentre(const Program& program) {
        auto rt = makeTarget(4, 4);
        glClearColor(0, 0, 0, 0);
        glClear(GL_COLOR_BUFFER_BIT);
        auto vao = VertexArray::create();
        glBindVertexArray(vao.id());
        glUseProgram(program.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glUseProgram(0);
        glBindVertexArray(0);
        auto img = rt.readColor();
        EXPECT_GL_OK();
        const auto* p = img.pixel(2, 2);
        return {p[0], p[1], p[2], p[3]};
    }

    fs::path mDir;
    std::optional<std::string> mOld;
};

using Rgba = std::array<std::uint8_t, 4>;

TEST_F(ProgramBuilderGLTest, ValidProgramLinksAndDraws) {
    auto program = buildProgram("test/triangle.vert", "test/solid.frag");
    ASSERT_TRUE(program.ok()) << program.diagnostics.format();
    EXPECT_TRUE(program.diagnostics.empty()) << program.diagnostics.format();
    GLint linked = GL_FALSE;
    glGetProgramiv(program->id(), GL_LINK_STATUS, &linked);
    EXPECT_EQ(linked, GL_TRUE);
    EXPECT_EQ(drawCentre(*program), (Rgba{255, 0, 0, 255}));  // COLOUR from the include
}

TEST_F(ProgramBuilderGLTest, DefinesReachTheShader) {
    auto program =
        buildProgram("test/triangle.vert", "test/solid.frag", {"COLOUR vec4(0.0, 1.0, 0.0, 1.0)"});
    ASSERT_TRUE(program.ok()) << program.diagnostics.format();
    EXPECT_EQ(drawCentre(*program), (Rgba{0, 255, 0, 255}));
}

TEST_F(ProgramBuilderGLTest, EmbeddedShadersBuild) {
    // The shipped fill-rate pair: catches an embedded shader Mesa rejects.
    unsetenv("GEOKIOSK_SHADER_DIR");
    auto program = buildProgram("fillbound.vert", "fillbound.frag");
    EXPECT_TRUE(program.ok()) << program.diagnostics.format();
}

TEST_F(ProgramBuilderGLTest, CompileErrorNamesFileAndLine) {
    auto program = buildProgram("test/triangle.vert", "test/broken.frag");
    ASSERT_FALSE(program.ok());
    EXPECT_TRUE(program.diagnostics.has("SHADER_COMPILE")) << program.diagnostics.format();
    const std::string text = program.diagnostics.format();
    EXPECT_NE(text.find("test/broken.frag:6: "), std::string::npos) << text;
    EXPECT_NE(text.find("kioskUndeclared"), std::string::npos) << text;
}

TEST_F(ProgramBuilderGLTest, CompileErrorInIncludeNamesTheIncludedFile) {
    auto program = buildProgram("test/triangle.vert", "test/includes-bad.frag");
    ASSERT_FALSE(program.ok());
    const std::string text = program.diagnostics.format();
    EXPECT_NE(text.find("test/bad.glsl:2: "), std::string::npos) << text;
    EXPECT_NE(text.find("nope"), std::string::npos) << text;
}

TEST_F(ProgramBuilderGLTest, LinkErrorNamesBothStages) {
    auto program = buildProgram("test/link.vert", "test/link.frag");
    ASSERT_FALSE(program.ok());
    ASSERT_TRUE(program.diagnostics.has("SHADER_LINK")) << program.diagnostics.format();
    const std::string text = program.diagnostics.format();
    EXPECT_NE(text.find("test/link.vert+test/link.frag"), std::string::npos) << text;
    EXPECT_NE(text.find("vMissing"), std::string::npos) << text;
}

TEST_F(ProgramBuilderGLTest, MissingShaderIsReported) {
    auto program = buildProgram("test/triangle.vert", "test/absent.frag");
    ASSERT_FALSE(program.ok());
    EXPECT_TRUE(program.diagnostics.has("SHADER_NOT_FOUND")) << program.diagnostics.format();
    EXPECT_NE(program.diagnostics.format().find("test/absent.frag"), std::string::npos);
}

}  // namespace
}  // namespace kiosk::gl
