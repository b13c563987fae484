// Impostor measurement (issue 20, Wahl et al. 2004 §5; docs/terrain.md §12): could replacing
// far terrain by impostors (textured quads) win on llvmpipe? Per view and far distance D:
//   all     frame time with every selected tile drawn,
//   near    the same view with the far plane at D: the terrain beyond D is not drawn at all
//           (what any impostor scheme saves at most: all - near),
//   quad    the cheapest impostor over the same pixels: a one-fetch textured quad covering the
//           far terrain's pixel count (scissored FillBound), drawn after the near frame.
// An impostor can win only if (all - near) > quad; it must also re-render its texture whenever
// parallax exceeds the error bound, which this upper bound leaves out. Prints ONE JSON object.
//
// usage: bench-impostor SCENARIO [--view X,Y,Z,HEADING,PITCH,RANGE]... [--far M,...]
//                       [--size WxH] [--frames N] [--passes N]
#include "runtime/app/FrameStats.h"
#include "runtime/app/Session.h"
#include "runtime/core/Clock.h"
#include "runtime/core/Strings.h"
#include "runtime/gl/RenderTarget.h"
#include "runtime/render/FillBound.h"

#include "bench/common/BenchArgs.h"
#include "bench/common/BenchScene.h"
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace kiosk;

namespace {

/** Pixels that are not the clear colour (terrain and overlays). */
long long paintedPixels(const gl::Image& img) {
    long long n = 0;
    for (std::size_t i = 0; i + 3 < img.rgba.size(); i += 4) {
        const int r = img.rgba[i], g = img.rgba[i + 1], b = img.rgba[i + 2];
        n += (std::abs(r - 158) > 2 || std::abs(g - 181) > 2 || std::abs(b - 204) > 2) ? 1 : 0;
    }
    return n;
}

/** Settle the view, draw two untimed frames (first-use costs), then time `n` frames. */
std::vector<double> timeFrames(app::Session& s, const math::Camera& cam, int w, int h, int n) {
    for (int k = 0; k < 20000 && (k == 0 || !s.terrain().settled()); ++k)
        s.prepare(cam, s.startTime());
    for (int i = 0; i < 2; ++i) s.drawFrame(cam, s.startTime(), w, h);
    glFinish();
    RealClock clock;
    std::vector<double> ms;
    for (int i = 0; i < n; ++i) {
        const double t0 = clock.now();
        s.drawFrame(cam, s.startTime(), w, h);
        glFinish();
        ms.push_back((clock.now() - t0) * 1000.0);
    }
    return ms;
}

double best(const std::vector<double>& v) {
    return *std::min_element(v.begin(), v.end());
}

}  // namespace

