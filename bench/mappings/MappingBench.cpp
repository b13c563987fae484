// Projective-mapping benchmark (issue 8): the paper's Table 1 on this machine. Renders the
// terrain of a scenario from a fixed view with 0 (off), 1, 4, 16, 27 and 64 symbol mappings
// tiled over the visible area, at each size, and prints ONE JSON object: fps with mappings off
// and on, the on/off ratio, and the llvmpipe fill bound measured in the same run (a full-screen
// quad with the stack's texture fetches per pixel, and with one more per mapping).
//
// usage: bench-mappings [SCENARIO] [--sizes 1280x720,1920x1080] [--frames N] [--counts 1,4,...]
//        (SCENARIO defaults to scenarios/mappings/common.json; run from the repository root)
#include "bench/common/HeadlessGl.h"
#include "runtime/app/FrameStats.h"
#include "runtime/app/Session.h"
#include "runtime/core/Clock.h"
#include "runtime/core/Strings.h"
#include "runtime/gl/Context.h"
#include "runtime/gl/RenderTarget.h"
#include "runtime/platform/Display.h"
#include "runtime/render/FillBound.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

using namespace kiosk;

namespace {

/**
 * max(counts) symbol mappings on a ceil(sqrt n) grid covering `extent` around `centre`; mapping
 * i is opaque at clock offset 60 s * k when i < counts[k] and transparent (culled, not
 * uploaded) otherwise, so one session - settled once - measures every count.
 */
void addMappings(config::Scenario& sc, const std::vector<int>& counts, glm::dvec2 centre,
                 double extent, const std::filesystem::path& atlas) {
    sc.projectiveMappings.clear();
    const int n = *std::max_element(counts.begin(), counts.end());
    const int side = int(std::ceil(std::sqrt(double(n))));
    const double cell = extent / side;
    for (int i = 0; i < n; ++i) {
        config::ProjectiveMapping m;
        m.id = "bench-" + std::to_string(i);
        const int cx = i % side, cy = i / side;
        m.origin = {centre.x - extent / 2 + (cx + 0.5) * cell,
                    centre.y - extent / 2 + (cy + 0.5) * cell, 0.0};
        m.u = {cell, 0, 0};
        m.v = {0, cell, 0};
        // Cycle through the four atlas cells.
        const double col = (i % 2) * 0.5, row = ((i / 2) % 2) * 0.5;
        m.textureMatrix = {0.5, 0, col, 0, 0.5, row, 0, 0, 1};
        m.image = atlas;
        for (std::size_t k = 0; k < counts.size(); ++k) {
            config::MappingKey key;
            key.time.isOffset = true;
            key.time.seconds = 60.0 * double(k);
            key.opacity = i < counts[k] ? 1.0 : 0.0;
            m.keys.push_back(key);
        }
        sc.projectiveMappings.push_back(m);
    }
}

double medianFrameMs(app::Session& s, const math::Camera& cam, double t, int w, int h, int frames,
                     std::uint32_t* active) {
    for (int k = 0; k < 20000 && !s.terrain().settled(); ++k) s.drawFrame(cam, t, w, h);
    RealClock clock;
    std::vector<double> ms;
    for (int i = 0; i < frames; ++i) {
        const double t0 = clock.now();
        auto rec = s.drawFrame(cam, t, w, h);
        glFinish();
        ms.push_back((clock.now() - t0) * 1000.0);
        if (active) *active = rec.mappingsActive;
    }
    return app::percentile(ms, 50);
}

double fillBoundMs(int fetches) {
    auto fill = render::FillBound::create(fetches);
    if (!fill) return -1.0;
    RealClock clock;
    std::vector<double> ms;
    for (int i = 0; i < 20; ++i) {
        const double t0 = clock.now();
        glClear(GL_COLOR_BUFFER_BIT);
        fill->draw();
        glFinish();
        ms.push_back((clock.now() - t0) * 1000.0);
    }
    return app::percentile(ms, 50);
}

std::vector<std::string> splitList(const std::string& list) {
    std::vector<std::string> out;
    for (std::size_t p = 0; p <= list.size();) {
        auto q = list.find(',', p);
        if (q == std::string::npos) q = list.size();
        if (q > p) out.push_back(list.substr(p, q - p));
        p = q + 1;
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    std::string scenario = "scenarios/mappings/common.json";
    std::vector<std::pair<int, int>> sizes{{1280, 720}, {1920, 1080}};
    std::vector<int> counts{1, 4, 16, 27, 64};
    int frames = 5;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--frames") && i + 1 < argc) {
            frames = std::max(3, std::atoi(argv[++i]));
        } else if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) {
            sizes.clear();
            for (const auto& s : splitList(argv[++i]))
                if (auto wh = parseSize(s)) sizes.push_back(*wh);
        } else if (!std::strcmp(argv[i], "--counts") && i + 1 < argc) {
            counts.clear();
            for (const auto& s : splitList(argv[++i]))
                counts.push_back(std::max(1, std::atoi(s.c_str())));
        } else if (argv[i][0] != '-') {
            scenario = argv[i];
        } else {
            std::fprintf(stderr,
                         "usage: bench-mappings [SCENARIO] [--sizes WxH,...] [--frames N] "
                         "[--counts 1,4,...]\n");
            return 2;
        }
    }
    const auto atlas = std::filesystem::absolute("data/mappings/symbols.png");
    auto headless = bench::openHeadlessGl();
    if (!headless) return 3;
    const gl::Caps* caps = &headless->caps;
    // The view of the symbols scenario: about 30 km of terrain across, all mappings inside.
    const math::Viewpoint view{{596000, 5181000, 1200}, 0, -50, 36000};
    const glm::dvec2 centre(596000, 5183000);
    const double extent = 24000;

    nlohmann::json out;
    out["benchmark"] = "mappings";
    out["scenario"] = scenario;
    out["renderer"] = caps->renderer;
    out["frames"] = frames;
    out["max_uniform_block_size"] = caps->maxUniformBlockSize;
    out["max_array_texture_layers"] = caps->maxArrayLayers;
    for (auto [w, h] : sizes) {
        auto target = gl::RenderTarget::create(w, h);
        if (!target) return 3;
        target->bind();
        nlohmann::json r;
        r["size"] = std::to_string(w) + "x" + std::to_string(h);
        double offMs = 0;
        std::size_t layers = 0;
        {
            auto s = app::Session::open(
                scenario, *caps, [&](config::Scenario& sc) { sc.projectiveMappings.clear(); });
            if (!s) {
                std::fprintf(stderr, "%s", s.diagnostics.format().c_str());
                return 1;
            }
            layers = (*s)->scenario().layers.size();
            const auto cam = app::makeCamera(view, (*s)->terrain().bounds(), w, h, 45.0);
            offMs = medianFrameMs(**s, cam, (*s)->startTime(), w, h, frames, nullptr);
        }
        r["off"] = {{"frame_ms_p50", offMs}, {"fps", 1000.0 / std::max(1e-9, offMs)}};
        const double fill0 = fillBoundMs(int(layers) + 1);
        r["fill_bound_ms"] = fill0;
        r["fill_bound_fetches_per_pixel"] = int(layers) + 1;
        std::vector<int> stages{0};
        stages.insert(stages.end(), counts.begin(), counts.end());
        auto s = app::Session::open(scenario, *caps, [&](config::Scenario& sc) {
            addMappings(sc, stages, centre, extent, atlas);
        });
        if (!s) {
            std::fprintf(stderr, "%s", s.diagnostics.format().c_str());
            return 1;
        }
        const auto cam = app::makeCamera(view, (*s)->terrain().bounds(), w, h, 45.0);
        std::uint32_t active = 0;
        // Stage 0: the mapping program with nothing active (settles the tiles cheaply).
        const double zeroMs = medianFrameMs(**s, cam, (*s)->startTime(), w, h, frames, &active);
        r["program_with_no_active_mappings_ms_p50"] = zeroMs;
        for (std::size_t k = 1; k < stages.size(); ++k) {
            const int n = stages[k];
            const double ms = medianFrameMs(**s, cam, (*s)->startTime() + 60.0 * double(k), w, h,
                                            frames, &active);
            const double fillN = fillBoundMs(int(layers) + 1 + n);
            r["on"].push_back({{"mappings", n},
                               {"active", active},
                               {"frame_ms_p50", ms},
                               {"fps", 1000.0 / std::max(1e-9, ms)},
                               {"ratio_to_off", ms / std::max(1e-9, offMs)},
                               {"fill_bound_ms", fillN},
                               {"fill_bound_fetches_per_pixel", int(layers) + 1 + n},
                               {"ratio_to_fill_bound", ms / std::max(1e-9, fillN)}});
            // Issue 12's goal: one mapping costs at most 1.3x the frame without mappings.
            if (n == 1) {
                r["one_mapping_ratio"] = ms / std::max(1e-9, offMs);
                r["one_mapping_within_1_3x"] = ms <= 1.3 * offMs;
            }
        }
        out["results"].push_back(r);
    }
    std::printf("%s\n", out.dump().c_str());
    return 0;
}
