#include "runtime/gl/ShaderLibrary.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "runtime/core/Log.h"
#include "runtime/shaders/EmbeddedShaders.h"

namespace kiosk::gl {
namespace {

constexpr int kMaxIncludeDepth = 8;

bool expandInto(std::string_view name, ShaderLibrary::Expanded& out, int depth,
                Diagnostics& diags) {
    if (depth > kMaxIncludeDepth) {
        diags.error("SHADER_INCLUDE_DEPTH", std::string(name), "", "includes nested too deeply");
        return false;
    }
    auto src = ShaderLibrary::source(name);
    if (!src) {
        diags.append(src.diagnostics);
        return false;
    }
    const int fileIndex = static_cast<int>(out.fileNames.size());
    out.fileNames.emplace_back(name);
    std::istringstream in(*src);
    std::string line;
    int lineNo = 0;
    out.text += "#line 1 " + std::to_string(fileIndex) + "\n";
    while (std::getline(in, line)) {
        ++lineNo;
        const std::string_view marker = "// #pragma include \"";
        auto pos = line.find(marker);
        if (pos != std::string::npos) {
            auto start = pos + marker.size();
            auto end = line.find('"', start);
            if (end == std::string::npos) {
                diags.error("SHADER_BAD_INCLUDE", std::string(name), "line " + std::to_string(lineNo),
                            "unterminated include");
                return false;
            }
            if (!expandInto(line.substr(start, end - start), out, depth + 1, diags)) return false;
            out.text += "#line " + std::to_string(lineNo + 1) + " " + std::to_string(fileIndex) + "\n";
            continue;
        }
        if (line.rfind("#version", 0) == 0) {
            out.text += "\n";  // the library writes #version itself
            continue;
        }
        out.text += line;
        out.text += '\n';
    }
    return true;
}

}  // namespace

Result<std::string> ShaderLibrary::source(std::string_view name) {
    if (const char* dir = std::getenv("GEOKIOSK_SHADER_DIR"); dir && *dir) {
        std::filesystem::path p = std::filesystem::path(dir) / std::string(name);
        std::ifstream f(p);
        if (f) {
            std::stringstream ss;
            ss << f.rdbuf();
            KIOSK_LOG_INFO("gl::ShaderLibrary", "loaded external shader %s from %s",
                           std::string(name).c_str(), p.c_str());
            return ss.str();
        }
    }
    for (const auto& e : shaders::embedded())
        if (e.name == name) return std::string(e.text);
    Diagnostics d;
    d.error("SHADER_NOT_FOUND", std::string(name), "", "no such shader (embedded or on disk)");
    return d;
}

Result<ShaderLibrary::Expanded> ShaderLibrary::expand(std::string_view name,
                                                      const std::vector<std::string>& defines) {
    Expanded out;
    out.text = "#version 300 es\n";
    for (const auto& d : defines) out.text += "#define " + d + "\n";
    Diagnostics diags;
    if (!expandInto(name, out, 0, diags)) return diags;
    return out;
}

std::vector<std::string> ShaderLibrary::embeddedNames() {
    std::vector<std::string> names;
    for (const auto& e : shaders::embedded()) names.emplace_back(e.name);
    return names;
}

}  // namespace kiosk::gl
