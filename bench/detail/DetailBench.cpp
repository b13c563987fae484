// Procedural detail benchmark (issue 21): a low close-up flight over the demo, rendered headless
// on llvmpipe three times in the same run — detail off (the quadtree alone), detail on with the
// importance-warped grid, and detail on with a regular grid of the same vertex count (the
// comparison of DS04) — and ONE JSON object: per variant frame time p50/p95/mean, triangles per
// frame, frames the detail drew, and the side of the region the grid covered.
//
// usage: bench-detail [SCENARIO] [--size WxH] [--frames N]
#include "runtime/app/Session.h"
#include "runtime/core/Clock.h"
#include "runtime/core/Strings.h"
#include "runtime/gl/RenderTarget.h"

#include "bench/common/HeadlessGl.h"
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace kiosk;

namespace {

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, std::size_t(p * double(v.size() - 1) + 0.5))];
}

double mean(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0 : s / double(v.size());
}

/** The close-up viewpoint flown 3 km along its heading, turning 40 degrees, 150 m lower. */
math::Viewpoint flightView(const math::Viewpoint& start, int i, int n) {
    const double a = double(i) / double(std::max(1, n - 1));
    math::Viewpoint vp = start;
    const double h = glm::radians(start.headingDeg);
    vp.target += glm::dvec3(std::sin(h), std::cos(h), 0.0) * (3000.0 * a);
    vp.headingDeg += 40.0 * a;
    vp.range = start.range - 150.0 * a;
    return vp;
}

nlohmann::json fly(const std::string& scenario, const gl::Caps& caps, int w, int h, int frames,
                   bool detail, int iterations) {
    auto session = app::Session::open(
        scenario, caps, [detail](config::Scenario& sc) { sc.terrain.proceduralDetail = detail; });
    if (!session) {
        std::fprintf(stderr, "%s", session.diagnostics.format().c_str());
        return {};
    }
    app::Session& s = **session;
    s.terrain().setDetailWarpIterations(iterations);
    auto start = s.viewpointAt(s.startTime(), "");
    if (!start) return {};
    RealClock clock;
    std::vector<double> ms, triangles, side;
    int detailFrames = 0;
    for (int i = 0; i < frames; ++i) {
        const math::Camera cam =
            app::makeCamera(flightView(*start, i, frames), s.terrain().bounds(), w, h, 45.0);
        if (i == 0) {  // warm-up: the first view resident, as after start-up
            for (int k = 0; k < 20000 && (k == 0 || !s.terrain().settled()); ++k)
                s.drawFrame(cam, s.startTime(), w, h);
            glFinish();
        }
        const double t0 = clock.now();
        const auto rec = s.drawFrame(cam, s.startTime(), w, h);
        glFinish();
        ms.push_back((clock.now() - t0) * 1000.0);
        triangles.push_back(double(rec.triangles));
        glm::dvec2 lo, hi;
        if (s.terrain().detailHole(lo, hi)) {
            ++detailFrames;
            side.push_back(hi.x - lo.x);
        }
    }
    nlohmann::json r;
    r["frame_ms_p50"] = percentile(ms, 0.5);
    r["frame_ms_p95"] = percentile(ms, 0.95);
    r["frame_ms_mean"] = mean(ms);
    r["triangles_mean"] = mean(triangles);
    r["detail_frames"] = detailFrames;
    r["detail_region_m_mean"] = mean(side);
    return r;
}

}  // namespace

int main(int argc, char** argv) {
    std::string scenario = "scenarios/demo/rainier-closeup.json";
    int w = 1280, h = 720, frames = 40;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
            frames = std::max(2, std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "--size") && i + 1 < argc) {
            if (auto wh = parseSize(argv[++i])) std::tie(w, h) = *wh;
        } else
            scenario = argv[i];
    }
    auto headless = bench::openHeadlessGl();
    if (!headless) return 3;
    auto target = gl::RenderTarget::create(w, h);
    if (!target) return 3;
    target->bind();
    nlohmann::json out;
    out["benchmark"] = "procedural_detail";
    out["scenario"] = scenario;
    out["renderer"] = headless->caps.renderer;
    out["size"] = std::to_string(w) + "x" + std::to_string(h);
    out["frames"] = frames;
    out["grid_vertices"] = 161 * 161;
    out["detail_off"] = fly(scenario, headless->caps, w, h, frames, false, 2);
    out["detail_warped"] = fly(scenario, headless->caps, w, h, frames, true, 2);
    out["detail_uniform_grid"] = fly(scenario, headless->caps, w, h, frames, true, 0);
    if (out["detail_off"].is_null() || out["detail_warped"].is_null()) return 1;
    std::printf("%s\n", out.dump().c_str());
    return 0;
}
