#include "runtime/app/StartupPhases.h"

#include "runtime/core/Log.h"

#include <cstdio>
#include <cstring>
#include <string>
#include <time.h>
#include <unistd.h>

namespace kiosk::app {
namespace {

/** The process's start time in seconds of CLOCK_BOOTTIME, read once (negative: unknown). */
double processStartSeconds() noexcept {
    std::FILE* f = std::fopen("/proc/self/stat", "r");
    if (!f) return -1.0;
    char buf[1024] = {};
    const std::size_t n = std::fread(buf, 1, sizeof buf - 1, f);
    std::fclose(f);
    buf[n] = '\0';
    // Field 22 (starttime); the command name (field 2) may hold spaces: count after its ')'.
    const char* p = std::strrchr(buf, ')');
    if (!p) return -1.0;
    unsigned long long ticks = 0;
    int field = 2;
    for (const char* c = p + 1; *c; ++c) {
        if (*c != ' ') continue;
        if (++field == 22) {
            if (std::sscanf(c + 1, "%llu", &ticks) != 1) return -1.0;
            const long hz = sysconf(_SC_CLK_TCK);
            return hz > 0 ? double(ticks) / double(hz) : -1.0;
        }
    }
    return -1.0;
}

}  // namespace

double StartupPhases::sinceProcessStart() noexcept {
    static const double start = processStartSeconds();
    if (start < 0) return -1.0;
    timespec ts{};
    clock_gettime(CLOCK_BOOTTIME, &ts);
    return double(ts.tv_sec) + double(ts.tv_nsec) * 1e-9 - start;
}

void StartupPhases::mark(const char* name) noexcept {
    // Only log() reads the marks, and it says them at debug level only: no /proc read otherwise.
    if (log::threshold() < log::Level::Debug) return;
    if (mCount < mMarks.size()) mMarks[mCount++] = {name, sinceProcessStart()};
}

void StartupPhases::log(const char* tag) const {
    if (log::threshold() < log::Level::Debug) return;
    std::string line = "start-up (seconds since exec):";
    for (std::size_t i = 0; i < mCount; ++i) {
        char item[64];
        std::snprintf(item, sizeof item, "%s %s %.3f", i ? "," : "", mMarks[i].name,
                      mMarks[i].seconds);
        line += item;
    }
    KIOSK_LOG_DEBUG(tag, "%s", line.c_str());
}

}  // namespace kiosk::app