int main(int argc, char** argv) {
    bench::ViewBenchArgs args;
    args.frames = 3;
    args.passes = 3;
    std::vector<double> fars;
    const auto farList = [&fars](const char* opt, const char* value) {
        if (std::strcmp(opt, "--far")) return false;
        for (const char* p = value; *p;) {
            char* end = nullptr;
            const double d = std::strtod(p, &end);
            if (end == p || !(d > 0)) return false;
            fars.push_back(d);
            p = *end == ',' ? end + 1 : end;
        }
        return true;
    };
    if (!bench::parseViewBenchArgs(argc, argv, "bench-impostor", args, farList)) {
        std::fprintf(stderr,
                     "usage: bench-impostor SCENARIO [--view X,Y,Z,HEADING,PITCH,RANGE]... "
                     "[--far M,...] [--size WxH] [--frames N] [--passes N]\n");
        return 2;
    }
    const std::string& scenario = args.scenario;
    std::vector<math::Viewpoint>& views = args.views;
    const int w = args.width, h = args.height, frames = args.frames, passes = args.passes;
    auto scene = bench::openBenchScene(scenario, w, h);
    if (!scene) return scene.exitCode;
    const gl::RenderTarget& target = *scene.target;
    app::Session& s = scene.s();
    auto quad = render::FillBound::create(1);
    if (!quad) {
        std::fprintf(stderr, "%s", quad.diagnostics.format().c_str());
        return 3;
    }
    const math::Aabb b = s.terrain().bounds();
    if (views.empty()) views.push_back(s.terrain().overviewViewpoint());
    nlohmann::json out;
    out["benchmark"] = "impostor";
    out["scenario"] = scenario;
    out["renderer"] = scene.gl.caps.renderer;
    out["size"] = std::to_string(w) + "x" + std::to_string(h);
    out["frames_per_pass"] = frames;
    out["passes"] = passes;
    for (const auto& vp : views) {
        const math::Camera cam = app::makeCamera(vp, b, w, h, s.scenario().camera.fovY);
        std::vector<double> cuts = fars;
        if (cuts.empty()) {
            double farthest = 0;
            for (int c = 0; c < 8; ++c)
                farthest = std::max(farthest, glm::length(glm::dvec3((c & 1) ? b.max.x : b.min.x,
                                                                     (c & 2) ? b.max.y : b.min.y,
                                                                     (c & 4) ? b.max.z : b.min.z) -
                                                          cam.eye));
            // Between the near plane and the farthest terrain (an overview's near plane is far).
            const double n0 = cam.nearPlane;
            cuts = {n0 + 0.5 * (farthest - n0), n0 + 0.75 * (farthest - n0)};
        }
        s.drawFrame(cam, s.startTime(), w, h);
        timeFrames(s, cam, w, h, 1);
        const long long paintedAll = paintedPixels(target.readColor());
        const scene::SceneFrameInfo allInfo = s.terrain().frameInfo();
        nlohmann::json v;
        v["view"] = {vp.target.x, vp.target.y, vp.target.z, vp.headingDeg, vp.pitchDeg, vp.range};
        v["all"] = {{"tiles_drawn", allInfo.tilesDrawn}, {"triangles", allInfo.triangles}};
        for (double d : cuts) {
            math::Camera nearCam = cam;
            nearCam.farPlane = std::max(d, nearCam.nearPlane * 2.0);
            timeFrames(s, nearCam, w, h, 1);
            const long long farPixels =
                std::max(0LL, paintedAll - paintedPixels(target.readColor()));
            const scene::SceneFrameInfo nearInfo = s.terrain().frameInfo();
            // Alternating passes: this VM's load swings hit both alike; the best frames count.
            std::vector<double> allMs, nearMs;
            for (int p = 0; p < passes; ++p) {
                const auto a = timeFrames(s, cam, w, h, frames);
                const auto n = timeFrames(s, nearCam, w, h, frames);
                allMs.insert(allMs.end(), a.begin(), a.end());
                nearMs.insert(nearMs.end(), n.begin(), n.end());
            }
            // The impostor's pixels: a full-width band of the same area, one texture fetch each.
            const int rows = int(std::min<long long>(h, (farPixels + w - 1) / w));
            RealClock clock;
            std::vector<double> quadMs;
            for (int i = 0; i < frames; ++i) {
                glFinish();
                const double t0 = clock.now();
                glEnable(GL_SCISSOR_TEST);
                glScissor(0, h - rows, w, rows);
                quad->draw();
                glDisable(GL_SCISSOR_TEST);
                glFinish();
                quadMs.push_back((clock.now() - t0) * 1000.0);
            }
            const double saved = best(allMs) - best(nearMs);
            v["far"].push_back({{"far_plane_m", nearCam.farPlane},
                                {"all_frame_ms_best", best(allMs)},
                                {"all_frame_ms_p50", app::percentile(allMs, 50)},
                                {"near_frame_ms_best", best(nearMs)},
                                {"near_frame_ms_p50", app::percentile(nearMs, 50)},
                                {"near_tiles_drawn", nearInfo.tilesDrawn},
                                {"near_triangles", nearInfo.triangles},
                                {"far_pixels", farPixels},
                                {"upper_bound_saving_ms", saved},
                                {"impostor_quad_ms_best", best(quadMs)},
                                {"impostor_net_win_ms_at_most", saved - best(quadMs)}});
        }
        out["views"].push_back(v);
    }
    std::printf("%s\n", out.dump().c_str());
    return 0;
}
