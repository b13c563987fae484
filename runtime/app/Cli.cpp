#include "runtime/app/Cli.h"

#include <cstdio>
#include <exception>

#include "runtime/app/ImporterExec.h"
#include "runtime/app/InfoCommand.h"
#include "runtime/app/PlayCommand.h"
#include "runtime/app/RenderCommand.h"
#include "runtime/app/ValidateCommand.h"
#include "runtime/core/ExitCode.h"
#include "runtime/core/Strings.h"

namespace kiosk::app {

std::string usageText() {
    return R"(usage: geokiosk COMMAND ...

  play SCENARIO [--display auto|kms|x11|wayland|headless] [--size WxH] [--windowed]
                [--max-fps N] [--frames N] [--connector NAME|INDEX] [--drm-device PATH]
                [--stats STATS.json]
        show a scenario fullscreen until SIGINT/SIGTERM (or N frames); --max-fps 0: unthrottled
  render SCENARIO --out OUT [--time T | --from T0 --to T1 --fps N] [--size WxH]
                  [--viewpoint NAME] [--stats STATS.json]
        render offscreen: OUT is x.png (one frame) or dir/ (dir/000001.png ...)
  import elevation SRC --store STORE [--name NAME]
  import imagery   SRC --store STORE --name NAME
  import sequence  SRC... --store STORE --name NAME [--times TIMES.csv] [--variable VAR]
  import topographic --store STORE [--elevation LAYER] [--name NAME] [--azimuth DEG]
                     [--altitude DEG] [--variant default|multidirectional|combined] [--shadows]
                     [--normals]
        build or extend a store (a GeoPackage) from GDAL-readable rasters and model output
        (runs geokiosk-import, installed beside geokiosk)
  validate SCENARIO...
        check scenarios against the schema and their stores
  info STORE [--json]
        describe a store: layers, CRS, extent, levels, sequences

Times: ISO 8601 UTC (2026-03-14T06:40:00Z) or offsets from the scenario start (+3600, +1h30m).
Exit status: 0 ok, 1 bad input (scenario, data, store), 2 usage error, 3 cannot run here
(no display, no OpenGL ES 3 context).
)";
}

namespace {

int dispatch(const std::vector<std::string>& args) {
    if (args.empty()) {
        std::fputs(usageText().c_str(), stderr);
        return kExitUsage;
    }
    const std::string& cmd = args[0];
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    if (cmd == "-h" || cmd == "--help" || cmd == "help") {
        std::fputs(usageText().c_str(), stdout);
        return kExitOk;
    }
    if (cmd == "--version") {
        std::printf("geokiosk %s\n", KIOSK_VERSION);
        return kExitOk;
    }
    if (cmd == "play") return runPlayCommand(rest);
    if (cmd == "render") return runRenderCommand(rest);
    // The importer is a separate executable (GDAL, netCDF stay out of the kiosk process).
    if (cmd == "import") return execImporter(rest);
    if (cmd == "validate") return runValidateCommand(rest);
    if (cmd == "info") return runInfoCommand(rest);
    std::string msg = "geokiosk: unknown command '" + cmd + "'";
    if (auto m = closestMatch(cmd, {"play", "render", "import", "validate", "info"}))
        msg += " (did you mean '" + *m + "'?)";
    std::fprintf(stderr, "%s\nrun 'geokiosk --help' for usage\n", msg.c_str());
    return kExitUsage;
}

}  // namespace

int runCli(const std::vector<std::string>& args) {
    // Third-party code may throw (std::filesystem, nlohmann); a user must still get one
    // line and a documented status, never an abort.
    try {
        return dispatch(args);
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "geokiosk: out of memory\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "geokiosk: internal error: %s\n", e.what());
    }
    return kExitBadInput;
}

}  // namespace kiosk::app
