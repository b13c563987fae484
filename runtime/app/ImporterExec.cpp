#include "runtime/app/ImporterExec.h"

#include "runtime/core/ExitCode.h"
#include "runtime/core/SelfPath.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <unistd.h>

namespace kiosk::app {

std::filesystem::path importerPath() {
    return core::executableDir() / kImporterName;
}

int execImporter(const std::vector<std::string>& args) {
    const std::filesystem::path path = importerPath();
    std::vector<char*> argv;
    argv.reserve(args.size() + 2);
    std::string arg0 = path.string();
    argv.push_back(arg0.data());
    std::vector<std::string> words = args;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    std::fflush(stdout);
    std::fflush(stderr);
    ::execv(arg0.c_str(), argv.data());
    const int err = errno;
    std::fprintf(
        stderr,
        "geokiosk import: cannot run the importer %s: %s (it is installed beside geokiosk)\n",
        arg0.c_str(), std::strerror(err));
    return kExitCannotRun;
}

}  // namespace kiosk::app
