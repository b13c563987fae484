// Occlusion culling benchmark (issue 20; docs/terrain.md §10): per oblique view of a scenario,
// tiles drawn and frame time with culling on and off, the same session, the same resident
// tiles, passes alternating between the two so machine load hits both alike. Prints ONE JSON
// object (the baseline, culling off, measured in the same run).
//
// usage: bench-occlusion SCENARIO [--view X,Y,Z,HEADING,PITCH,RANGE]... [--size WxH]
//                        [--frames N] [--passes N]
// Without --view: three low views (pitch -4) at the terrain's centre, headings 0, 120, 240.
#include "runtime/app/FrameStats.h"
#include "runtime/app/Session.h"
#include "runtime/core/Clock.h"
#include "runtime/core/Strings.h"
#include "runtime/gl/RenderTarget.h"

#include "bench/common/BenchArgs.h"
#include "bench/common/BenchScene.h"
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace kiosk;

namespace {

struct Mode {
    std::vector<double> frameMs, occlusionMs;
    scene::SceneFrameInfo last;
};

void frames(app::Session& s, const math::Camera& cam, int w, int h, int n, Mode& m) {
    RealClock clock;
    for (int i = 0; i < n; ++i) {
        const double t0 = clock.now();
        s.drawFrame(cam, s.startTime(), w, h);
        glFinish();
        m.frameMs.push_back((clock.now() - t0) * 1000.0);
        m.occlusionMs.push_back(s.terrain().frameInfo().occlusionMs);
        m.last = s.terrain().frameInfo();
    }
}

nlohmann::json report(const Mode& m) {
    return {{"tiles_drawn", m.last.tilesDrawn},
            {"tiles_occluded", m.last.tilesOccluded},
            {"triangles", m.last.triangles},
            {"occlusion_queries", m.last.occlusionQueries},
            {"occlusion_rounds", m.last.occlusionRounds},
            {"frame_ms_p50", app::percentile(m.frameMs, 50)},
            {"frame_ms_min", *std::min_element(m.frameMs.begin(), m.frameMs.end())},
            {"occlusion_ms_p50", app::percentile(m.occlusionMs, 50)}};
}

}  // namespace

int main(int argc, char** argv) {
    bench::ViewBenchArgs args;
    if (!bench::parseViewBenchArgs(argc, argv, "bench-occlusion", args)) {
        std::fprintf(stderr,
                     "usage: bench-occlusion SCENARIO [--view X,Y,Z,HEADING,PITCH,RANGE]... "
                     "[--size WxH] [--frames N] [--passes N]\n");
        return 2;
    }
    const std::string& scenario = args.scenario;
    std::vector<math::Viewpoint>& views = args.views;
    const int w = args.width, h = args.height, perPass = args.frames, passes = args.passes;
    auto scene = bench::openBenchScene(scenario, w, h);
    if (!scene) return scene.exitCode;
    app::Session& s = scene.s();
    const math::Aabb b = s.terrain().bounds();
    if (views.empty()) {
        const glm::dvec3 c = b.center();
        const double extent = std::max(b.max.x - b.min.x, b.max.y - b.min.y);
        for (double heading : {0.0, 120.0, 240.0})
            views.push_back({glm::dvec3(c.x, c.y, b.min.z + 0.5 * (b.max.z - b.min.z)), heading,
                             -4.0, 0.2 * extent});
    }
    nlohmann::json out;
    out["benchmark"] = "occlusion";
    out["scenario"] = scenario;
    out["renderer"] = scene.gl.caps.renderer;
    out["size"] = std::to_string(w) + "x" + std::to_string(h);
    out["frames_per_pass"] = perPass;
    out["passes"] = passes;
    for (const auto& vp : views) {
        const math::Camera cam = app::makeCamera(vp, b, w, h, s.scenario().camera.fovY);
        // Warm-up: every tile of the view resident, as a kiosk is after start-up.
        for (int k = 0; k < 20000 && (k == 0 || !s.terrain().settled()); ++k)
            s.prepare(cam, s.startTime());
        Mode on, off;
        for (int p = 0; p < passes; ++p) {
            s.terrain().setOcclusionCulling(true);
            frames(s, cam, w, h, perPass, on);
            s.terrain().setOcclusionCulling(false);
            frames(s, cam, w, h, perPass, off);
        }
        s.terrain().setOcclusionCulling(true);
        nlohmann::json r;
        r["view"] = {vp.target.x, vp.target.y, vp.target.z, vp.headingDeg, vp.pitchDeg, vp.range};
        r["settled"] = s.terrain().settled();
        r["culling_on"] = report(on);
        r["culling_off_baseline"] = report(off);
        r["frame_time_ratio_on_over_off"] =
            app::percentile(on.frameMs, 50) / std::max(1e-9, app::percentile(off.frameMs, 50));
        out["views"].push_back(r);
    }
    std::printf("%s\n", out.dump().c_str());
    return 0;
}
