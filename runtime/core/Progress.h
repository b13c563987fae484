#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace kiosk {

/**
 * @brief Progress of a long job (an import, a render) on stderr: on a terminal a redrawn bar with
 * percent, count and ETA; otherwise (logs, CI) a plain line every 10 % once the job has run 2 s,
 * and a closing "done" line. Quiet mode prints nothing. One thread only (the job's).
 */
class Progress {
public:
    /** @brief `unit` names what is counted ("tiles", "frames"). */
    explicit Progress(bool quiet = false, std::string unit = "tiles");
    void begin(const std::string& label, std::int64_t total);
    void advance(std::int64_t n = 1);
    void finish();

    /** @brief "1m05s" style remaining time from the rate so far; "?" before any progress. */
    static std::string eta(double elapsedSeconds, std::int64_t done, std::int64_t total);

private:
    void draw(bool force);

    bool mQuiet;
    bool mTty;
    std::string mUnit;
    std::string mLabel;
    std::int64_t mTotal = 0, mDone = 0;
    int mLastDecile = -1;
    std::chrono::steady_clock::time_point mStart, mLastDraw;
};

}  // namespace kiosk
