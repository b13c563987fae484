#include "runtime/app/TextureCommand.h"

#include "runtime/app/Args.h"
#include "runtime/app/Report.h"
#include "runtime/core/ExitCode.h"
#include "runtime/import/TextureCompression.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace kiosk::app {
namespace {

constexpr const char* kUsage =
    "usage: geokiosk import textures --store STORE [--layers NAME,NAME...]\n"
    "                       [--quality fast|medium|thorough] [--threads N] [--quiet]\n"
    "  ASTC 4x4 GPU blocks (every mip level) of the store's imagery layers, kept beside their\n"
    "  PNG tiles; a kiosk uploads them where the GL context has ASTC "
    "(terrain.textureCompression).\n"
    "  --layers: imagery layers only (default: all of them); data layers are never compressed.\n"
    "  Running it again replaces a layer's blocks.\n";

int usage(const std::string& message) {
    std::fprintf(stderr, "geokiosk import textures: %s\n%s", message.c_str(), kUsage);
    return kExitUsage;
}

}  // namespace

int runImportTextures(const std::vector<std::string>& argv) {
    Args args("import textures", {"store", "layers", "quality", "threads"}, {"quiet"});
    if (!args.parse(argv)) return usage(args.error());
    if (args.help()) return showHelp(kUsage);
    if (!args.positionals().empty())
        return usage("unexpected argument '" + args.positionals()[0] + "'");
    if (!args.value("store")) return usage("--store STORE is required");
    import::TextureImportOptions o;
    o.store = *args.value("store");
    if (auto l = args.value("layers")) {
        std::size_t start = 0;
        while (start <= l->size()) {
            const std::size_t comma = std::min(l->find(',', start), l->size());
            if (comma == start) return usage("--layers wants NAME,NAME..., got '" + *l + "'");
            o.layers.push_back(l->substr(start, comma - start));
            start = comma + 1;
        }
    }
    if (auto q = args.value("quality")) {
        if (*q == "fast")
            o.quality = import::AstcQuality::Fast;
        else if (*q == "medium")
            o.quality = import::AstcQuality::Medium;
        else if (*q == "thorough")
            o.quality = import::AstcQuality::Thorough;
        else
            return usage("--quality wants fast|medium|thorough, got '" + *q + "'");
    }
    if (auto t = args.value("threads")) {
        char* end = nullptr;
        const long n = std::strtol(t->c_str(), &end, 10);
        if (end == t->c_str() || *end != '\0' || n < 1 || n > 256)
            return usage("--threads wants 1..256, got '" + *t + "'");
        o.threads = int(n);
    }
    o.quiet = args.flag("quiet");
    if (!std::filesystem::exists(o.store)) {
        std::fprintf(stderr, "geokiosk import textures: %s: no such store\n",
                     o.store.string().c_str());
        return kExitBadInput;
    }
    auto r = import::importTextureBlocks(o);
    printDiagnostics(r.diagnostics);
    if (!r.ok()) return kExitBadInput;
    if (!o.quiet)
        for (const auto& l : *r)
            std::fprintf(stderr,
                         "geokiosk: %s: %zu tiles as ASTC 4x4, PSNR %.1f dB worst / %.1f dB "
                         "median, %.2f MB RGBA8 -> %.2f MB blocks (with mip levels), encode %.1f "
                         "s CPU\n",
                         l.layer.c_str(), l.tiles, l.psnrMinDb, l.psnrMedianDb,
                         double(l.rgbaBytes) / 1e6, double(l.blockBytes) / 1e6,
                         l.encodeCpuMs / 1e3);
    return kExitOk;
}

}  // namespace kiosk::app
