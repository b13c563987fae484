#include "runtime/app/InfoCommand.h"

#include "runtime/app/Args.h"

#include "runtime/core/ExitCode.h"
#include "runtime/core/TimeParse.h"
#include "runtime/io/StoreIntegrity.h"
#include "runtime/io/StoreReader.h"
#include "runtime/loader/TileLoader.h"
#include "runtime/scene/CacheBudgets.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>

namespace kiosk::app {

namespace {

const char* kindName(io::LayerKind k) {
    switch (k) {
        case io::LayerKind::Elevation:
            return "elevation";
        case io::LayerKind::Imagery:
            return "imagery";
        case io::LayerKind::Sequence:
            return "sequence_frame";
    }
    return "?";
}

/** @brief The budgets a scenario over this store gets by default (docs/performance.md). */
nlohmann::json budgetsOf(const io::TileGrid& g) {
    using D = scene::CacheDefaults;
    const std::int64_t tw = g.levels.empty() ? 0 : g.levels.back().tileWidth;
    const std::int64_t th = g.levels.empty() ? 0 : g.levels.back().tileHeight;
    return {{"cache", "sized to the view's working set (terrain.cacheBytes/gpuBytes override)"},
            {"working_set_margin", D::kWorkingSetMargin},
            {"cache_cpu_floor_bytes", D::kFloorCpuBytes},
            {"cache_gpu_floor_bytes", D::kFloorGpuBytes},
            {"upload_bytes_per_frame", D::kUploadBytesPerFrame},
            {"upload_ms_per_frame", D::kUploadMsPerFrame},
            {"loader_max_in_flight", loader::LoaderOptions{}.maxInFlight},
            {"loader_max_bytes_in_flight", loader::LoaderOptions{}.maxBytesInFlight},
            // What one tile costs resident: RGBA8 with mipmaps; sequence frames as RG16F posts.
            {"imagery_tile_gpu_bytes", tw * th * 4 * 4 / 3},
            {"sequence_tile_gpu_bytes", (tw + 1) * (th + 1) * 4}};
}

}  // namespace

int runInfoCommand(const std::vector<std::string>& args) {
    if (wantsHelp(args)) return showHelp("usage: geokiosk info STORE [--json]\n");
    std::string path;
    bool json = false, check = false, deep = false;
    for (const auto& a : args) {
        if (a == "--json") {
            json = true;
        } else if (a == "--check") {
            check = true;
        } else if (a == "--deep") {
            deep = true;
        } else if (a.rfind("--", 0) == 0 || !path.empty()) {
            std::fprintf(stderr,
                         "geokiosk: info: unexpected argument '%s' [CLI_USAGE]\n"
                         "usage: geokiosk info STORE [--json] [--check [--deep]]\n",
                         a.c_str());
            return kExitUsage;
        } else {
            path = a;
        }
    }
    if (path.empty()) {
        std::fprintf(stderr, "usage: geokiosk info STORE [--json] [--check [--deep]]\n");
        return kExitUsage;
    }
    if (deep && !check) {
        std::fprintf(stderr, "geokiosk: info: --deep needs --check [CLI_USAGE]\n");
        return kExitUsage;
    }
    auto reader = io::StoreReader::open(path);
    for (const auto& d : reader.diagnostics.items())
        std::fprintf(stderr, "%s\n", d.format().c_str());
    if (!reader) return kExitBadInput;
    if (check) {
        // Core and geokiosk tables' invariants; with --deep every tile decoded (StoreIntegrity.h).
        const Diagnostics problems = io::checkStoreIntegrity(
            path, deep ? io::IntegrityLevel::Deep : io::IntegrityLevel::Tables);
        for (const auto& d : problems.items()) std::fprintf(stderr, "%s\n", d.format().c_str());
        if (problems.hasErrors()) return kExitBadInput;
        if (!json) std::printf("check: ok%s\n", deep ? " (every tile decoded)" : "");
    }
    const io::StoreInfo& info = (*reader)->info();
    const io::TileGrid& g = info.grid;
    std::int64_t frameTiles = 0;
    if (json) {
        nlohmann::json j;
        j["path"] = info.path;
        j["size_bytes"] = info.sizeBytes;
        j["crs"] = {{"srs_id", g.srsId}, {"name", g.crsName}};
        j["extent"] = {g.minX, g.minY, g.maxX, g.maxY};
        j["levels"] = int(g.levels.size());
        j["tile_size"] = g.levels.empty() ? 0 : g.levels.back().tileWidth;
        j["finest_pixel_size"] = g.levels.empty() ? 0.0 : g.levels.back().pixelXSize;
        j["layers"] = nlohmann::json::array();
        for (const auto& l : info.layers) {
            if (l.kind == io::LayerKind::Sequence) {
                frameTiles += l.tileCount;
                continue;
            }
            nlohmann::json lj = {{"name", l.name},
                                 {"kind", kindName(l.kind)},
                                 {"units", l.units},
                                 {"min", l.minValue},
                                 {"max", l.maxValue},
                                 {"levels", l.levels},
                                 {"tiles", l.tileCount},
                                 {"data_extent", {l.dataMinX, l.dataMinY, l.dataMaxX, l.dataMaxY}}};
            if (l.nodata) lj["nodata"] = *l.nodata;
            j["layers"].push_back(lj);
        }
        j["sequences"] = nlohmann::json::array();
        for (const auto& s : info.sequences) {
            nlohmann::json sj = {{"name", s.name},
                                 {"units", s.units},
                                 {"variable", s.variable},
                                 {"categorical", s.categorical},
                                 {"frames", s.frameTimes.size()},
                                 {"levels", s.levels}};
            if (!s.frameTimes.empty()) {
                sj["first_time"] = formatIso8601(s.frameTimes.front());
                sj["last_time"] = formatIso8601(s.frameTimes.back());
                double lo = s.frameMin.front(), hi = s.frameMax.front();
                for (std::size_t i = 0; i < s.frameMin.size(); ++i) {
                    lo = std::min(lo, s.frameMin[i]);
                    hi = std::max(hi, s.frameMax[i]);
                }
                sj["min"] = lo;
                sj["max"] = hi;
            }
            j["sequences"].push_back(sj);
        }
        j["sequence_tiles"] = frameTiles;
        j["budgets"] = budgetsOf(g);
        std::printf("%s\n", j.dump(2).c_str());
        return kExitOk;
    }
    std::printf("store:   %s (%.1f MB)\n", info.path.c_str(), double(info.sizeBytes) / 1e6);
    std::printf("crs:     %s (srs_id %d)\n", g.crsName.c_str(), g.srsId);
    std::printf("extent:  %.3f %.3f %.3f %.3f\n", g.minX, g.minY, g.maxX, g.maxY);
    if (!g.levels.empty())
        std::printf("grid:    %zu levels, %dx%d tiles, finest pixel %.4g\n", g.levels.size(),
                    g.levels.back().tileWidth, g.levels.back().tileHeight,
                    g.levels.back().pixelXSize);
    for (const auto& l : info.layers) {
        if (l.kind == io::LayerKind::Sequence) continue;
        // Units only when the store records some (an empty "()" reads as a bug).
        std::printf("layer:   %s [%s] %lld tiles, %d levels, values %.3f..%.3f%s%s\n",
                    l.name.c_str(), kindName(l.kind), (long long)l.tileCount, l.levels, l.minValue,
                    l.maxValue, l.units.empty() ? "" : " ", l.units.c_str());
    }
    for (const auto& s : info.sequences) {
        std::printf("sequence: %s%s %zu frames", s.name.c_str(),
                    s.categorical ? " [categorical]" : "", s.frameTimes.size());
        if (!s.frameTimes.empty())
            std::printf(", %s .. %s", formatIso8601(s.frameTimes.front()).c_str(),
                        formatIso8601(s.frameTimes.back()).c_str());
        if (!s.units.empty()) std::printf(" (%s)", s.units.c_str());
        std::printf("\n");
    }
    const nlohmann::json b = budgetsOf(g);
    std::printf(
        "budgets: cache sized to the view's working set x%.1f (at least %.0f MiB CPU, %.0f MiB "
        "GPU; terrain.cacheBytes/gpuBytes override), uploads %.0f MiB / %.0f ms per frame, "
        "%d tiles / %.0f MiB in flight; per tile: imagery %lld B, sequence frame %lld B\n",
        b["working_set_margin"].get<double>(), b["cache_cpu_floor_bytes"].get<double>() / 1048576.0,
        b["cache_gpu_floor_bytes"].get<double>() / 1048576.0,
        b["upload_bytes_per_frame"].get<double>() / 1048576.0,
        b["upload_ms_per_frame"].get<double>(), b["loader_max_in_flight"].get<int>(),
        b["loader_max_bytes_in_flight"].get<double>() / 1048576.0,
        b["imagery_tile_gpu_bytes"].get<long long>(),
        b["sequence_tile_gpu_bytes"].get<long long>());
    return kExitOk;
}

}  // namespace kiosk::app
