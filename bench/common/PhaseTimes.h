#pragma once
// Per-phase frame timings for the benchmarks (bench-only): where a frame's time went on the
// main thread (update = select + uploads, draw submission, overlays) and what was left waiting
// for llvmpipe's rasterizer threads (finish = glFinish after drawFrame). Spikes are listed with
// their phases so a long frame can be attributed, not just counted.
#include <sys/resource.h>

#include <algorithm>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <vector>

#include "runtime/app/FrameStats.h"

namespace kiosk::bench {

struct PhaseSample {
    double frameMs = 0, updateMs = 0, uploadMs = 0, drawMs = 0, overlayMs = 0, finishMs = 0;
    std::uint32_t uploads = 0;
    /** @brief CPU time of the whole process (all threads) during the frame: a frame whose
     * wall time grew but whose CPU time did not was waiting for other jobs on the machine. */
    double cpuMs = 0;
    std::uint64_t triangles = 0;
};

/** @brief CPU time used so far by every thread of the process (ms). */
inline double processCpuMs() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return (double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) * 1e3 +
            double(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-3);
}

/** @brief A sample from a drawFrame() record and the whole frame's wall time (finish = rest). */
inline PhaseSample phaseSample(const app::FrameRecord& r, double frameMs, double cpuMs = 0) {
    PhaseSample s;
    s.frameMs = frameMs;
    s.cpuMs = cpuMs;
    s.triangles = r.triangles;
    s.updateMs = r.updateMs;
    s.uploadMs = r.uploadMs;
    s.uploads = r.uploads;
    s.drawMs = r.drawMs;
    s.overlayMs = r.overlayMs;
    s.finishMs = std::max(0.0, frameMs - r.updateMs - r.drawMs - r.overlayMs);
    return s;
}

/**
 * @brief {"phase_ms": {phase: {p50, p95, p99, max}}, "frame_ms_max", "spikes": [...]}: spikes
 * are the frames slower than 1.5x the median (worst first, at most `maxSpikes`).
 */
inline nlohmann::json phaseReport(const std::vector<PhaseSample>& v, std::size_t maxSpikes = 8) {
    nlohmann::json out;
    if (v.empty()) return out;
    auto stats = [&](double PhaseSample::*m) {
        std::vector<double> x;
        for (const auto& s : v) x.push_back(s.*m);
        return nlohmann::json{{"p50", app::percentile(x, 50)},
                              {"p95", app::percentile(x, 95)},
                              {"p99", app::percentile(x, 99)},
                              {"max", *std::max_element(x.begin(), x.end())}};
    };
    out["phase_ms"] = {{"update", stats(&PhaseSample::updateMs)},
                       {"upload", stats(&PhaseSample::uploadMs)},
                       {"draw", stats(&PhaseSample::drawMs)},
                       {"overlay", stats(&PhaseSample::overlayMs)},
                       {"finish", stats(&PhaseSample::finishMs)},
                       {"process_cpu", stats(&PhaseSample::cpuMs)}};
    std::vector<double> frame;
    for (const auto& s : v) frame.push_back(s.frameMs);
    const double median = app::percentile(frame, 50);
    out["frame_ms_max"] = *std::max_element(frame.begin(), frame.end());
    std::vector<std::size_t> idx;
    for (std::size_t i = 0; i < v.size(); ++i)
        if (v[i].frameMs > 1.5 * median) idx.push_back(i);
    std::sort(idx.begin(), idx.end(),
              [&](std::size_t a, std::size_t b) { return v[a].frameMs > v[b].frameMs; });
    out["spike_frames"] = idx.size();
    out["spikes"] = nlohmann::json::array();
    for (std::size_t k = 0; k < std::min(idx.size(), maxSpikes); ++k) {
        const auto& s = v[idx[k]];
        out["spikes"].push_back({{"frame", idx[k]},
                                 {"ms", s.frameMs},
                                 {"update", s.updateMs},
                                 {"upload", s.uploadMs},
                                 {"uploads", s.uploads},
                                 {"draw", s.drawMs},
                                 {"overlay", s.overlayMs},
                                 {"finish", s.finishMs},
                                 {"process_cpu", s.cpuMs},
                                 {"triangles", s.triangles}});
    }
    return out;
}

}  // namespace kiosk::bench
