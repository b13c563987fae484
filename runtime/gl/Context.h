#pragma once

#include <string>

#include "runtime/core/Result.h"

namespace kiosk::gl {

/** @brief What the current context offers, queried once at start-up (never in the frame). */
struct Caps {
    std::string renderer;
    std::string version;
    int majorVersion = 0;
    int minorVersion = 0;
    int maxTextureSize = 0;
    int maxTextureUnits = 0;          ///< GL_MAX_TEXTURE_IMAGE_UNITS (fragment)
    int maxVertexTextureUnits = 0;
    int maxArrayLayers = 0;
    int maxUniformBlockSize = 0;
    bool khrDebug = false;
    bool colorBufferFloat = false;    ///< EXT_color_buffer_float
    bool textureFloatLinear = false;  ///< OES_texture_float_linear

    bool hasExtension(const char* name) const;
    std::string extensions;  ///< space separated
};

/**
 * @brief Query the current context; fails (code GL_TOO_OLD) below OpenGL ES 3.0.
 * In debug builds, or when GEOKIOSK_GL_DEBUG=1, routes KHR_debug messages to the log.
 */
Result<Caps> initContext();

/** @brief Name of a glGetError code, "GL_NO_ERROR" for 0. */
const char* glErrorName(unsigned error) noexcept;

}  // namespace kiosk::gl
