#include "runtime/gl/Context.h"

#include <GLES3/gl32.h>

#include <cstdlib>
#include <cstring>

#include "runtime/core/Log.h"

namespace kiosk::gl {
namespace {

void GL_APIENTRY debugCallback(GLenum, GLenum type, GLuint id, GLenum severity, GLsizei,
                               const GLchar* message, const void*) {
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) {
        KIOSK_LOG_DEBUG("gl::debug", "[%u] %s", id, message);
    } else if (type == GL_DEBUG_TYPE_ERROR) {
        KIOSK_LOG_ERROR("gl::debug", "[%u] %s", id, message);
    } else {
        KIOSK_LOG_WARN("gl::debug", "[%u] %s", id, message);
    }
}

bool wantDebug() {
#ifndef NDEBUG
    return true;
#else
    const char* v = std::getenv("GEOKIOSK_GL_DEBUG");
    return v && std::strcmp(v, "1") == 0;
#endif
}

}  // namespace

bool Caps::hasExtension(const char* name) const {
    const std::size_t len = std::strlen(name);
    for (std::size_t p = extensions.find(name); p != std::string::npos;
         p = extensions.find(name, p + len)) {
        bool startOk = p == 0 || extensions[p - 1] == ' ';
        bool endOk = p + len == extensions.size() || extensions[p + len] == ' ';
        if (startOk && endOk) return true;
    }
    return false;
}

Result<Caps> initContext() {
    Caps caps;
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    caps.renderer = renderer ? renderer : "";
    caps.version = version ? version : "";
    glGetIntegerv(GL_MAJOR_VERSION, &caps.majorVersion);
    glGetIntegerv(GL_MINOR_VERSION, &caps.minorVersion);
    if (caps.majorVersion < 3) {
        Diagnostics d;
        d.error("GL_TOO_OLD", "", "", "OpenGL ES 3.0 is required, the context offers '" +
                                          caps.version + "'");
        return d;
    }
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &caps.maxTextureSize);
    glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &caps.maxTextureUnits);
    glGetIntegerv(GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS, &caps.maxVertexTextureUnits);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &caps.maxArrayLayers);
    glGetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &caps.maxUniformBlockSize);
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; ++i) {
        const auto* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
        if (!e) continue;
        if (!caps.extensions.empty()) caps.extensions += ' ';
        caps.extensions += e;
    }
    caps.khrDebug = caps.hasExtension("GL_KHR_debug");
    caps.colorBufferFloat = caps.hasExtension("GL_EXT_color_buffer_float");
    caps.textureFloatLinear = caps.hasExtension("GL_OES_texture_float_linear");
    // glDebugMessageCallback is core in ES 3.2 (llvmpipe, Mali, V3D report 3.1+); on a bare 3.0
    // context KHR_debug output is simply not routed.
    const bool es32 = caps.majorVersion > 3 || (caps.majorVersion == 3 && caps.minorVersion >= 2);
    if (es32 && wantDebug()) {
        glEnable(GL_DEBUG_OUTPUT);
        glDebugMessageCallback(debugCallback, nullptr);
    }
    return caps;
}

const char* glErrorName(unsigned error) noexcept {
    switch (error) {
        case GL_NO_ERROR: return "GL_NO_ERROR";
        case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
        default: return "GL error";
    }
}

}  // namespace kiosk::gl
