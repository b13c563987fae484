#include "runtime/app/ImportCommand.h"

#include "runtime/app/Args.h"

#include "runtime/core/Diagnostics.h"
#include "runtime/core/ExitCode.h"
#include "runtime/core/Strings.h"
#include "runtime/core/TimeParse.h"
#include "runtime/core/Units.h"
#include "runtime/import/Importer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>

namespace kiosk::app {

namespace {

constexpr const char* kUsage =
    "usage: geokiosk import elevation SRC --store STORE [--name NAME] [--band N]\n"
    "                       [--pixel-size M] [--z-scale F] [--units m|ft] [--fill-voids]\n"
    "       geokiosk import imagery SRC --store STORE --name NAME [--jpeg]\n"
    "       geokiosk import sequence SRC... --store STORE --name NAME [--times TIMES.csv]\n"
    "                       [--variable VAR] [--start TIME] [--step SECONDS] [--like RASTER]\n"
    "                       [--wet-threshold M] [--categorical] [--units U]\n"
    "       geokiosk import topographic|breaklines|model-mesh|textures ... (see their --help)\n"
    "common: [--assign-crs CRS] [--to-crs CRS] [--max-memory MB] [--quiet] [--threads N]\n"
    "  --assign-crs names the source's CRS (EPSG:N, WKT or PROJ), --to-crs the new store's\n"
    "  (default: the source's; UTM of the centre, or a global projection for wide geographic\n"
    "  grids); --crs is the deprecated mix of both\n";

int usage(const std::string& message, const std::string& hint = {}) {
    Diagnostic d;
    d.code = "CLI_USAGE";
    d.where = "import";
    d.message = message;
    d.hint = hint;
    std::fprintf(stderr, "%s\n%s", d.format().c_str(), kUsage);
    return kExitUsage;
}

std::optional<double> number(const std::string& s) {
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || !end || *end != '\0') return std::nullopt;
    return v;
}

}  // namespace

int runImportCommand(const std::vector<std::string>& args) {
    if (args.empty()) {
        std::fputs(kUsage, stderr);
        return kExitUsage;
    }
    if (wantsHelp(args)) return showHelp(kUsage);
    const std::string kind = args[0];
    const std::vector<std::string> kinds = {"elevation", "imagery", "sequence"};
    if (kind != "elevation" && kind != "imagery" && kind != "sequence") {
        auto m = closestMatch(kind, kinds);
        return usage("unknown import kind '" + kind + "'",
                     m ? "did you mean '" + *m + "'?" : "elevation, imagery or sequence");
    }
    import::ImportOptions o;
    std::vector<std::string> sources;
    const std::vector<std::string> valued = {
        "--store",   "--name",       "--crs",           "--pixel-size", "--z-scale",   "--units",
        "--times",   "--variable",   "--wet-threshold", "--start",      "--step",      "--like",
        "--threads", "--assign-crs", "--to-crs",        "--band",       "--max-memory"};
    const std::vector<std::string> flags = {"--categorical", "--jpeg", "--quiet", "--fill-voids"};
    for (std::size_t i = 1; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a.rfind("--", 0) != 0) {
            sources.push_back(a);
            continue;
        }
        if (a == "--categorical") {
            o.categorical = true;
            continue;
        }
        if (a == "--jpeg") {
            o.jpeg = true;
            continue;
        }
        if (a == "--quiet") {
            o.quiet = true;
            continue;
        }
        if (a == "--fill-voids") {
            o.fillVoids = true;
            continue;
        }
        if (std::find(valued.begin(), valued.end(), a) == valued.end()) {
            std::vector<std::string> all = valued;
            all.insert(all.end(), flags.begin(), flags.end());
            auto m = closestMatch(a, all);
            return usage("unknown option '" + a + "'", m ? "did you mean '" + *m + "'?" : "");
        }
        if (i + 1 >= args.size()) return usage("option " + a + " needs a value");
        const std::string v = args[++i];
        if (a == "--store") {
            o.store = v;
        } else if (a == "--name") {
            o.name = v;
        } else if (a == "--crs") {
            std::fputs(
                "geokiosk: warning: --crs is deprecated: use --assign-crs CRS (the source's "
                "own CRS) or --to-crs CRS (the store's)\n",
                stderr);
            o.crs = v;
        } else if (a == "--assign-crs") {
            o.assignCrs = v;
        } else if (a == "--to-crs") {
            o.toCrs = v;
        } else if (a == "--units") {
            o.units = v;
        } else if (a == "--times") {
            o.timesCsv = v;
        } else if (a == "--variable") {
            o.variable = v;
        } else if (a == "--like") {
            o.gridLike = v;
        } else if (a == "--start") {
            auto t = parseIso8601(v);
            if (!t)
                return usage("--start needs an ISO 8601 UTC time, got '" + v + "'",
                             "e.g. 2026-03-14T06:40:00Z");
            o.start = *t;
        } else {
            auto n = number(v);
            if (!n) return usage("option " + a + " needs a number, got '" + v + "'");
            if (a == "--pixel-size") {
                if (!(*n > 0)) return usage("--pixel-size must be positive");
                o.pixelSize = *n;
            } else if (a == "--z-scale") {
                if (*n == 0) return usage("--z-scale must not be 0");
                o.zScale = *n;
            } else if (a == "--wet-threshold") {
                o.wetThreshold = *n;
            } else if (a == "--step") {
                if (!(*n > 0)) return usage("--step must be positive");
                o.step = *n;
            } else if (a == "--threads") {
                o.threads = std::max(1, int(*n));
            } else if (a == "--band") {
                if (!(*n >= 1) || *n != std::floor(*n) || *n > 65535)
                    return usage("--band needs a band number from 1, got '" + v + "'");
                o.band = int(*n);
            } else if (a == "--max-memory") {
                if (!(*n >= 64) || *n > 1048576)
                    return usage("--max-memory needs megabytes from 64 to 1048576, got '" + v +
                                 "'");
                o.memoryBudget = std::int64_t(*n) << 20;
            }
        }
    }
    if (o.store.empty()) return usage("--store STORE is required");
    if (sources.empty()) return usage("no source file given");
    if (kind != "sequence" && sources.size() > 1)
        return usage("import " + kind + " takes one source, got " + std::to_string(sources.size()));
    if (kind == "elevation" && o.units && *o.units != "m" && *o.units != "ft")
        return usage("--units must be m or ft for elevation, got '" + *o.units + "'");
    std::string unitsWhy;
    if (o.units && !cleanUnits(*o.units, &unitsWhy)) return usage("--units " + unitsWhy);
    if (kind != "elevation" && o.name.empty()) return usage("import " + kind + " needs --name");
    if (kind != "elevation" && o.band) return usage("--band applies to import elevation only");
    if (o.crs && (o.assignCrs || o.toCrs))
        return usage("--crs cannot be combined with --assign-crs / --to-crs");

    Diagnostics d;
    if (kind == "elevation")
        d = import::importElevation(sources[0], o);
    else if (kind == "imagery")
        d = import::importImagery(sources[0], o);
    else
        d = import::importSequence(sources, o);
    for (const auto& item : d.items()) std::fprintf(stderr, "%s\n", item.format().c_str());
    if (d.hasErrors()) return kExitBadInput;
    if (!o.quiet)
        std::fprintf(stderr, "geokiosk: imported %s into %s\n", kind.c_str(),
                     o.store.string().c_str());
    return kExitOk;
}

}  // namespace kiosk::app
