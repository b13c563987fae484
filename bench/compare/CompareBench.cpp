// Comparison-lens benchmark (issue 19): the frame cost of a comparison lens. Renders one
// scenario headless from its camera at a few data times, once as written and once with its
// lenses removed and only the layers drawn outside them (run A) kept - the same flight, same
// run - and prints ONE JSON object: median frame ms of both per size and the lens's share.
//
// usage: bench-compare [SCENARIO] [--sizes 1280x720,1920x1080] [--frames N]
//        (SCENARIO defaults to scenarios/demo/rainier-compare.json; run from the repository root)
#include "runtime/app/FrameStats.h"
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

/** The baseline: no lens, and the layers only a comparison lens's inside showed disabled. */
void withoutLens(config::Scenario& sc) {
    for (const auto& lens : sc.lenses)
        for (const auto& id : lens.insideStack)
            for (auto& l : sc.layers)
                if (l.id == id) l.enabled = false;
    sc.lenses.clear();
}

/** Median ms of `frames` frames at each of 4 data times, every tile resident first. */
double medianMs(app::Session& s, int w, int h, int frames) {
    auto vp = s.viewpointAt(s.startTime(), "");
    const math::Camera cam = app::makeCamera(*vp, s.terrain().bounds(), w, h, 45.0);
    RealClock clock;
    std::vector<double> ms;
    for (int step = 0; step < 4; ++step) {
        const double t = s.startTime() + (s.endTime() - s.startTime()) * (0.2 + 0.2 * step);
        for (int k = 0; k < 20000 && (k == 0 || !s.terrain().settled()); ++k)
            s.drawFrame(cam, t, w, h);
        for (int i = 0; i < frames; ++i) {
            const double t0 = clock.now();
            s.drawFrame(cam, t, w, h);
            glFinish();
            ms.push_back((clock.now() - t0) * 1000.0);
        }
    }
    return app::percentile(ms, 50);
}

}  // namespace

int main(int argc, char** argv) {
    std::string scenario = "scenarios/demo/rainier-compare.json";
    std::vector<std::pair<int, int>> sizes{{1280, 720}, {1920, 1080}};
    int frames = 10;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--frames") && i + 1 < argc) {
            frames = std::max(3, std::atoi(argv[++i]));
        } else if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) {
            sizes.clear();
            std::string list = argv[++i];
            for (std::size_t p = 0; p <= list.size();) {
                const auto q = std::min(list.find(',', p), list.size());
                if (auto wh = parseSize(list.substr(p, q - p))) sizes.push_back(*wh);
                p = q + 1;
            }
        } else if (argv[i][0] != '-') {
            scenario = argv[i];
        } else {
            std::fprintf(stderr,
                         "usage: bench-compare [SCENARIO] [--sizes WxH,...] [--frames N]\n");
            return 2;
        }
    }
    auto headless = bench::openHeadlessGl();
    if (!headless) return 3;
    nlohmann::json out{
        {"benchmark", "comparison-lens"}, {"scenario", scenario}, {"frames", frames}};
    for (const auto& [w, h] : sizes) {
        auto lens = app::Session::open(scenario, headless->caps);
        auto plain = app::Session::open(scenario, headless->caps, withoutLens);
        if (!lens || !plain) {
            std::fprintf(stderr, "%s%s", lens.diagnostics.format().c_str(),
                         plain.diagnostics.format().c_str());
            return 1;
        }
        auto rt = gl::RenderTarget::create(w, h);
        if (!rt) return 3;
        rt->bind();
        // Interleaved twice so a machine getting busier does not favour one side.
        const double a1 = medianMs(**plain, w, h, frames), b1 = medianMs(**lens, w, h, frames);
        const double b2 = medianMs(**lens, w, h, frames), a2 = medianMs(**plain, w, h, frames);
        const double base = std::min(a1, a2), with = std::min(b1, b2);
        out["sizes"].push_back({{"size", std::to_string(w) + "x" + std::to_string(h)},
                                {"without_lens_ms_p50", base},
                                {"with_lens_ms_p50", with},
                                {"lens_cost_percent", 100.0 * (with - base) / base}});
    }
    std::printf("%s\n", out.dump().c_str());
    return 0;
}
