// Import throughput of `geokiosk import elevation` against `gdal_translate -of GPKG` + `gdaladdo`
// on the same synthetic DEM, in the same run. Prints one JSON object on stdout.
//
//   bench-import [--sizes 4096,16384] [--dir DIR] [--keep]
//
// Each measured command runs in its own child process; wall time and peak RSS (ru_maxrss from
// wait4) are per child. MB/s counts the source raster bytes (float32), tiles/s the tiles written
// over all pyramid levels.
#include "runtime/import/Importer.h"

#include "tools/synthetic-dem/SyntheticDem.h"
#include <gdal.h>
#include <sqlite3.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct Run {
    double seconds = 0;
    double peakRssMb = 0;
    int status = -1;
};

// Fork, run `fn` (returns exit code) in the child, measure wall time and the child's peak RSS.
template <class Fn>
Run measure(Fn&& fn) {
    Run r;
    const auto t0 = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    if (pid == 0) {
        std::fflush(stdout);
        _exit(fn());
    }
    int status = 0;
    struct rusage ru {};
    wait4(pid, &status, 0, &ru);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.peakRssMb = double(ru.ru_maxrss) / 1024.0;
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
    return r;
}

int execQuiet(const std::vector<std::string>& argv) {
    std::vector<char*> a;
    for (const auto& s : argv) a.push_back(const_cast<char*>(s.c_str()));
    a.push_back(nullptr);
    if (std::freopen("/dev/null", "w", stdout) == nullptr) return 127;
    execvp(a[0], a.data());
    return 127;
}

long long countTiles(const fs::path& gpkg, const char* table) {
    sqlite3* db = nullptr;
    long long n = -1;
    if (sqlite3_open_v2(gpkg.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK) {
        sqlite3_stmt* st = nullptr;
        const std::string sql = std::string("SELECT COUNT(*) FROM \"") + table + "\"";
        if (sqlite3_prepare_v2(db, sql.c_str(), -1, &st, nullptr) == SQLITE_OK &&
            sqlite3_step(st) == SQLITE_ROW)
            n = sqlite3_column_int64(st, 0);
        sqlite3_finalize(st);
    }
    sqlite3_close(db);
    return n;
}

std::string runJson(const Run& r, double mb, long long tiles, double bytesOnDisk) {
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "{\"ok\": %s, \"seconds\": %.3f, \"mb_per_s\": %.2f, \"tiles\": %lld, "
                  "\"tiles_per_s\": %.1f, \"peak_rss_mb\": %.1f, \"output_mb\": %.1f}",
                  r.status == 0 ? "true" : "false", r.seconds, mb / r.seconds, tiles,
                  double(tiles) / r.seconds, r.peakRssMb, bytesOnDisk / 1e6);
    return buf;
}

}  // namespace

int main(int argc, char** argv) {
    // Child mode: a clean process per measured import, so ru_maxrss is the import's own.
    if (argc == 4 && std::string(argv[1]) == "--run-import") {
        kiosk::import::ImportOptions o;
        o.store = argv[3];
        o.quiet = true;
        return kiosk::import::importElevation(argv[2], o).hasErrors() ? 1 : 0;
    }
    std::vector<int> sizes = {4096};  // --sizes 4096,16384 adds the 16k run (~5 min)
    fs::path dir = fs::temp_directory_path() / "geokiosk-bench-import";
    bool keep = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--sizes" && i + 1 < argc) {
            sizes.clear();
            std::string s = argv[++i];
            for (std::size_t p = 0; p < s.size();) {
                const std::size_t q = s.find(',', p);
                sizes.push_back(std::atoi(s.substr(p, q - p).c_str()));
                p = q == std::string::npos ? s.size() : q + 1;
            }
        } else if (a == "--dir" && i + 1 < argc) {
            dir = argv[++i];
        } else if (a == "--keep") {
            keep = true;
        } else {
            std::fprintf(stderr, "usage: bench-import [--sizes 4096,16384] [--dir DIR] [--keep]\n");
            return 2;
        }
    }
    fs::create_directories(dir);
    std::string out =
        "{\"benchmark\": \"import_elevation\", \"baseline\": \"gdal_translate -of GPKG "
        "-co TILE_FORMAT=PNG + gdaladdo -r average\", \"cores\": " +
        std::to_string(sysconf(_SC_NPROCESSORS_ONLN)) + ", \"runs\": [";
    bool first = true;
    for (int n : sizes) {
        const fs::path dem = dir / ("dem_" + std::to_string(n) + ".tif");
        const fs::path ours = dir / ("ours_" + std::to_string(n) + ".gpkg");
        const fs::path theirs = dir / ("gdal_" + std::to_string(n) + ".gpkg");
        fs::remove(ours);
        fs::remove(theirs);
        std::fprintf(stderr, "bench: generating %dx%d DEM\n", n, n);
        if (!fs::exists(dem)) {
            kiosk::tools::SyntheticDemOptions so;
            so.size = n;
            if (const std::string e = kiosk::tools::writeSyntheticDem(dem, so); !e.empty()) {
                std::fprintf(stderr, "bench: %s\n", e.c_str());
                return 1;
            }
        }
        const double mb = double(n) * n * 4 / 1e6;
        std::fprintf(stderr, "bench: geokiosk import (%d)\n", n);
        const Run a = measure([&] {
            return execQuiet({"/proc/self/exe", "--run-import", dem.string(), ours.string()});
        });
        std::fprintf(stderr, "bench: gdal_translate + gdaladdo (%d)\n", n);
        const Run t = measure([&] {
            return execQuiet({"gdal_translate", "-q", "-of", "GPKG", "-co", "TILE_FORMAT=PNG",
                              "-co", "RASTER_TABLE=dem", dem.string(), theirs.string()});
        });
        std::vector<std::string> addo = {"gdaladdo", "-q", "-r", "average", theirs.string()};
        for (int f = 2; n / f >= 128; f *= 2) addo.push_back(std::to_string(f));
        const Run o = measure([&] { return execQuiet(addo); });
        Run g;
        g.seconds = t.seconds + o.seconds;
        g.peakRssMb = std::max(t.peakRssMb, o.peakRssMb);
        g.status = t.status == 0 && o.status == 0 ? 0 : 1;
        const long long ourTiles = countTiles(ours, "elevation");
        const long long gdalTiles = countTiles(theirs, "dem");
        std::error_code ec;
        const double ourBytes = double(fs::file_size(ours, ec));
        const double gdalBytes = double(fs::file_size(theirs, ec));
        char ratio[160];
        std::snprintf(ratio, sizeof ratio,
                      ", \"speedup_vs_gdal\": %.2f, \"tiles_per_s_ratio\": %.2f}",
                      g.seconds / a.seconds,
                      (double(ourTiles) / a.seconds) / (double(gdalTiles) / g.seconds));
        out += std::string(first ? "" : ", ") + "{\"size\": " + std::to_string(n) +
               ", \"source_mb\": " + std::to_string(int(mb)) +
               ", \"geokiosk\": " + runJson(a, mb, ourTiles, ourBytes) +
               ", \"gdal\": " + runJson(g, mb, gdalTiles, gdalBytes) + ratio;
        first = false;
        if (!keep) {
            fs::remove(dem, ec);
            fs::remove(ours, ec);
            fs::remove(theirs, ec);
        }
    }
    out += "]}";
    std::printf("%s\n", out.c_str());
    return 0;
}
