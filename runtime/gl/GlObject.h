#pragma once

#include <GLES3/gl3.h>

#include <utility>

namespace kiosk::gl {

/**
 * @brief Move-only owner of one GL object name. Render thread only: created and destroyed where
 * the context is current. `release()` hands the name over without deleting it.
 */
template <class Traits>
class GlObject {
public:
    GlObject() = default;
    explicit GlObject(GLuint id) noexcept : mId(id) {}
    GlObject(GlObject&& o) noexcept : mId(std::exchange(o.mId, 0)) {}
    GlObject& operator=(GlObject&& o) noexcept {
        if (this != &o) {
            reset();
            mId = std::exchange(o.mId, 0);
        }
        return *this;
    }
    GlObject(const GlObject&) = delete;
    GlObject& operator=(const GlObject&) = delete;
    ~GlObject() { reset(); }

    static GlObject create() { return GlObject(Traits::create()); }
    GLuint id() const noexcept { return mId; }
    explicit operator bool() const noexcept { return mId != 0; }
    GLuint release() noexcept { return std::exchange(mId, 0); }
    void reset() noexcept {
        if (mId) {
            Traits::destroy(mId);
            mId = 0;
        }
    }

private:
    GLuint mId = 0;
};

struct TextureTraits {
    static GLuint create() noexcept { GLuint id = 0; glGenTextures(1, &id); return id; }
    static void destroy(GLuint id) noexcept { glDeleteTextures(1, &id); }
};
struct BufferTraits {
    static GLuint create() noexcept { GLuint id = 0; glGenBuffers(1, &id); return id; }
    static void destroy(GLuint id) noexcept { glDeleteBuffers(1, &id); }
};
struct VertexArrayTraits {
    static GLuint create() noexcept { GLuint id = 0; glGenVertexArrays(1, &id); return id; }
    static void destroy(GLuint id) noexcept { glDeleteVertexArrays(1, &id); }
};
struct FramebufferTraits {
    static GLuint create() noexcept { GLuint id = 0; glGenFramebuffers(1, &id); return id; }
    static void destroy(GLuint id) noexcept { glDeleteFramebuffers(1, &id); }
};
struct RenderbufferTraits {
    static GLuint create() noexcept { GLuint id = 0; glGenRenderbuffers(1, &id); return id; }
    static void destroy(GLuint id) noexcept { glDeleteRenderbuffers(1, &id); }
};
struct ShaderTraits {
    static void destroy(GLuint id) noexcept { glDeleteShader(id); }
};
struct ProgramTraits {
    static GLuint create() noexcept { return glCreateProgram(); }
    static void destroy(GLuint id) noexcept { glDeleteProgram(id); }
};
struct QueryTraits {
    static GLuint create() noexcept { GLuint id = 0; glGenQueries(1, &id); return id; }
    static void destroy(GLuint id) noexcept { glDeleteQueries(1, &id); }
};

using Texture = GlObject<TextureTraits>;
using Buffer = GlObject<BufferTraits>;
using VertexArray = GlObject<VertexArrayTraits>;
using Framebuffer = GlObject<FramebufferTraits>;
using Renderbuffer = GlObject<RenderbufferTraits>;
using Shader = GlObject<ShaderTraits>;
using Program = GlObject<ProgramTraits>;
using Query = GlObject<QueryTraits>;

}  // namespace kiosk::gl
