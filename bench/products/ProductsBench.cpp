// Derived products benchmark (issue 19): the frame time of the ANUGA cairns replay with 0, 1 and
// 3 product layers (maximum; + arrival and duration) over the same depth sequence layer, in the
// same run, headless on llvmpipe. Prints ONE JSON object with each configuration's frame time
// and the cost of one product as a fraction of the frame it is drawn in (goal < 0.15). The
// product configurations run twice: with the depth layer reading its frames from the products'
// texel (the default, docs/products.md) and with it sampling its own frame pair
// (GEOKIOSK_PRODUCT_FRAME_SHARING=0), and the machine's load average is printed.
//
// The sessions are prepared once (view resident, the pair and the products' states on the
// GPU), then drawn in turn, frame after frame, while the data time sweeps through the run, so
// they see the same machine load; the loader runs as in play (states of new steps are computed
// on its thread, never on the frame). Then a second phase draws them at one fixed data time
// ("still": no step, no upload, no loader work), which leaves the cost of shading alone.
//
// Besides wall time, each configuration reports CPU time per frame by thread (from
// /proc/self/task/*/schedstat, robust on a shared machine): the render thread, llvmpipe's
// rasterizer threads while it is drawn, and its own loader thread over the sweep.
//
// usage: bench-products CAIRNS.sww [--frames N] [--size WxH]
#include "runtime/app/FrameStats.h"
#include "runtime/app/Session.h"
#include "runtime/core/Clock.h"
#include "runtime/core/Strings.h"
#include "runtime/core/TimeParse.h"
#include "runtime/gl/RenderTarget.h"
#include "runtime/import/Importer.h"

#include "bench/common/HeadlessGl.h"
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <set>
#include <unistd.h>

using namespace kiosk;
namespace fs = std::filesystem;

namespace {

constexpr const char* kStart = "2026-03-14T00:00:00Z";

std::string layer(const std::string& id, const std::string& kind, const std::string& extra) {
    return R"({ "id": ")" + id + R"(", "kind": ")" + kind +
           R"(", "source": { "store": "s", "sequence": "flood" }, "nodataAs": 0, )" + extra + "}";
}

std::string scenario(int products) {
    std::string layers = layer("flood", "sequence", R"("transfer": "depth")");
    if (products >= 1)
        layers +=
            ", " +
            layer("max", "maximum",
                  R"("transfer": "depth", "operation": { "type": "opacity", "opacity": 0.5 })");
    if (products >= 3) {
        layers +=
            ", " + layer("arr", "arrival",
                         R"("transfer": "t", "operation": { "type": "opacity", "opacity": 0.5 },
                                  "product": { "threshold": 0.1, "timeUnits": "min" })");
        layers +=
            ", " + layer("dur", "duration",
                         R"("transfer": "t", "operation": { "type": "opacity", "opacity": 0.5 },
                                  "product": { "threshold": 0.5, "timeUnits": "min" })");
    }
    return R"({ "version": 1, "title": "ANUGA products", "stores": { "s": "anuga.gpkg" },
        "terrain": { "store": "s" },
        "clock": { "start": ")" +
           std::string(kStart) + R"(", "end": "2026-03-14T00:08:20Z", "rate": 10 },
        "transferFunctions": {
          "depth": { "units": "m", "stops": [ { "value": 0, "color": "#c6dbef00" },
            { "value": 0.05, "color": "#6baed6" }, { "value": 2, "color": "#08306b" } ] },
          "t": { "units": "min", "stops": [ { "value": 0, "color": "#440154" },
            { "value": 8, "color": "#fde725" } ] } },
        "layers": [ )" +
           layers + " ] }";
}

// The ids of this process's threads whose name starts with `prefix`.
std::set<std::string> threadsNamed(const std::string& prefix) {
    std::set<std::string> ids;
    std::error_code ec;
    for (const auto& task : fs::directory_iterator("/proc/self/task", ec)) {
        std::string name;
        std::getline(std::ifstream(task.path() / "comm"), name);
        if (name.rfind(prefix, 0) == 0) ids.insert(task.path().filename().string());
    }
    return ids;
}

// CPU time (ms) of the threads `ids` of this process.
double threadsCpuMs(const std::set<std::string>& ids) {
    double ns = 0;
    for (const auto& tid : ids) {
        double run = 0;  // schedstat: ns on the CPU, ns waiting, timeslices
        if (std::ifstream(fs::path("/proc/self/task") / tid / "schedstat") >> run) ns += run;
    }
    return ns / 1e6;
}

double mainThreadCpuMs() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) / 1e6;
}

