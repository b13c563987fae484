#pragma once

#include "tests/platform/ChildProcess.h"

#include <string>

namespace kiosk::test {

/**
 * @brief A private headless Weston compositor for one test, on its own socket name, stopped by
 * the destructor. When XDG_RUNTIME_DIR is unset (CI containers) a private 0700 directory is
 * created, exported for the test's Wayland client and removed afterwards.
 */
class WestonServer {
public:
    WestonServer() = default;
    ~WestonServer();
    WestonServer(const WestonServer&) = delete;
    WestonServer& operator=(const WestonServer&) = delete;

    /** @brief Path of the weston binary found on PATH, or empty. */
    static std::string binary() { return findOnPath("weston"); }

    /**
     * @brief Start `weston --backend=headless-backend.so --shell=SHELL` with a WxH output and
     * wait (at most 15 s) for its socket. On failure returns false with one line in `error`.
     */
    bool start(int width, int height, const std::string& shell, std::string& error);

    /** @brief The socket name, for WAYLAND_DISPLAY. */
    const std::string& socketName() const noexcept { return mSocket; }

private:
    ChildProcess mProcess;
    std::string mSocket;
    std::string mLogPath;
    std::string mOwnRuntimeDir;
};

}  // namespace kiosk::test
