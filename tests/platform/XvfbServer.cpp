#include "tests/platform/XvfbServer.h"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <poll.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace kiosk::test {
namespace {

constexpr int kStartTimeoutMs = 15000;

}  // namespace

bool XvfbServer::start(int width, int height, std::string& error) {
    const std::string exe = binary();
    if (exe.empty()) {
        error = "Xvfb not found on PATH";
        return false;
    }
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0) {
        error = std::string("pipe: ") + std::strerror(errno);
        return false;
    }
    mLogPath = (std::filesystem::temp_directory_path() /
                ("kiosk-xvfb-" + std::to_string(getpid()) + ".log"))
                   .string();
    // The server writes its display number to fd 3 once it accepts connections.
    const std::vector<std::string> args = {
        exe,         "-displayfd", "3",
        "-screen",   "0",          std::to_string(width) + "x" + std::to_string(height) + "x24",
        "-nolisten", "tcp",        "-noreset"};
    const bool started = mProcess.start(args, mLogPath, fds[1], error);
    close(fds[1]);
    if (!started) {
        close(fds[0]);
        return false;
    }

    std::string number;
    bool done = false;
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::milliseconds(kStartTimeoutMs);
    while (!done) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                              deadline - std::chrono::steady_clock::now())
                              .count();
        if (left <= 0) break;
        pollfd pfd{fds[0], POLLIN, 0};
        const int pr = poll(&pfd, 1, int(left));
        if (pr < 0 && errno == EINTR) continue;
        if (pr <= 0) break;
        char buf[32];
        const ssize_t n = read(fds[0], buf, sizeof(buf));
        if (n <= 0) break;  // EOF: the server exited before it was ready
        for (ssize_t i = 0; i < n; ++i) {
            if (buf[i] == '\n')
                done = true;
            else
                number += buf[i];
        }
    }
    close(fds[0]);
    if (!done || number.empty()) {
        mProcess.stop();
        error = "Xvfb did not become ready within " + std::to_string(kStartTimeoutMs) +
                " ms; its log: " + logTail(mLogPath);
        return false;
    }
    mDisplay = ":" + number;
    const std::string socket = "/tmp/.X11-unix/X" + number;
    for (int i = 0; i < 100 && !std::filesystem::exists(socket); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (!std::filesystem::exists(socket)) {
        mProcess.stop();
        error = "Xvfb reported display " + mDisplay + " but " + socket + " does not exist";
        return false;
    }
    return true;
}

XvfbServer::~XvfbServer() {
    mProcess.stop();
    std::error_code ec;
    if (!mLogPath.empty()) std::filesystem::remove(mLogPath, ec);
}

}  // namespace kiosk::test
