#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "runtime/gl/Context.h"
#include "runtime/gl/RenderTarget.h"
#include "runtime/platform/Display.h"

namespace kiosk::test {

/**
 * @brief GoogleTest fixture with a current surfaceless OpenGL ES 3 context (Mesa llvmpipe).
 * Without EGL the test is skipped with the reason, unless KIOSK_REQUIRE_GL=1 (CI), which turns
 * the skip into a failure (Filament's SKIP_IF, made strict).
 */
class EglTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;

    /** @brief Offscreen target, bound, viewport set. */
    gl::RenderTarget makeTarget(int width, int height);

    std::unique_ptr<platform::Display> mDisplay;
    gl::Caps mCaps;
};

/** @brief True when KIOSK_REQUIRE_GL=1. */
bool glRequired();

/** @brief Skip (or fail under KIOSK_REQUIRE_GL / KIOSK_REQUIRE_DATA) with a message. */
#define KIOSK_SKIP_OR_FAIL(requiredVar, reason)                                             \
    do {                                                                                    \
        if (::kiosk::test::envFlag(requiredVar)) FAIL() << (reason) << " (" requiredVar "=1)"; \
        GTEST_SKIP() << (reason);                                                           \
    } while (0)

bool envFlag(const char* name);

/** @brief Expect no pending GL error (Magnum's MAGNUM_VERIFY_NO_GL_ERROR). */
#define EXPECT_GL_OK()                                                          \
    do {                                                                        \
        unsigned err_ = glGetError();                                           \
        EXPECT_EQ(err_, 0u) << "GL error " << ::kiosk::gl::glErrorName(err_);   \
    } while (0)

/** @brief Path to ../shared/data/<rel>, or empty if the shared data set is absent. */
std::string sharedData(const std::string& rel);

}  // namespace kiosk::test
