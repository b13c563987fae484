#include "runtime/gl/ProgramBuilder.h"

#include <regex>
#include <sstream>

#include "runtime/gl/ShaderLibrary.h"

namespace kiosk::gl {
namespace {

std::string infoLog(GLuint object, bool isProgram) {
    GLint len = 0;
    if (isProgram)
        glGetProgramiv(object, GL_INFO_LOG_LENGTH, &len);
    else
        glGetShaderiv(object, GL_INFO_LOG_LENGTH, &len);
    if (len <= 1) return {};
    std::string log(std::size_t(len), '\0');
    if (isProgram)
        glGetProgramInfoLog(object, len, nullptr, log.data());
    else
        glGetShaderInfoLog(object, len, nullptr, log.data());
    log.resize(std::size_t(len - 1));
    return log;
}

bool compileText(GLenum stage, const std::string& name, const std::string& source,
                 const std::vector<std::string>& fileNames, Shader& out, Diagnostics& diags) {
    Shader shader(glCreateShader(stage));
    const char* text = source.c_str();
    glShaderSource(shader.id(), 1, &text, nullptr);
    glCompileShader(shader.id());
    GLint ok = GL_FALSE;
    glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
    if (!ok) {
        for (const auto& line : mapInfoLog(infoLog(shader.id(), false), fileNames))
            diags.error("SHADER_COMPILE", "", "", line);
        if (!diags.hasErrors()) diags.error("SHADER_COMPILE", name, "", "compile failed");
        return false;
    }
    out = std::move(shader);
    return true;
}

bool compile(GLenum stage, const std::string& name, const std::vector<std::string>& defines,
             Shader& out, Diagnostics& diags) {
    auto expanded = ShaderLibrary::expand(name, defines);
    if (!expanded) {
        diags.append(expanded.diagnostics);
        return false;
    }
    return compileText(stage, name, expanded->text, expanded->fileNames, out, diags);
}

Result<Program> link(const Shader& vs, const Shader& fs, const std::string& name) {
    auto program = Program::create();
    glAttachShader(program.id(), vs.id());
    glAttachShader(program.id(), fs.id());
    glLinkProgram(program.id());
    GLint ok = GL_FALSE;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    if (!ok) {
        Diagnostics diags;
        diags.error("SHADER_LINK", name, "", "link failed: " + infoLog(program.id(), true));
        return diags;
    }
    return program;
}

}  // namespace

std::vector<std::string> mapInfoLog(const std::string& log,
                                    const std::vector<std::string>& fileNames) {
    // Mesa: "0:12(5): error: ...", ANGLE/others: "ERROR: 0:12: ..."
    static const std::regex pattern(R"(^(?:ERROR: |WARNING: )?(\d+):(\d+)(?:\((\d+)\))?:\s*(.*)$)");
    std::vector<std::string> out;
    std::istringstream in(log);
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        std::smatch m;
        if (std::regex_match(line, m, pattern)) {
            std::size_t idx = std::stoul(m[1].str());
            std::string file = idx < fileNames.size() ? fileNames[idx] : "shader#" + m[1].str();
            out.push_back(file + ":" + m[2].str() + ": " + m[4].str());
        } else {
            out.push_back(line);
        }
    }
    return out;
}

Result<Program> buildProgram(const std::string& vertexName, const std::string& fragmentName,
                             const std::vector<std::string>& defines) {
    Diagnostics diags;
    Shader vs, fs;
    if (!compile(GL_VERTEX_SHADER, vertexName, defines, vs, diags)) return diags;
    if (!compile(GL_FRAGMENT_SHADER, fragmentName, defines, fs, diags)) return diags;
    return link(vs, fs, vertexName + "+" + fragmentName);
}

Result<Program> buildProgramWithFragmentText(const std::string& vertexName,
                                             const std::string& fragmentName,
                                             const std::string& fragmentText) {
    Diagnostics diags;
    Shader vs, fs;
    if (!compile(GL_VERTEX_SHADER, vertexName, {}, vs, diags)) return diags;
    if (!compileText(GL_FRAGMENT_SHADER, fragmentName, fragmentText, {fragmentName}, fs, diags))
        return diags;
    return link(vs, fs, vertexName + "+" + fragmentName);
}

}  // namespace kiosk::gl
