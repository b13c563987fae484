// gl::GlObject ownership semantics against real GL names: the driver, not a mock, says whether
// a name is still alive (glIsTexture & co.).
#include "runtime/gl/GlObject.h"
#include "tests/support/EglTestContext.h"

#include <utility>

namespace kiosk::gl {
namespace {

class GlObjectGLTest : public test::EglTest {};

// glIsTexture is only true once a generated name has been bound (ES 3.0 §3.8.1).
Texture boundTexture() {
    auto t = Texture::create();
    glBindTexture(GL_TEXTURE_2D, t.id());
    glBindTexture(GL_TEXTURE_2D, 0);
    return t;
}

bool alive(GLuint texture) {
    return glIsTexture(texture) == GL_TRUE;
}

TEST_F(GlObjectGLTest, CreateGivesALiveNameAndDestructorDeletesIt) {
    GLuint id = 0;
    {
        auto t = boundTexture();
        id = t.id();
        EXPECT_NE(id, 0u);
        EXPECT_TRUE(bool(t));
        EXPECT_TRUE(alive(id));
    }
    EXPECT_FALSE(alive(id));
    EXPECT_GL_OK();
}

TEST_F(GlObjectGLTest, DefaultIsEmptyAndResetIsANoOp) {
    Texture t;
    EXPECT_EQ(t.id(), 0u);
    EXPECT_FALSE(bool(t));
    t.reset();
    t.reset();
    EXPECT_EQ(t.release(), 0u);
    EXPECT_GL_OK();
}

TEST_F(GlObjectGLTest, MoveConstructionTransfersOwnership) {
    auto a = boundTexture();
    const GLuint id = a.id();
    Texture b(std::move(a));
    EXPECT_EQ(a.id(), 0u);  // NOLINT(bugprone-use-after-move): the moved-from state is the point
    EXPECT_FALSE(bool(a));
    EXPECT_EQ(b.id(), id);
    a.reset();  // the moved-from object must not delete b's texture
    EXPECT_TRUE(alive(id));
    b.reset();
    EXPECT_FALSE(alive(id));
    EXPECT_GL_OK();
}

TEST_F(GlObjectGLTest, MoveAssignmentDeletesTheOldName) {
    auto a = boundTexture();
    auto b = boundTexture();
    const GLuint idA = a.id(), idB = b.id();
    ASSERT_NE(idA, idB);
    b = std::move(a);
    EXPECT_FALSE(alive(idB)) << "the overwritten texture leaked";
    EXPECT_TRUE(alive(idA));
    EXPECT_EQ(b.id(), idA);
    EXPECT_EQ(a.id(), 0u);  // NOLINT(bugprone-use-after-move)
    EXPECT_GL_OK();
}

TEST_F(GlObjectGLTest, SelfMoveAssignmentKeepsTheName) {
    auto a = boundTexture();
    const GLuint id = a.id();
    Texture& alias = a;  // through a reference: the self-move the guard exists for
    a = std::move(alias);
    EXPECT_EQ(a.id(), id);
    EXPECT_TRUE(alive(id));
}

TEST_F(GlObjectGLTest, ReleaseHandsOverWithoutDeleting) {
    GLuint id = 0;
    {
        auto t = boundTexture();
        id = t.release();
        EXPECT_EQ(t.id(), 0u);
        EXPECT_FALSE(bool(t));
    }
    EXPECT_TRUE(alive(id)) << "release() must not delete";
    Texture adopted(id);  // adopting the name again makes it owned once more
    adopted.reset();
    EXPECT_FALSE(alive(id));
    EXPECT_GL_OK();
}

TEST_F(GlObjectGLTest, ResetDeletesImmediately) {
    auto t = boundTexture();
    const GLuint id = t.id();
    t.reset();
    EXPECT_EQ(t.id(), 0u);
    EXPECT_FALSE(alive(id));
    EXPECT_GL_OK();
}

// The other traits delete with the right call: each name is alive after binding and gone after
// the owner dies.
TEST_F(GlObjectGLTest, EveryObjectKindIsDeletedWithItsOwner) {
    GLuint buffer = 0, vao = 0, fbo = 0, rbo = 0, program = 0, shader = 0, query = 0;
    {
        auto b = Buffer::create();
        glBindBuffer(GL_ARRAY_BUFFER, b.id());
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        auto v = VertexArray::create();
        glBindVertexArray(v.id());
        glBindVertexArray(0);
        auto f = Framebuffer::create();
        glBindFramebuffer(GL_FRAMEBUFFER, f.id());
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        auto r = Renderbuffer::create();
        glBindRenderbuffer(GL_RENDERBUFFER, r.id());
        glBindRenderbuffer(GL_RENDERBUFFER, 0);
        auto p = Program::create();
        Shader s(glCreateShader(GL_VERTEX_SHADER));
        auto q = Query::create();
        glBeginQuery(GL_ANY_SAMPLES_PASSED, q.id());
        glEndQuery(GL_ANY_SAMPLES_PASSED);
        buffer = b.id(), vao = v.id(), fbo = f.id(), rbo = r.id();
        program = p.id(), shader = s.id(), query = q.id();
        EXPECT_TRUE(glIsBuffer(buffer));
        EXPECT_TRUE(glIsVertexArray(vao));
        EXPECT_TRUE(glIsFramebuffer(fbo));
        EXPECT_TRUE(glIsRenderbuffer(rbo));
        EXPECT_TRUE(glIsProgram(program));
        EXPECT_TRUE(glIsShader(shader));
        EXPECT_TRUE(glIsQuery(query));
        EXPECT_GL_OK();
    }
    EXPECT_FALSE(glIsBuffer(buffer));
    EXPECT_FALSE(glIsVertexArray(vao));
    EXPECT_FALSE(glIsFramebuffer(fbo));
    EXPECT_FALSE(glIsRenderbuffer(rbo));
    EXPECT_FALSE(glIsProgram(program));
    EXPECT_FALSE(glIsShader(shader));
    EXPECT_FALSE(glIsQuery(query));
    EXPECT_GL_OK();
}

}  // namespace
}  // namespace kiosk::gl
