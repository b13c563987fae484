#pragma once

#include <string>
#include <sys/types.h>
#include <vector>

namespace kiosk::test {

/** @brief Absolute path of `name` in $PATH, or empty. */
std::string findOnPath(const char* name);

/** @brief Up to the last 400 characters of a log file, on one line (for failure messages). */
std::string logTail(const std::string& path);

/**
 * @brief A helper server (Xvfb, weston) started by a test. stdout and stderr go to `logPath`;
 * the child gets SIGKILL if the test process dies first (PR_SET_PDEATHSIG), so a crashed or
 * timed-out test never leaves a server behind. The destructor stops it (SIGTERM, then SIGKILL
 * after 3 s).
 */
class ChildProcess {
public:
    ChildProcess() = default;
    ~ChildProcess() { stop(); }
    ChildProcess(const ChildProcess&) = delete;
    ChildProcess& operator=(const ChildProcess&) = delete;

    /**
     * @brief fork + exec `args` (args[0] is the path). With `passFd` >= 0 that descriptor is
     * handed to the child as fd 3. False with one line in `error` if fork fails.
     */
    bool start(const std::vector<std::string>& args, const std::string& logPath, int passFd,
               std::string& error);
    /** @brief True (and reaped) once the child has exited. */
    bool exited();
    void stop();
    bool running() const noexcept { return mPid > 0; }

private:
    pid_t mPid = -1;
};

}  // namespace kiosk::test
