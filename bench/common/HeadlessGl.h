#pragma once
// A benchmark's GL: a headless (surfaceless llvmpipe) display and its context, held for the
// whole run. On failure the reason goes to stderr and the caller exits 3 ("cannot run here",
// docs/cli.md).

#include "runtime/gl/Context.h"
#include "runtime/platform/Display.h"

#include <cstdio>
#include <memory>
#include <optional>

namespace kiosk::bench {

struct HeadlessGl {
    std::unique_ptr<platform::Display> display;
    gl::Caps caps;
};

inline std::optional<HeadlessGl> openHeadlessGl() {
    platform::DisplayOptions options;
    options.kind = platform::DisplayKind::Headless;
    auto display = platform::createDisplay(options);
    if (!display) {
        std::fprintf(stderr, "%s", display.diagnostics.format().c_str());
        return std::nullopt;
    }
    auto caps = gl::initContext();
    if (!caps) {
        std::fprintf(stderr, "%s", caps.diagnostics.format().c_str());
        return std::nullopt;
    }
    return HeadlessGl{std::move(*display.value), *caps.value};
}

}  // namespace kiosk::bench
