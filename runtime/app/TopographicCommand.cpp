#include "runtime/app/TopographicCommand.h"

#include <cstdio>
#include <cstdlib>

#include "runtime/app/Args.h"
#include "runtime/app/Report.h"
#include "runtime/core/ExitCode.h"
#include "runtime/import/Topographic.h"

namespace kiosk::app {
namespace {

constexpr const char* kUsage =
    "usage: geokiosk import topographic --store STORE "
    "[--elevation LAYER] [--name NAME] [--azimuth DEG] [--altitude DEG] [--z-factor F] "
    "[--variant default|multidirectional|combined] [--shadows] [--normals] [--quiet]\n";

int usage(const std::string& message) {
    std::fprintf(stderr, "geokiosk import topographic: %s\n%s", message.c_str(), kUsage);
    return kExitUsage;
}

bool number(const std::optional<std::string>& text, double& out) {
    if (!text) return true;
    char* end = nullptr;
    out = std::strtod(text->c_str(), &end);
    return end != text->c_str() && *end == '\0';
}

}  // namespace

int runImportTopographic(const std::vector<std::string>& argv) {
    Args args("import topographic",
              {"store", "elevation", "name", "azimuth", "altitude", "z-factor", "variant", "threads"},
              {"shadows", "normals", "quiet"});
    if (!args.parse(argv)) return usage(args.error());
    if (args.help()) return showHelp(kUsage);
    if (!args.positionals().empty()) return usage("unexpected argument '" + args.positionals()[0] + "'");
    import::TopographicOptions o;
    if (!args.value("store")) return usage("--store STORE is required");
    o.store = *args.value("store");
    o.elevation = args.value("elevation").value_or("elevation");
    o.normals = args.flag("normals");
    o.name = args.value("name").value_or(o.normals ? "normals" : "hillshade");
    if (o.normals && args.flag("shadows"))
        return usage("--shadows applies to the hillshade, not to --normals (the light moves)");
    if (!number(args.value("azimuth"), o.light.azimuthDeg)) return usage("--azimuth wants degrees");
    if (!number(args.value("altitude"), o.light.altitudeDeg) || o.light.altitudeDeg <= 0 ||
        o.light.altitudeDeg > 90)
        return usage("--altitude wants degrees in (0, 90]");
    if (!number(args.value("z-factor"), o.light.zFactor) || o.light.zFactor == 0)
        return usage("--z-factor wants a non-zero number");
    if (auto v = args.value("variant")) {
        if (*v == "default") o.light.variant = topo::HillshadeVariant::Default;
        else if (*v == "multidirectional") o.light.variant = topo::HillshadeVariant::Multidirectional;
        else if (*v == "combined") o.light.variant = topo::HillshadeVariant::Combined;
        else return usage("--variant wants default|multidirectional|combined, got '" + *v + "'");
    }
    double threads = 2;
    if (!number(args.value("threads"), threads) || threads < 1) return usage("--threads wants >= 1");
    o.threads = int(threads);
    o.shadows = args.flag("shadows");
    o.quiet = args.flag("quiet");
    const Diagnostics d = import::importTopographic(o);
    printDiagnostics(d);
    if (d.hasErrors()) return kExitBadInput;
    if (!o.quiet) std::fprintf(stderr, "geokiosk: imported %s into %s\n", o.name.c_str(), o.store.c_str());
    return kExitOk;
}

}  // namespace kiosk::app
