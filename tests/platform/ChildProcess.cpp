#include "tests/platform/ChildProcess.h"

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <signal.h>
#include <sstream>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace kiosk::test {

std::string findOnPath(const char* name) {
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path ? path : "/usr/bin:/bin");
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        std::filesystem::path p = std::filesystem::path(dir.empty() ? "." : dir) / name;
        if (access(p.c_str(), X_OK) == 0) return p.string();
    }
    return {};
}

std::string logTail(const std::string& path) {
    std::ifstream f(path);
    std::stringstream ss;
    ss << f.rdbuf();
    std::string text = ss.str();
    if (text.size() > 400) text = "..." + text.substr(text.size() - 400);
    for (char& c : text)
        if (c == '\n') c = ' ';
    return text;
}

bool ChildProcess::start(const std::vector<std::string>& args, const std::string& logPath,
                         int passFd, std::string& error) {
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const pid_t parent = getpid();
    const pid_t pid = fork();
    if (pid < 0) {
        error = std::string("fork: ") + std::strerror(errno);
        return false;
    }
    if (pid == 0) {
        // Child: only async-signal-safe calls until exec.
        prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (getppid() != parent) _exit(127);  // the parent died before prctl took effect
        const int log = open(logPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
        if (log >= 0) {
            dup2(log, 1);
            dup2(log, 2);
        }
        if (passFd == 3)
            fcntl(3, F_SETFD, 0);
        else if (passFd >= 0)
            dup2(passFd, 3);  // dup2 clears FD_CLOEXEC on the copy
        execv(argv[0], argv.data());
        _exit(127);
    }
    mPid = pid;
    return true;
}

bool ChildProcess::exited() {
    if (mPid <= 0) return true;
    int status = 0;
    if (waitpid(mPid, &status, WNOHANG) == mPid) {
        mPid = -1;
        return true;
    }
    return false;
}

void ChildProcess::stop() {
    if (mPid <= 0) return;
    kill(mPid, SIGTERM);
    for (int i = 0; i < 150; ++i) {
        if (exited()) return;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    kill(mPid, SIGKILL);
    int status = 0;
    waitpid(mPid, &status, 0);
    mPid = -1;
}

}  // namespace kiosk::test
