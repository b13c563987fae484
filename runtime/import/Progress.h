#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace kiosk::import {

/**
 * @brief Import progress on stderr: a redrawn bar on a terminal; otherwise (logs, CI) a plain
 * line every 10 % once the import has run 2 s, and a closing "done" line. Quiet mode prints
 * nothing. Used from the importer's writer thread only.
 */
class Progress {
public:
    explicit Progress(bool quiet = false);
    void begin(const std::string& label, std::int64_t total);
    void advance(std::int64_t n = 1);
    void finish();

private:
    void draw(bool force);

    bool mQuiet;
    bool mTty;
    std::string mLabel;
    std::int64_t mTotal = 0, mDone = 0;
    int mLastDecile = -1;
    std::chrono::steady_clock::time_point mStart, mLastDraw;
};

}  // namespace kiosk::import
