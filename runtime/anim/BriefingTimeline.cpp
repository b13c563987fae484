#include "runtime/anim/BriefingTimeline.h"

#include <algorithm>
#include <cmath>

namespace kiosk::anim {

double chapterTimeAt(const ChapterSpan& c, double elapsed) noexcept {
    if (!(c.seconds > 0) || !std::isfinite(elapsed)) return c.from;
    const double a = std::clamp(elapsed / c.seconds, 0.0, 1.0);
    return c.from + (c.to - c.from) * a;
}

std::vector<BriefingFrame> briefingFrames(const std::vector<ChapterSpan>& chapters, double fps,
                                          double holdSeconds, std::vector<ChapterFrames>* spans) {
    std::vector<BriefingFrame> out;
    if (spans) spans->clear();
    if (!(fps > 0)) return out;
    const std::int64_t hold = std::max<std::int64_t>(0, std::llround(holdSeconds * fps));
    for (std::size_t i = 0; i < chapters.size(); ++i) {
        const ChapterSpan& c = chapters[i];
        const std::int64_t n = std::max<std::int64_t>(1, std::llround(c.seconds * fps));
        const std::int64_t first = std::int64_t(out.size());
        for (std::int64_t k = 0; k < n; ++k) {
            // Both ends shown: the chapter's last frame is its `to`, what a pause holds.
            const double a = n == 1 ? 0.0 : double(k) / double(n - 1);
            out.push_back({c.from + (c.to - c.from) * a, int(i)});
        }
        if (c.pause)
            for (std::int64_t k = 0; k < hold; ++k) out.push_back({c.to, int(i)});
        if (spans) spans->push_back({first, std::int64_t(out.size())});
    }
    return out;
}

}  // namespace kiosk::anim
