// gl::ShaderLibrary (embedded sources, disk override, include expansion) and gl::mapInfoLog.
// Pure text: no GL context needed (label `unit`).
#include "runtime/gl/ProgramBuilder.h"
#include "runtime/gl/ShaderLibrary.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <unistd.h>

namespace kiosk::gl {
namespace {

namespace fs = std::filesystem;

std::string readFile(const fs::path& p) {
    std::ifstream f(p);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

/** @brief A scratch shader directory; GEOKIOSK_SHADER_DIR is restored on teardown. */
class ShaderLibraryTest : public ::testing::Test {
protected:
    void SetUp() override {
        if (const char* old = std::getenv("GEOKIOSK_SHADER_DIR")) mOld = old;
        unsetenv("GEOKIOSK_SHADER_DIR");
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = info->name();  // "Case/param" for parameterised tests
        for (char& c : name)
            if (c == '/') c = '_';
        mDir =
            fs::temp_directory_path() / ("kiosk-shaders-" + std::to_string(getpid()) + "-" + name);
        fs::remove_all(mDir);
        fs::create_directories(mDir);
    }
    void TearDown() override {
        if (mOld)
            setenv("GEOKIOSK_SHADER_DIR", mOld->c_str(), 1);
        else
            unsetenv("GEOKIOSK_SHADER_DIR");
        std::error_code ec;
        fs::remove_all(mDir, ec);
    }
    void write(const std::string& name, const std::string& text) {
        fs::create_directories((mDir / name).parent_path());
        std::ofstream(mDir / name) << text;
    }
    void useDir() { setenv("GEOKIOSK_SHADER_DIR", mDir.c_str(), 1); }

    fs::path mDir;
    std::optional<std::string> mOld;
};

TEST_F(ShaderLibraryTest, EveryShaderFileIsEmbeddedVerbatim) {
    // Catches a file added to runtime/shaders but not to its CMake list (or a broken embed).
    const fs::path root = "runtime/shaders";
    ASSERT_TRUE(fs::is_directory(root)) << "tests run from the repository root";
    int checked = 0;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        const auto ext = entry.path().extension().string();
        if (ext != ".vert" && ext != ".frag" && ext != ".glsl") continue;
        const std::string name = fs::relative(entry.path(), root).generic_string();
        auto src = ShaderLibrary::source(name);
        ASSERT_TRUE(src.ok()) << name << " is not embedded: " << src.diagnostics.format();
        EXPECT_EQ(*src, readFile(entry.path())) << name;
        ++checked;
    }
    EXPECT_GT(checked, 0);
    EXPECT_EQ(std::size_t(checked), ShaderLibrary::embeddedNames().size());
}

TEST_F(ShaderLibraryTest, EveryEmbeddedShaderExpands) {
    for (const auto& name : ShaderLibrary::embeddedNames()) {
        auto e = ShaderLibrary::expand(name, {});
        ASSERT_TRUE(e.ok()) << name << ": " << e.diagnostics.format();
        EXPECT_EQ(e->text.rfind("#version 300 es\n", 0), 0u) << name;
        ASSERT_FALSE(e->fileNames.empty());
        EXPECT_EQ(e->fileNames[0], name);
        // Exactly one #version, the library's own.
        EXPECT_EQ(e->text.find("#version", 1), std::string::npos) << name;
    }
}

TEST_F(ShaderLibraryTest, UnknownNameIsAnError) {
    auto r = ShaderLibrary::source("nope/missing.frag");
    ASSERT_FALSE(r.ok());
    ASSERT_EQ(r.diagnostics.size(), 1u);
    EXPECT_EQ(r.diagnostics.items()[0].code, "SHADER_NOT_FOUND");
    EXPECT_EQ(r.diagnostics.items()[0].file, "nope/missing.frag");
}

TEST_F(ShaderLibraryTest, DiskOverrideWinsAndFallsBackPerFile) {
    const auto embeddedNames = ShaderLibrary::embeddedNames();
    ASSERT_GE(embeddedNames.size(), 2u);
    const std::string overridden = embeddedNames[0], untouched = embeddedNames[1];
    auto embeddedText = ShaderLibrary::source(untouched);
    ASSERT_TRUE(embeddedText.ok());

    write(overridden, "// live edit\n");
    write("only-on-disk.frag", "// not embedded\n");
    useDir();
    auto a = ShaderLibrary::source(overridden);
    ASSERT_TRUE(a.ok()) << a.diagnostics.format();
    EXPECT_EQ(*a, "// live edit\n");
    auto b = ShaderLibrary::source(untouched);  // absent from the directory: embedded text
    ASSERT_TRUE(b.ok());
    EXPECT_EQ(*b, *embeddedText);
    auto c = ShaderLibrary::source("only-on-disk.frag");
    ASSERT_TRUE(c.ok()) << c.diagnostics.format();
    EXPECT_EQ(*c, "// not embedded\n");

    unsetenv("GEOKIOSK_SHADER_DIR");
    auto d = ShaderLibrary::source(overridden);
    ASSERT_TRUE(d.ok());
    EXPECT_NE(*d, "// live edit\n");
}

TEST_F(ShaderLibraryTest, IncludesExpandRecursivelyWithLineDirectives) {
    write("main.frag",
          "#version 300 es\n"
          "precision highp float;\n"
          "// #pragma include \"inc/a.glsl\"\n"
          "out vec4 c;\n"
          "void main() { c = vec4(a()); }\n");
    write("inc/a.glsl",
          "// #pragma include \"inc/b.glsl\"\n"
          "float a() { return b(); }\n");
    write("inc/b.glsl", "float b() { return 1.0; }\n");
    useDir();
    auto e = ShaderLibrary::expand("main.frag", {"FOO 2", "BAR"});
    ASSERT_TRUE(e.ok()) << e.diagnostics.format();
    EXPECT_EQ(e->text,
              "#version 300 es\n"
              "#define FOO 2\n"
              "#define BAR\n"
              "#line 1 0\n"
              "\n"  // the file's own #version, blanked so line numbers stay right
              "precision highp float;\n"
              "#line 1 1\n"
              "#line 1 2\n"
              "float b() { return 1.0; }\n"
              "#line 2 1\n"
              "float a() { return b(); }\n"
              "#line 4 0\n"
              "out vec4 c;\n"
              "void main() { c = vec4(a()); }\n");
    EXPECT_EQ(e->fileNames, (std::vector<std::string>{"main.frag", "inc/a.glsl", "inc/b.glsl"}));
}

struct BadInclude {
    const char* name;
    const char* mainText;
    const char* code;
    const char* substring;  ///< in the formatted diagnostic
};

// Test names and failure messages show the case name, not the struct's bytes.
void PrintTo(const BadInclude& c, std::ostream* os) {
    *os << c.name;
}

const BadInclude kBadIncludes[] = {
    {"missing", "// #pragma include \"inc/missing.glsl\"\n", "SHADER_NOT_FOUND",
     "inc/missing.glsl"},
    {"unterminated", "void f();\n// #pragma include \"inc/a.glsl\n", "SHADER_BAD_INCLUDE",
     "line 2"},
    {"recursive", "// #pragma include \"main.frag\"\n", "SHADER_INCLUDE_DEPTH", "main.frag"},
};

class ShaderLibraryBadInclude : public ShaderLibraryTest,
                                public ::testing::WithParamInterface<BadInclude> {};

TEST_P(ShaderLibraryBadInclude, ReportsCodeAndPlace) {
    write("main.frag", GetParam().mainText);
    useDir();
    auto e = ShaderLibrary::expand("main.frag", {});
    ASSERT_FALSE(e.ok());
    EXPECT_TRUE(e.diagnostics.has(GetParam().code)) << e.diagnostics.format();
    EXPECT_NE(e.diagnostics.format().find(GetParam().substring), std::string::npos)
        << e.diagnostics.format();
}

INSTANTIATE_TEST_SUITE_P(Table, ShaderLibraryBadInclude, ::testing::ValuesIn(kBadIncludes),
                         [](const auto& p) { return std::string(p.param.name); });

// Driver info logs name source strings by number; mapInfoLog turns them into file names.
struct LogCase {
    const char* name;
    const char* log;
    std::vector<std::string> expected;
};

void PrintTo(const LogCase& c, std::ostream* os) {
    *os << c.name;
}

const std::vector<std::string> kFiles = {"terrain.frag", "common/encode.glsl"};

const LogCase kLogCases[] = {
    {"MesaError",
     "0:12(5): error: `foo' undeclared\n",
     {"terrain.frag:12: error: `foo' undeclared"}},
    {"MesaErrorInInclude",
     "1:3(10): error: syntax error, unexpected IDENTIFIER\n",
     {"common/encode.glsl:3: error: syntax error, unexpected IDENTIFIER"}},
    {"MesaWarning",
     "0:4(1): warning: extension `GL_FOO' unsupported\n",
     {"terrain.frag:4: warning: extension `GL_FOO' unsupported"}},
    {"GlslangStyle",
     "ERROR: 0:7: 'x' : undeclared identifier\n",
     {"terrain.frag:7: 'x' : undeclared identifier"}},
    {"UnknownSourceNumber", "5:1(1): error: what\n", {"shader#5:1: error: what"}},
    {"OtherLinesPassThroughEmptyDropped",
     "0:2(3): error: a\n\nerror: linking failed\n1:9(1): error: b",
     {"terrain.frag:2: error: a", "error: linking failed", "common/encode.glsl:9: error: b"}},
    {"Empty", "", {}},
};

class MapInfoLog : public ::testing::TestWithParam<LogCase> {};

TEST_P(MapInfoLog, RewritesSourceNumbers) {
    EXPECT_EQ(mapInfoLog(GetParam().log, kFiles), GetParam().expected);
}

INSTANTIATE_TEST_SUITE_P(Table, MapInfoLog, ::testing::ValuesIn(kLogCases),
                         [](const auto& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace kiosk::gl
