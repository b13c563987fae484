#include "runtime/platform/CompilerPages.h"

#include <array>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <sys/mman.h>

#ifndef MADV_PAGEOUT
#define MADV_PAGEOUT 21  // Linux 5.4; older kernels answer EINVAL, which is harmless here
#endif

namespace kiosk::platform {

namespace {

struct Range {
    std::uintptr_t begin = 0, end = 0;
};

struct State {
    bool scanned = false;
    std::array<Range, 8> ranges{};
    std::size_t count = 0;
    double last = -1.0;
    CompilerPagesStats stats;
};

State& state() {
    static State s;
    return s;
}

double monotonicSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return double(ts.tv_sec) + double(ts.tv_nsec) * 1e-9;
}

// Executable mappings of libLLVM (llvmpipe's compiler), read once.
void scan(State& s) {
    s.scanned = true;
    std::FILE* f = std::fopen("/proc/self/maps", "re");
    if (!f) return;
    char line[4096];
    while (s.count < s.ranges.size() && std::fgets(line, sizeof line, f)) {
        unsigned long begin = 0, end = 0;
        char perms[8] = {};
        if (std::sscanf(line, "%lx-%lx %7s", &begin, &end, perms) != 3) continue;
        if (perms[2] != 'x' || !std::strstr(line, "/libLLVM")) continue;
        s.ranges[s.count++] = Range{std::uintptr_t(begin), std::uintptr_t(end)};
        s.stats.mappedBytes += std::size_t(end - begin);
    }
    std::fclose(f);
}

}  // namespace

bool releaseCompilerPages(double intervalSeconds) {
    State& s = state();
    if (!s.scanned) scan(s);
    if (s.count == 0) return false;
    const double now = monotonicSeconds();
    if (s.last >= 0.0 && now - s.last < intervalSeconds) return false;
    s.last = now;
    for (std::size_t i = 0; i < s.count; ++i)
        madvise(reinterpret_cast<void*>(s.ranges[i].begin), s.ranges[i].end - s.ranges[i].begin,
                MADV_PAGEOUT);
    ++s.stats.releases;
    return true;
}

CompilerPagesStats compilerPagesStats() {
    return state().stats;
}

}  // namespace kiosk::platform
