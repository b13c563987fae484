// RGBA -> YUV 4:2:0 for the video export (issue 18): the export's own BT.709 converter
// (runtime/export/Yuv420.h) against the previous code path, libswscale with the flags the export
// used (bicubic, accurate rounding, full chroma interpolation), on the same 1080p frame in the
// same run. ONE JSON object: ms per frame (median and best of --rounds) of each, the speed-up,
// and the largest difference in code values between the two (luma and chroma).
//
// usage: bench-yuv420 [--size 1920x1080] [--rounds 30]
#include "runtime/export/Yuv420.h"

#include "bench/common/SteadyTime.h"
#include <nlohmann/json.hpp>

extern "C" {
#include <libavutil/pixfmt.h>
#include <libswscale/swscale.h>
}

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace {

struct Planes {
    int w, h;
    std::vector<std::uint8_t> y, u, v;
    Planes(int width, int height)
        : w(width), h(height), y(std::size_t(w * h)), u(std::size_t(w * h / 4)), v(u) {}
};

// A terrain-like frame: smooth colour ramps with per-pixel noise (the loops do not depend on
// the content; the noise only keeps the comparison of the two converters honest).
std::vector<std::uint8_t> frame(int w, int h) {
    std::vector<std::uint8_t> px(std::size_t(w) * std::size_t(h) * 4);
    std::mt19937 rng(1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::uint8_t* p = px.data() + (std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4;
            const int n = int(rng() % 17) - 8;
            p[0] = std::uint8_t(std::clamp(x * 255 / w + n, 0, 255));
            p[1] = std::uint8_t(std::clamp(y * 255 / h - n, 0, 255));
            p[2] = std::uint8_t(std::clamp((x + y) * 255 / (w + h) + n, 0, 255));
            p[3] = 255;
        }
    return px;
}

template <class F>
std::pair<double, double> time(int rounds, F&& f) {
    std::vector<double> ms;
    for (int i = 0; i < rounds; ++i) {
        const double t0 = kiosk::bench::nowUs();
        f();
        ms.push_back((kiosk::bench::nowUs() - t0) / 1000.0);
    }
    std::sort(ms.begin(), ms.end());
    return {ms[ms.size() / 2], ms.front()};
}

int maxDiff(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
    int d = 0;
    for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(int(a[i]) - int(b[i])));
    return d;
}

}  // namespace

int main(int argc, char** argv) {
    int w = 1920, h = 1080, rounds = 30;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string a = argv[i];
        if (a == "--size" && std::sscanf(argv[i + 1], "%dx%d", &w, &h) == 2 && w > 1 && h > 1 &&
            w % 2 == 0 && h % 2 == 0)
            continue;
        if (a == "--rounds" && (rounds = std::atoi(argv[i + 1])) > 0) continue;
        std::fprintf(stderr, "usage: bench-yuv420 [--size WxH (even)] [--rounds N]\n");
        return 2;
    }
    const std::vector<std::uint8_t> rgba = frame(w, h);
    Planes own(w, h), sws(w, h);

    SwsContext* ctx = sws_getContext(w, h, AV_PIX_FMT_RGBA, w, h, AV_PIX_FMT_YUV420P,
                                     SWS_BICUBIC | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT, nullptr,
                                     nullptr, nullptr);
    const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
    if (!ctx || sws_setColorspaceDetails(ctx, bt709, 1, bt709, 0, 0, 1 << 16, 1 << 16) < 0) {
        std::fprintf(stderr, "bench-yuv420: cannot set up libswscale\n");
        return 3;
    }
    // Both read the frame bottom row first, as the export hands over glReadPixels' rows.
    const std::uint8_t* src[1] = {rgba.data() + std::size_t(h - 1) * std::size_t(w) * 4};
    const int stride[1] = {-w * 4};
    std::uint8_t* dst[3] = {sws.y.data(), sws.u.data(), sws.v.data()};
    const int dstStride[3] = {w, w / 2, w / 2};
    const kiosk::video::Yuv420Planes planes{own.y.data(), own.u.data(), own.v.data(), w,
                                            w / 2,        w / 2};

    // Interleaved so that both see the same machine load.
    std::pair<double, double> ownMs{1e300, 1e300}, swsMs{1e300, 1e300};  // median, best
    for (int r = 0; r < 3; ++r) {
        const auto o =
            time(rounds, [&] { kiosk::video::rgbaToYuv420Bt709(rgba.data(), w, h, planes); });
        const auto s = time(rounds, [&] { sws_scale(ctx, src, stride, 0, h, dst, dstStride); });
        if (o.second < ownMs.second) ownMs = o;  // the round least disturbed by other jobs
        if (s.second < swsMs.second) swsMs = s;
    }
    const auto [ownMedian, ownBest] = ownMs;
    const auto [swsMedian, swsBest] = swsMs;
    sws_freeContext(ctx);

    nlohmann::json j;
    j["bench"] = "yuv420";
    j["size"] = std::to_string(w) + "x" + std::to_string(h);
    j["rounds"] = rounds;
    j["own_ms"] = {{"median", ownMedian}, {"best", ownBest}};
    j["swscale_ms"] = {{"median", swsMedian}, {"best", swsBest}};
    j["speedup_median"] = swsMedian / ownMedian;
    j["max_diff_luma"] = maxDiff(own.y, sws.y);
    j["max_diff_chroma"] = std::max(maxDiff(own.u, sws.u), maxDiff(own.v, sws.v));
    std::printf("%s\n", j.dump().c_str());
    return 0;
}
