#include "runtime/app/ImportCli.h"

#include "runtime/app/ImportCommand.h"
#include "runtime/app/LocalTinCommand.h"
#include "runtime/app/TextureCommand.h"
#include "runtime/app/TopographicCommand.h"
#include "runtime/core/ExitCode.h"

#include <cstdio>
#include <exception>
#include <new>

namespace kiosk::app {

namespace {

int dispatch(const std::vector<std::string>& args) {
    if (!args.empty() && args[0] == "--version") {
        std::printf("geokiosk-import %s\n", KIOSK_VERSION);
        return kExitOk;
    }
    if (!args.empty() && args[0] == "topographic")
        return runImportTopographic({args.begin() + 1, args.end()});
    if (!args.empty() && (args[0] == "breaklines" || args[0] == "model-mesh"))
        return runImportLocalTins(args[0], {args.begin() + 1, args.end()});
    if (!args.empty() && args[0] == "textures")
        return runImportTextures({args.begin() + 1, args.end()});
    return runImportCommand(args);
}

}  // namespace

int runImportCli(const std::vector<std::string>& args) {
    // GDAL, netCDF and std::filesystem may throw; a user still gets one line and a status.
    try {
        return dispatch(args);
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "geokiosk import: out of memory\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "geokiosk import: internal error: %s\n", e.what());
    }
    return kExitBadInput;
}

}  // namespace kiosk::app
