// make-synthetic-dem: a large SYNTHETIC elevation raster for benchmarks (docs/terrain.md §9).
//   make-synthetic-dem SIZE OUT.tif [--post METRES]
// Exit codes as docs/cli.md: 0 written, 1 cannot write, 2 usage.
#include "tools/synthetic-dem/SyntheticDem.h"
#include <gdal.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
    kiosk::tools::SyntheticDemOptions o;
    if (argc != 3 && !(argc == 5 && std::string(argv[3]) == "--post")) {
        std::fprintf(stderr, "usage: make-synthetic-dem SIZE OUT.tif [--post METRES]\n");
        return 2;
    }
    char* end = nullptr;
    const long size = std::strtol(argv[1], &end, 10);
    if (*end != '\0' || size < 2 || size > 65536) {
        std::fprintf(stderr, "make-synthetic-dem: SIZE must be 2..65536 posts, got '%s'\n",
                     argv[1]);
        return 2;
    }
    o.size = int(size);
    if (argc == 5) {
        o.post = std::strtod(argv[4], &end);
        if (*end != '\0' || !(o.post > 0) || o.post > 1e5) {
            std::fprintf(stderr, "make-synthetic-dem: --post must be a spacing in metres > 0\n");
            return 2;
        }
    }
    // GDAL's default block cache (5 % of RAM) would hold the whole 1 GiB of a 16k grid.
    GDALSetCacheMax64(std::int64_t(64) << 20);
    const std::string error = kiosk::tools::writeSyntheticDem(argv[2], o);
    if (!error.empty()) {
        std::fprintf(stderr, "make-synthetic-dem: %s\n", error.c_str());
        return 1;
    }
    std::printf("make-synthetic-dem: wrote %s (%dx%d posts, %.1f m, SYNTHETIC)\n", argv[2], o.size,
                o.size, o.post);
    return 0;
}
