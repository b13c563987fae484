#include "runtime/core/Log.h"

#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <mutex>

namespace kiosk::log {
namespace {

Level initialThreshold() {
    const char* env = std::getenv("GEOKIOSK_LOG");
    if (!env) return Level::Info;
    if (std::strcmp(env, "debug") == 0) return Level::Debug;
    if (std::strcmp(env, "warn") == 0) return Level::Warn;
    if (std::strcmp(env, "error") == 0) return Level::Error;
    // Runs once (it initialises gThreshold), so an unknown value is reported exactly once.
    if (std::strcmp(env, "info") != 0)
        std::fprintf(stderr,
                     "geokiosk: warning: GEOKIOSK_LOG=%s is not a log level (debug, info, warn, "
                     "error); using info\n",
                     env);
    return Level::Info;
}

std::atomic<int> gThreshold{static_cast<int>(initialThreshold())};
std::atomic<bool> gSyslogPrefix{isatty(STDERR_FILENO) == 0};
std::mutex gMutex;
// Ring of recent lines; fixed capacity so a chatty failure cannot grow memory over weeks.
constexpr std::size_t kRecentCapacity = 64;
std::deque<std::string> gRecent;

}  // namespace

void vwrite(Level level, const char* tag, const char* fmt, std::va_list args) {
    if (static_cast<int>(level) > gThreshold.load(std::memory_order_relaxed)) return;
    std::array<char, 1024> buf{};
    int n = 0;
    if (gSyslogPrefix.load(std::memory_order_relaxed))
        n = std::snprintf(buf.data(), buf.size(), "<%d>", static_cast<int>(level));
    n += std::snprintf(buf.data() + n, buf.size() - std::size_t(n), "%s: ", tag);
    if (n < 0 || std::size_t(n) >= buf.size()) n = 0;
    std::vsnprintf(buf.data() + n, buf.size() - std::size_t(n), fmt, args);
    std::lock_guard lock(gMutex);
    std::fprintf(stderr, "%s\n", buf.data());
    if (gRecent.size() == kRecentCapacity) gRecent.pop_front();
    gRecent.emplace_back(buf.data() + (buf[0] == '<' ? 3 : 0));
}

void write(Level level, const char* tag, const char* fmt, ...) {
    std::va_list args;
    va_start(args, fmt);
    vwrite(level, tag, fmt, args);
    va_end(args);
}

void setThreshold(Level level) noexcept { gThreshold = static_cast<int>(level); }
Level threshold() noexcept { return static_cast<Level>(gThreshold.load()); }
void setSyslogPrefix(bool on) noexcept { gSyslogPrefix = on; }

std::vector<std::string> recent(std::size_t maxLines) {
    std::lock_guard lock(gMutex);
    std::size_t start = gRecent.size() > maxLines ? gRecent.size() - maxLines : 0;
    return {gRecent.begin() + std::ptrdiff_t(start), gRecent.end()};
}

}  // namespace kiosk::log
