#include "runtime/service/ServiceState.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <malloc.h>
#include <unistd.h>

namespace kiosk::service {

HealthVerdict evaluateHealth(const ServiceSnapshot& s, double now, double stallSeconds) {
    nlohmann::json body;
    std::string reason;
    if (s.lastFrameAt < 0)
        reason = "no frame yet";
    else if (now - s.lastFrameAt > stallSeconds) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "no frame for %.1f s (limit %.1f s)", now - s.lastFrameAt,
                      stallSeconds);
        reason = buf;
    }
    if (!reason.empty() && !s.holding.empty())
        reason = s.holding + ": " + reason + (s.lastFrameAt >= 0 ? ", last frame kept" : "");
    body["status"] = reason.empty() ? "ok" : "stalled";
    if (!reason.empty()) body["reason"] = reason;
    body["frames"] = s.frames;
    body["scenario"] = s.scenario;
    body["data_time"] = s.dataTime;
    body["fps"] = s.fps;
    body["paused"] = s.paused;
    if (s.playlistIndex >= 0) {
        body["playlist_position"] = s.playlistIndex;
        body["playlist_length"] = s.playlistLength;
    }
    nlohmann::json degraded = nlohmann::json::array();
    for (const auto& l : s.layers)
        if (l.state != "ready")
            degraded.push_back({{"layer", l.id}, {"state", l.state}, {"message", l.message}});
    body["degraded_layers"] = degraded;
    body["store_degraded"] = s.storeDegraded;
    body["store_swaps"] = s.storeSwaps;
    nlohmann::json stores = nlohmann::json::array();
    for (const auto& [path, inode] : s.storeFiles)
        stores.push_back({{"path", path}, {"inode", inode}});
    body["stores"] = stores;
    body["warnings"] = s.warnings;
    return {reason.empty() ? 200 : 503, body.dump()};
}

std::uint64_t readRssBytes() {
    std::FILE* f = std::fopen("/proc/self/statm", "r");
    if (!f) return 0;
    unsigned long long size = 0, resident = 0;
    const int n = std::fscanf(f, "%llu %llu", &size, &resident);
    std::fclose(f);
    return n == 2 ? resident * std::uint64_t(sysconf(_SC_PAGESIZE)) : 0;
}

std::uint64_t readHeapInUseBytes() {
    const struct mallinfo2 mi = mallinfo2();
    return std::uint64_t(mi.uordblks) + std::uint64_t(mi.hblkhd);  // arena chunks + mmapped
}

std::string renderMetrics(const ServiceSnapshot& s, const ProcessFigures& process) {
    using T = MetricsWriter::Type;
    MetricsWriter w;
    w.histogram("geokiosk_frame_time_ms", "Wall time of one frame loop iteration in milliseconds.",
                kFrameMsBuckets, s.frameMs);
    w.family("geokiosk_frames_total", "Frames completed.", T::Counter);
    w.sample(double(s.frames));
    w.family("geokiosk_held_frames_total",
             "Frames on which a sequence showed an older step because tiles were late.",
             T::Counter);
    w.sample(double(s.heldFrames));
    w.family("geokiosk_sequence_missing_frames_total",
             "Frames drawn while wanted sequence tiles were not resident.", T::Counter);
    w.sample(double(s.sequenceMissingFrames));
    w.family("geokiosk_cache_bytes", "Bytes held by each cache.", T::Gauge);
    w.sample("", {{"kind", "cpu_tiles"}}, double(s.cache.cpuTiles));
    w.sample("", {{"kind", "gpu_textures"}}, double(s.cache.gpuTextures));
    w.sample("", {{"kind", "gpu_meshes"}}, double(s.cache.gpuMeshes));
    w.sample("", {{"kind", "sqlite_page_cache"}}, double(s.cache.sqlitePageCache));
    w.sample("", {{"kind", "luts"}}, double(s.cache.luts));
    w.sample("", {{"kind", "mappings"}}, double(s.cache.mappings));
    w.sample("", {{"kind", "font_atlas"}}, double(s.cache.fontAtlas));
    w.family("geokiosk_cache_budget_bytes",
             "Byte budget of each cache (gpu: textures and meshes; sqlite_page_cache: per "
             "connection times the connections open).",
             T::Gauge);
    w.sample("", {{"kind", "cpu_tiles"}}, double(s.budgets.cpuTiles));
    w.sample("", {{"kind", "gpu"}}, double(s.budgets.gpu));
    w.sample("", {{"kind", "sqlite_page_cache"}}, double(s.budgets.sqlitePageCache));
    w.sample("", {{"kind", "luts"}}, double(s.budgets.luts));
    w.sample("", {{"kind", "mappings"}}, double(s.budgets.mappings));
    w.sample("", {{"kind", "font_atlas"}}, double(s.budgets.fontAtlas));
    w.family("geokiosk_store_connections", "SQLite store connections open.", T::Gauge);
    w.sample(double(s.budgets.storeConnections));
    w.family("geokiosk_loader_queue_depth", "Tile requests waiting for the loader thread.",
             T::Gauge);
    w.sample(double(s.loaderQueue));
    w.family("geokiosk_layer_state",
             "1 for the state each layer is in (ready, degraded, failed), else 0.", T::Gauge);
    for (const auto& l : s.layers)
        for (const char* st : {"ready", "degraded", "failed"})
            w.sample("", {{"layer", l.id}, {"state", st}}, l.state == st ? 1.0 : 0.0);
    w.family("geokiosk_reloads_total", "Scenario or store reloads taken.", T::Counter);
    w.sample(double(s.reloads));
    w.family("geokiosk_reload_failures_total", "Scenario or store reloads refused.", T::Counter);
    w.sample(double(s.reloadFailures));
    w.family("geokiosk_store_swaps_total", "Stores replaced on disk and taken over.", T::Counter);
    w.sample(double(s.storeSwaps));
    w.family("geokiosk_store_degraded", "1 while a store file is missing (picture kept).",
             T::Gauge);
    w.sample(s.storeDegraded ? 1.0 : 0.0);
    w.family("geokiosk_playlist_position", "Index of the playlist entry on screen (-1: none).",
             T::Gauge);
    w.sample(double(s.playlistIndex));
    w.family("geokiosk_playlist_skipped_total", "Playlist entries skipped as broken.", T::Counter);
    w.sample(double(s.playlistSkipped));
    w.family("geokiosk_data_time_seconds", "Data time drawn, Unix epoch seconds.", T::Gauge);
    w.sample(s.dataTime);
    w.family("geokiosk_fps", "Frames per second over the last second.", T::Gauge);
    w.sample(s.fps);
    w.family("geokiosk_resident_memory_bytes", "Resident set size of the process.", T::Gauge);
    w.sample(double(process.rssBytes));
    w.family("geokiosk_heap_in_use_bytes", "C heap bytes allocated and not freed (mallinfo2).",
             T::Gauge);
    w.sample(double(process.heapBytes));
    w.family("geokiosk_uptime_seconds", "Seconds since the kiosk started.", T::Gauge);
    w.sample(process.uptimeSeconds);
    return w.text();
}

}  // namespace kiosk::service
