#pragma once

#include "tests/platform/ChildProcess.h"

#include <string>

namespace kiosk::test {

/**
 * @brief A private Xvfb server for one test: started on a free display number (the server picks
 * it through `-displayfd`, so parallel tests never race for a number) and stopped by the
 * destructor. Not thread-safe; one per test.
 */
class XvfbServer {
public:
    XvfbServer() = default;
    ~XvfbServer();
    XvfbServer(const XvfbServer&) = delete;
    XvfbServer& operator=(const XvfbServer&) = delete;

    /** @brief Path of the Xvfb binary found on PATH, or empty. */
    static std::string binary() { return findOnPath("Xvfb"); }

    /**
     * @brief Start `Xvfb -screen 0 WxHx24 -nolisten tcp` and wait (at most 15 s) until it accepts
     * connections and its socket /tmp/.X11-unix/XN exists. On failure returns false and puts one
     * line (with the server's log tail) in `error`.
     */
    bool start(int width, int height, std::string& error);

    /** @brief ":N" once started. */
    const std::string& display() const noexcept { return mDisplay; }

private:
    ChildProcess mProcess;
    std::string mDisplay;
    std::string mLogPath;
};

}  // namespace kiosk::test
