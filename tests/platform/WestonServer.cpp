#include "tests/platform/WestonServer.h"

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <thread>
#include <unistd.h>
#include <vector>

namespace kiosk::test {
namespace {

constexpr int kStartTimeoutMs = 15000;

}  // namespace

bool WestonServer::start(int width, int height, const std::string& shell, std::string& error) {
    const std::string exe = binary();
    if (exe.empty()) {
        error = "weston not found on PATH";
        return false;
    }
    const char* runtime = std::getenv("XDG_RUNTIME_DIR");
    if (!runtime || !*runtime || !std::filesystem::is_directory(runtime)) {
        std::string tmpl = (std::filesystem::temp_directory_path() / "kiosk-xdg-XXXXXX").string();
        if (!mkdtemp(tmpl.data())) {
            error = std::string("mkdtemp: ") + std::strerror(errno);
            return false;
        }
        mOwnRuntimeDir = tmpl;
        setenv("XDG_RUNTIME_DIR", mOwnRuntimeDir.c_str(), 1);
        runtime = mOwnRuntimeDir.c_str();
    }
    static int counter = 0;
    mSocket = "kiosk-test-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
    const std::filesystem::path socketPath = std::filesystem::path(runtime) / mSocket;
    mLogPath = (std::filesystem::temp_directory_path() / (mSocket + ".log")).string();

    const std::vector<std::string> args = {exe,
                                           "--backend=headless-backend.so",
                                           "--socket=" + mSocket,
                                           "--width=" + std::to_string(width),
                                           "--height=" + std::to_string(height),
                                           "--shell=" + shell,
                                           "--idle-time=0",
                                           "--no-config"};
    if (!mProcess.start(args, mLogPath, -1, error)) return false;
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::milliseconds(kStartTimeoutMs);
    while (!std::filesystem::exists(socketPath)) {
        if (mProcess.exited()) {
            error = "weston exited during start-up; its log: " + logTail(mLogPath);
            return false;
        }
        if (std::chrono::steady_clock::now() > deadline) {
            mProcess.stop();
            error = "weston did not create " + socketPath.string() + " within " +
                    std::to_string(kStartTimeoutMs) + " ms; its log: " + logTail(mLogPath);
            return false;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return true;
}

WestonServer::~WestonServer() {
    mProcess.stop();
    std::error_code ec;
    if (!mLogPath.empty()) std::filesystem::remove(mLogPath, ec);
    if (!mOwnRuntimeDir.empty()) {
        std::filesystem::remove_all(mOwnRuntimeDir, ec);
        unsetenv("XDG_RUNTIME_DIR");
    }
}

}  // namespace kiosk::test