// What one configuration measured in one phase.
struct Figures {
    std::vector<double> ms;  // wall time per frame (drawFrame + glFinish)
    double renderCpuMs = 0, rasterCpuMs = 0, uploadMs = 0;
    std::uint64_t uploads = 0;
    int held = 0;
    std::uint64_t triangles = 0, tiles = 0;  // of the last frame (the view is the same)
};

}  // namespace

int main(int argc, char** argv) {
    std::string sww;
    int frames = 120, w = 1280, h = 720;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--frames") && i + 1 < argc) {
            frames = std::max(10, std::atoi(argv[++i]));
        } else if (!std::strcmp(argv[i], "--size") && i + 1 < argc) {
            if (auto wh = parseSize(argv[++i])) std::tie(w, h) = *wh;
        } else if (argv[i][0] == '-') {
            std::fprintf(stderr, "usage: bench-products CAIRNS.sww [--frames N] [--size WxH]\n");
            return 2;
        } else {
            sww = argv[i];
        }
    }
    nlohmann::json out;
    out["benchmark"] = "products";
    std::error_code ec;
    if (sww.empty() || !fs::exists(sww, ec)) {
        out["skipped"] = (sww.empty() ? std::string("no SWW given") : sww + " not present");
        std::printf("%s\n", out.dump().c_str());
        return 0;
    }
    auto headless = bench::openHeadlessGl();
    if (!headless) return 3;
    out["renderer"] = headless->caps.renderer;
    const fs::path dir =
        fs::temp_directory_path() / ("kiosk-bench-products-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    import::ImportOptions o;
    o.store = dir / "anuga.gpkg";
    o.quiet = true;
    o.name = "elevation";
    Diagnostics d = import::importElevation(sww, o);
    o.name = "flood";
    o.start = *parseIso8601(kStart);
    if (!d.hasErrors()) d.append(import::importSequence({sww}, o));
    if (d.hasErrors()) {
        std::fprintf(stderr, "%s", d.format().c_str());
        fs::remove_all(dir, ec);
        return 1;
    }
    // 0, 1 and 3 products with the depth layer reading its frames from the products' texels
    // (the default), then 1 and 3 with the depth layer sampling its own frame pair (sharing off).
    const int counts[5] = {0, 1, 3, 1, 3};
    const bool shared[5] = {true, true, true, false, false};
    std::vector<std::unique_ptr<app::Session>> sessions;
    std::vector<std::set<std::string>> loaders;  // each session's loader thread
    for (int k = 0; k < 5; ++k) {
        const std::set<std::string> before = threadsNamed("kiosk-loader");
        const int n = counts[k];
        const fs::path file = dir / ("products" + std::to_string(n) + ".json");
        std::ofstream(file) << scenario(n);
        if (!shared[k]) setenv("GEOKIOSK_PRODUCT_FRAME_SHARING", "0", 1);
        auto s = app::Session::open(file, headless->caps);
        unsetenv("GEOKIOSK_PRODUCT_FRAME_SHARING");
        if (!s) {
            std::fprintf(stderr, "%s", s.diagnostics.format().c_str());
            fs::remove_all(dir, ec);
            return 1;
        }
        sessions.push_back(std::move(*s.value));
        std::set<std::string> mine;
        for (const auto& id : threadsNamed("kiosk-loader"))
            if (!before.count(id)) mine.insert(id);
        loaders.push_back(std::move(mine));
    }
    auto target = gl::RenderTarget::create(w, h);
    if (!target) return 3;
    target->bind();
    RealClock wall;
    const double t0 = sessions[0]->startTime(), span = sessions[0]->endTime() - t0;
    auto cameraOf = [&](app::Session& s) {
        auto vp = s.viewpointAt(t0, "");
        return app::makeCamera(vp ? *vp : s.terrain().overviewViewpoint(), s.terrain().bounds(), w,
                               h, s.scenario().camera.fovY);
    };
    // llvmpipe's rasterizer threads, started with the context.
    const std::set<std::string> rasterizers = threadsNamed("llvmpipe");
    // Draws every session at data time timeOf(f) for f < frames (each settled first, not timed,
    // as a kiosk's prefetch would have it).
    auto run = [&](auto timeOf, std::vector<double>* loaderMs) {
        std::vector<Figures> fig(sessions.size());
        std::vector<double> loader0(sessions.size());
        for (std::size_t k = 0; k < sessions.size(); ++k) loader0[k] = threadsCpuMs(loaders[k]);
        for (int f = 0; f < frames; ++f) {
            const double t = timeOf(f);
            for (std::size_t k = 0; k < sessions.size(); ++k) {
                app::Session& s = *sessions[k];
                const math::Camera cam = cameraOf(s);
                for (int tries = 0; tries < 20000 && (tries == 0 || !s.terrain().settled());
                     ++tries) {
                    s.prepare(cam, t);
                    if (!s.terrain().settled()) usleep(500);
                }
                const double raster = threadsCpuMs(rasterizers), cpu = mainThreadCpuMs();
                const double a = wall.now();
                const app::FrameRecord rec = s.drawFrame(cam, t, w, h);
                glFinish();
                fig[k].ms.push_back((wall.now() - a) * 1000.0);
                fig[k].renderCpuMs += mainThreadCpuMs() - cpu;
                fig[k].rasterCpuMs += threadsCpuMs(rasterizers) - raster;
                fig[k].uploadMs += rec.uploadMs;
                fig[k].uploads += rec.uploads;
                fig[k].held += s.terrain().frameInfo().holdingSequence;
                fig[k].triangles = s.terrain().frameInfo().triangles;
                fig[k].tiles = s.terrain().frameInfo().tilesDrawn;
            }
        }
        if (loaderMs)
            for (std::size_t k = 0; k < sessions.size(); ++k)
                loaderMs->push_back(threadsCpuMs(loaders[k]) - loader0[k]);
        return fig;
    };
    std::vector<double> loaderMs;
    // The data time sweeps the run once, then stays at mid-run.
    const std::vector<Figures> sweep =
        run([&](int f) { return t0 + span * (0.05 + 0.9 * double(f) / double(frames - 1)); },
            &loaderMs);
    const std::vector<Figures> still = run([&](int) { return t0 + 0.5 * span; }, nullptr);
    out["size"] = std::to_string(w) + "x" + std::to_string(h);
    out["frames_per_configuration"] = frames;
    // Small triangles shade whole 2x2 quads (and llvmpipe 4x4 blocks) for a few pixels: each
    // layer's per-fragment work is paid for every fragment shaded, helpers included.
    out["view"] = {{"tiles_drawn", still[0].tiles}, {"triangles", still[0].triangles}};
    const auto report = [&](const std::vector<Figures>& fig, std::size_t k) {
        const Figures& x = fig[k];
        const double base = app::percentile(fig[0].ms, 50);
        const double p50 = app::percentile(x.ms, 50), n = double(x.ms.size());
        const double cpu = (x.renderCpuMs + x.rasterCpuMs) / n;
        const double baseCpu = (fig[0].renderCpuMs + fig[0].rasterCpuMs) / n;
        nlohmann::json r;
        r["frame_ms"] = {{"p50", p50}, {"p95", app::percentile(x.ms, 95)}};
        // CPU per frame: the render thread (update, uploads, draw calls) and llvmpipe's
        // rasterizer threads (shading) while this configuration was drawn.
        r["cpu_ms_per_frame"] = {{"render_thread", x.renderCpuMs / n},
                                 {"rasterizer", x.rasterCpuMs / n},
                                 {"total", cpu}};
        r["uploads_per_frame"] = double(x.uploads) / n;
        r["upload_ms_per_frame"] = x.uploadMs / n;
        r["held_frames"] = x.held;
        if (counts[k] > 0) {
            const double each = (p50 - base) / counts[k];
            r["ms_per_product"] = each;
            r["fraction_of_frame_per_product"] = each / std::max(1e-9, p50);
            r["within_goal_0_15"] = each / std::max(1e-9, p50) < 0.15;
            r["cpu_fraction_of_frame_per_product"] =
                (cpu - baseCpu) / counts[k] / std::max(1e-9, cpu);
        }
        return r;
    };
    for (std::size_t k = 0; k < 5; ++k) {
        nlohmann::json r = report(sweep, k);
        r["product_layers"] = counts[k];
        r["depth_layer_reads_product_texel"] = shared[k];
        r["loader_cpu_ms_per_frame"] = loaderMs[k] / frames;
        for (const auto& [name, value] : sessions[k]->budgets())
            if (name == "derived_state_bytes") r["derived_state_bytes"] = value;
        r["still"] = report(still, k);
        out["results"].push_back(r);
    }
    out["baseline"] =
        "0 product layers: the depth sequence layer alone, same run, same view and times";
    out["still"] = "the same sessions drawn at one data time (mid-run): no step, upload or load";
    double loadavg[3] = {0, 0, 0};
    if (getloadavg(loadavg, 3) == 3)
        out["load_average_1_5_15"] = {loadavg[0], loadavg[1], loadavg[2]};
    sessions.clear();
    fs::remove_all(dir, ec);
    std::printf("%s\n", out.dump().c_str());
    return 0;
}
