#pragma once

#include <span>
#include <string_view>

namespace kiosk::shaders {

struct EmbeddedShader {
    std::string_view name;  ///< path relative to runtime/shaders, e.g. "terrain.frag"
    std::string_view text;
};

/** @brief Every shader in runtime/shaders, compiled into the binary (generated at build time). */
std::span<const EmbeddedShader> embedded();

}  // namespace kiosk::shaders
