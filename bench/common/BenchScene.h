#pragma once
// A benchmark's scene: the headless GL, an offscreen target of the benchmark's size (bound) and
// the scenario's session, opened in that order and destroyed in reverse (the session's GL objects
// before the context). On failure the reason goes to stderr and `exitCode` is what the benchmark
// exits with: 3 cannot run here (no GL, no target), 1 the scenario failed (docs/cli.md).

#include "runtime/app/Session.h"
#include "runtime/gl/RenderTarget.h"

#include "bench/common/HeadlessGl.h"

#include <cstdio>
#include <memory>
#include <optional>
#include <string>

namespace kiosk::bench {

struct BenchScene {
    HeadlessGl gl;
    std::optional<gl::RenderTarget> target;
    std::unique_ptr<app::Session> session;
    int exitCode = 0;

    explicit operator bool() const noexcept { return exitCode == 0; }
    app::Session& s() { return *session; }
};

inline BenchScene openBenchScene(const std::string& scenario, int width, int height) {
    BenchScene scene;
    auto headless = openHeadlessGl();
    if (!headless) {
        scene.exitCode = 3;
        return scene;
    }
    scene.gl = std::move(*headless);
    auto target = gl::RenderTarget::create(width, height);
    if (!target) {
        std::fprintf(stderr, "%s", target.diagnostics.format().c_str());
        scene.exitCode = 3;
        return scene;
    }
    scene.target = std::move(*target.value);
    scene.target->bind();
    auto session = app::Session::open(scenario, scene.gl.caps);
    if (!session) {
        std::fprintf(stderr, "%s", session.diagnostics.format().c_str());
        scene.exitCode = 1;
        return scene;
    }
    scene.session = std::move(*session.value);
    return scene;
}

}  // namespace kiosk::bench
