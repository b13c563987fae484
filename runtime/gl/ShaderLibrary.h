#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "runtime/core/Result.h"

namespace kiosk::gl {

/**
 * @brief Shader sources by name ("terrain.vert", "common/encode.glsl").
 *
 * Sources are embedded at build time from runtime/shaders/. When GEOKIOSK_SHADER_DIR is set, a
 * file of the same name there wins (live editing without a rebuild) and a log line says so.
 * `// #pragma include "name"` lines are expanded recursively; `#line` directives keep compile
 * errors pointing at the right file and line (file numbers are listed in `fileNames`).
 */
class ShaderLibrary {
public:
    struct Expanded {
        std::string text;
        std::vector<std::string> fileNames;  ///< index = GLSL source-string number in #line
    };

    /** @brief Raw text of one shader file, or an error naming it. */
    static Result<std::string> source(std::string_view name);
    /**
     * @brief Full text for compilation: `#version 300 es`, then `defines` (each "NAME VALUE" or
     * "NAME"), then the file with includes expanded.
     */
    static Result<Expanded> expand(std::string_view name, const std::vector<std::string>& defines);
    /** @brief Every embedded shader name (for the build-time glslang check and tests). */
    static std::vector<std::string> embeddedNames();
};

}  // namespace kiosk::gl
