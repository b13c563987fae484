#include "runtime/service/Playlist.h"

#include <algorithm>
#include <ctime>

namespace kiosk::service {

bool inWindow(const PlaylistRule& r, int s) noexcept {
    if (!r.hasWindow) return true;
    if (r.windowFrom < r.windowTo) return s >= r.windowFrom && s < r.windowTo;
    return s >= r.windowFrom || s < r.windowTo;  // wraps past midnight (e.g. 22:00 - 06:00)
}

int pickEntry(const std::vector<PlaylistRule>& rules, int from, int step, int secondOfDay,
              const std::vector<bool>& broken, bool includeFrom) {
    const int n = int(rules.size());
    if (n == 0) return -1;
    step = step < 0 ? -1 : 1;
    int i = ((from % n) + n) % n;
    if (!includeFrom) i = ((i + step) % n + n) % n;
    for (int k = 0; k < n; ++k, i = ((i + step) % n + n) % n) {
        const bool bad = i < int(broken.size()) && broken[i];
        if (!bad && inWindow(rules[i], secondOfDay)) return i;
    }
    return -1;
}

bool entryFinished(const PlaylistRule& r, const EntryProgress& p, int secondOfDay) noexcept {
    if (!inWindow(r, secondOfDay)) return true;
    if (r.durationSeconds > 0) return p.wallSeconds >= r.durationSeconds;
    if (r.loops > 0) return p.loops + (p.clockAtEnd ? 1u : 0u) >= std::uint64_t(r.loops);
    return false;
}

float fadeAlpha(double sinceStart, std::optional<double> untilEnd, double fadeSeconds) noexcept {
    if (fadeSeconds <= 0) return 0.0f;
    const double half = fadeSeconds / 2.0;
    double a = 0;
    if (sinceStart < half) a = 1.0 - sinceStart / half;
    if (untilEnd && *untilEnd < half) a = std::max(a, 1.0 - *untilEnd / half);
    return float(std::clamp(a, 0.0, 1.0));
}

int localSecondOfDay(double epochSeconds) noexcept {
    const std::time_t t = std::time_t(epochSeconds);
    std::tm tm{};
    localtime_r(&t, &tm);
    return tm.tm_hour * 3600 + tm.tm_min * 60 + tm.tm_sec;
}

}  // namespace kiosk::service
