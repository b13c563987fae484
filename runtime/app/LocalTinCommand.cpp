#include "runtime/app/LocalTinCommand.h"

#include "runtime/app/Args.h"
#include "runtime/app/Report.h"
#include "runtime/core/ExitCode.h"
#include "runtime/import/LocalTinImport.h"
#include "runtime/io/StoreWriter.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace kiosk::app {
namespace {

constexpr const char* kUsage =
    "usage: geokiosk import breaklines LINES --store STORE [--elevation LAYER] [--name NAME]\n"
    "                       [--threads N] [--quiet]\n"
    "       geokiosk import model-mesh MODEL.sww --store STORE [--elevation LAYER] [--name NAME]\n"
    "                       [--threads N] [--quiet]\n"
    "  LINES: a vector file GDAL reads (GeoPackage, GeoJSON, ...) of LineStrings with a CRS;\n"
    "  3D lines keep their Z, 2D lines take the elevation's heights. NAME (default: the file's\n"
    "  stem) names the TINs: importing the same NAME again replaces them.\n";

int usage(const std::string& kind, const std::string& message) {
    std::fprintf(stderr, "geokiosk import %s: %s\n%s", kind.c_str(), message.c_str(), kUsage);
    return kExitUsage;
}

}  // namespace

int runImportLocalTins(const std::string& kind, const std::vector<std::string>& argv) {
    Args args("import " + kind, {"store", "elevation", "name", "threads"}, {"quiet"});
    if (!args.parse(argv)) return usage(kind, args.error());
    if (args.help()) return showHelp(kUsage);
    if (args.positionals().size() != 1)
        return usage(kind, kind == "breaklines" ? "give one lines file" : "give one SWW file");
    if (!args.value("store")) return usage(kind, "--store STORE is required");
    import::LocalTinImportOptions o;
    const std::string source = args.positionals()[0];
    o.store = *args.value("store");
    o.elevation = args.value("elevation").value_or("elevation");
    o.name = args.value("name").value_or(std::filesystem::path(source).stem().string());
    if (!io::StoreWriter::validTableName(o.name))
        return usage(kind,
                     "--name wants a plain name ([A-Za-z_][A-Za-z0-9_]*), got '" + o.name + "'");
    if (auto t = args.value("threads")) {
        char* end = nullptr;
        const long n = std::strtol(t->c_str(), &end, 10);
        if (end == t->c_str() || *end != '\0' || n < 1 || n > 256)
            return usage(kind, "--threads wants 1..256, got '" + *t + "'");
        o.threads = int(n);
    }
    o.quiet = args.flag("quiet");
    if (!std::filesystem::exists(o.store)) {
        std::fprintf(stderr, "geokiosk import %s: %s: no such store (import elevation first)\n",
                     kind.c_str(), o.store.string().c_str());
        return kExitBadInput;
    }
    const Diagnostics d = kind == "breaklines" ? import::importBreaklines(source, o)
                                               : import::importModelMesh(source, o);
    printDiagnostics(d);
    if (d.hasErrors()) return kExitBadInput;
    if (!o.quiet)
        std::fprintf(stderr, "geokiosk: imported %s '%s' into %s\n", kind.c_str(), o.name.c_str(),
                     o.store.string().c_str());
    return kExitOk;
}

}  // namespace kiosk::app
