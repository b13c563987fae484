#include "runtime/anim/PrefetchPlanner.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kiosk::anim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool listed(const std::vector<PrefetchItem>& items, std::size_t frame) {
    return std::any_of(items.begin(), items.end(),
                       [frame](const PrefetchItem& it) { return it.frame == frame; });
}

}  // namespace

void PrefetchPlanner::plan(const PrefetchInput& in, PrefetchPlan& out) const {
    out.items.clear();
    out.generation = mGeneration;
    out.depth = 0;
    out.budgetLimited = false;
    out.wrapped = false;
    out.sustainable = true;
    const auto times = in.frameTimes;
    const std::size_t n = times.size();
    const double t = in.playhead;
    if (n == 0 || !std::isfinite(t)) return;

    const bool dataLike = in.mode == Interpolation::Data || in.mode == Interpolation::Arrival;
    const double rate = std::isfinite(in.rate) ? in.rate : 0.0;
    const double absRate = std::fabs(rate);
    const int margin = std::max(0, in.margin);
    const double meanLoad =
        std::isfinite(in.meanLoadSeconds) ? std::max(0.0, in.meanLoadSeconds) : 0.0;

    // Frame window the playhead can visit: frames needed to show any t in the range.
    const bool bounded = in.range != RangeMode::Unbounded && in.rangeEnd >= in.rangeStart &&
                         std::isfinite(in.rangeStart) && std::isfinite(in.rangeEnd);
    const bool loop = bounded && in.range == RangeMode::Loop && in.rangeEnd > in.rangeStart;
    std::size_t lo = 0, hi = n - 1;
    if (bounded) {
        auto ub = std::upper_bound(times.begin(), times.end(), in.rangeStart);
        lo = ub == times.begin() ? 0 : static_cast<std::size_t>(ub - times.begin()) - 1;
        if (dataLike) {
            auto lb = std::lower_bound(times.begin(), times.end(), in.rangeEnd);
            hi = std::min(n - 1, static_cast<std::size_t>(lb - times.begin()));
        } else {
            auto ub2 = std::upper_bound(times.begin(), times.end(), in.rangeEnd);
            hi = ub2 == times.begin() ? 0 : static_cast<std::size_t>(ub2 - times.begin()) - 1;
        }
        hi = std::max(hi, lo);
    }
    const std::size_t windowFrames = hi - lo + 1;
    const double meanInterval =
        hi > lo ? (times[hi] - times[lo]) / static_cast<double>(hi - lo) : 0.0;

    // Caps: byte budget (counts the current pair too), maxDepth (frames ahead).
    std::size_t budgetCap = std::numeric_limits<std::size_t>::max();
    if (in.byteBudget > 0 && in.bytesPerFrame > 0)
        budgetCap = static_cast<std::size_t>(in.byteBudget / in.bytesPerFrame);

    // 1. The current pair: needed now.
    const FrameBracket cur = bracketFrames(times, t, in.mode);
    if (rate < 0.0) {
        out.items.push_back({cur.i1, 0.0});
        if (cur.i0 != cur.i1) out.items.push_back({cur.i0, 0.0});
    } else {
        out.items.push_back({cur.i0, 0.0});
        if (cur.i0 != cur.i1) out.items.push_back({cur.i1, 0.0});
    }
    if (out.items.size() > budgetCap) out.budgetLimited = true;
    const std::size_t maxItems = std::max(
        out.items.size(),
        std::min(budgetCap, out.items.size() + static_cast<std::size_t>(std::max(0, in.maxDepth))));

    // 2. Paused / frozen: neighbours on both sides for stepping, no deadlines.
    if (absRate == 0.0) {
        out.depth = margin;
        const std::size_t first = std::min(cur.i0, cur.i1), last = std::max(cur.i0, cur.i1);
        for (int k = 1; k <= margin; ++k) {
            const std::size_t uk = static_cast<std::size_t>(k);
            for (int side = 0; side < 2; ++side) {
                const bool fwd = side == 0;
                if (fwd ? last + uk >= n : first < uk) continue;
                const std::size_t f = fwd ? last + uk : first - uk;
                if (listed(out.items, f)) continue;
                if (out.items.size() >= maxItems) {
                    out.budgetLimited = out.items.size() >= budgetCap;
                    return;
                }
                out.items.push_back({f, kInf});
            }
        }
        return;
    }

    // 3. Playing: walk ahead in playback direction, wrapping at the loop end.
    const double consumePerLoad = meanInterval > 0.0 ? meanLoad * absRate / meanInterval : 0.0;
    out.sustainable = consumePerLoad <= 1.0;
    const int depthRule = static_cast<int>(std::min(1e6, std::ceil(consumePerLoad)));
    int windowCount = 0;  // frames whose deadline falls within one load time
    int ahead = 0;
    const bool fwd = rate > 0.0;
    // Data time at which frame j first becomes part of the displayed bracket.
    auto needTime = [&](std::size_t j) {
        if (fwd) return dataLike && j > 0 ? times[j - 1] : times[j];
        return j + 1 < n ? times[j + 1] : times[j];
    };
    long long k = fwd ? static_cast<long long>(std::max(cur.i0, cur.i1)) + 1
                      : static_cast<long long>(std::min(cur.i0, cur.i1)) - 1;
    bool wrapped = false;
    double lastDeadline = 0.0;
    for (std::size_t visited = 0; visited < windowFrames + 2; ++visited) {
        const int target = std::max(depthRule, windowCount) + margin;
        if (ahead >= target && lastDeadline > meanLoad) break;
        if (fwd ? k > static_cast<long long>(hi) : k < static_cast<long long>(lo)) {
            if (!loop || wrapped) break;
            wrapped = true;
            k = fwd ? static_cast<long long>(lo) : static_cast<long long>(hi);
        }
        const auto j = static_cast<std::size_t>(k);
        k += fwd ? 1 : -1;
        if (listed(out.items, j)) {
            if (wrapped) break;  // came round to frames already planned
            continue;
        }
        double dist;
        if (!wrapped) {
            dist = fwd ? needTime(j) - t : t - needTime(j);
        } else if (fwd) {
            dist = (in.rangeEnd - t) + std::max(0.0, needTime(j) - in.rangeStart);
        } else {
            dist = (t - in.rangeStart) + std::max(0.0, in.rangeEnd - needTime(j));
        }
        const double deadline = std::max(0.0, dist) / absRate;
        if (out.items.size() >= maxItems) {
            out.budgetLimited = out.items.size() >= budgetCap;
            break;
        }
        out.items.push_back({j, deadline});
        out.wrapped = out.wrapped || wrapped;
        lastDeadline = deadline;
        ++ahead;
        if (deadline <= meanLoad) ++windowCount;
    }
    out.depth = std::max(depthRule, windowCount) + margin;
}

bool PrefetchPlanner::syncSeekSerial(std::uint64_t clockSeekSerial) noexcept {
    if (clockSeekSerial == mLastSeekSerial) return false;
    mLastSeekSerial = clockSeekSerial;
    ++mGeneration;
    return true;
}

void LoadTimeEstimator::record(double seconds) noexcept {
    if (!std::isfinite(seconds) || seconds < 0.0) return;
    mMean = mSamples == 0 ? seconds : mMean + mWeight * (seconds - mMean);
    ++mSamples;
}

}  // namespace kiosk::anim
