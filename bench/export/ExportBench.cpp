// Video export benchmark (issue 18): the same frames of a scenario rendered headless at 1080p
// three ways in one run, and ONE JSON object printed: frames/s of rendering alone (draw, no
// output), of `render` to PNG (draw + readback + PNG file) and of export to H.264 MP4 (draw +
// readback + encoder queue, encoding on its own thread, the file finished), and the encode
// overhead relative to the frame time of rendering alone (goal < 10 %). A warm-up pass first
// makes every pass start with the same resident tiles. The passes run `--rounds` times,
// interleaved, and each reports its fastest round (the one least disturbed by other jobs on the
// machine) and its CPU time per frame (all threads): on 2 cores llvmpipe already keeps both
// busy, so the encoder's CPU time is what the export costs. The load average is reported with
// the figures, since other processes on the machine move every wall-time figure.
// For .mp4 the pass `previous` exports the same frames with the previous default (libx264
// preset veryfast, CRF 15): the baseline of the preset change, same run. The pass
// `samepriority` exports with the encoder's threads at the render thread's priority (the code
// path before kEncoderNice): the baseline of the priority change, same run.
//
// usage: bench-export [SCENARIO] [--size 1920x1080] [--frames N] [--fps 30]
//                     [--format mp4|mkv|webm] [--rounds R] [--passes
//                     render,png,video,samepriority,previous]
// (--passes may also name rgba: drawing plus the RGBA readback, writing nothing: what the
// readback alone costs.)
#include "runtime/anim/ScenarioClock.h"
#include "runtime/app/FrameOutput.h"
#include "runtime/app/Session.h"
#include "runtime/core/Strings.h"
#include "runtime/gl/RenderTarget.h"

#include "bench/common/BenchScene.h"
#include "bench/common/PhaseTimes.h"
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

using namespace kiosk;

namespace {

enum class Output { None, Rgba, Png, Video, VideoPrevious };

struct PassTime {
    double wall = 0;   ///< seconds for all frames, output included (the video's finish() too)
    double cpuMs = 0;  ///< CPU time of every thread of the process over the pass
};

PassTime pass(app::Session& s, gl::RenderTarget& rt, const std::vector<double>& times, Output kind,
              const std::filesystem::path& out, const video::VideoOptions& vo) {
    std::optional<app::FrameOutput> output;
    if (kind == Output::Png) output.emplace(app::FrameOutput::folder(out));
    if (kind == Output::Video || kind == Output::VideoPrevious) {
        auto v = app::FrameOutput::video(vo);
        if (!v) {
            std::fprintf(stderr, "%s\n", v.diagnostics.format().c_str());
            std::exit(1);
        }
        output.emplace(std::move(*v.value));
    }
    const int w = rt.width(), h = rt.height();
    std::vector<std::uint8_t> readback(std::size_t(w) * std::size_t(h) * 4);
    const double cpu0 = bench::processCpuMs();
    const auto t0 = std::chrono::steady_clock::now();
    for (double t : times) {
        auto vp = s.viewpointAt(t, "");
        const math::Camera cam =
            app::makeCamera(*vp, s.terrain().bounds(), w, h, s.scenario().camera.fovY);
        for (s.prepare(cam, t); !s.terrain().settled(); s.prepare(cam, t))
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        rt.bind();
        s.drawFrame(cam, t, w, h);
        if (kind == Output::None) {
            glFinish();
            continue;
        }
        if (kind == Output::Rgba) {  // the RGBA readback alone, what PNG and video take
            rt.readInto(readback.data());
            continue;
        }
        Diagnostics d;
        if (!output->write(rt, d)) {
            std::fprintf(stderr, "%s\n", d.format().c_str());
            std::exit(1);
        }
    }
    if (output) {
        Diagnostics d;
        if (!output->finish(d)) {
            std::fprintf(stderr, "%s\n", d.format().c_str());
            std::exit(1);
        }
    }
    PassTime p;
    p.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    p.cpuMs = bench::processCpuMs() - cpu0;
    return p;
}

double loadAverage() {
    double l[1] = {0};
    return getloadavg(l, 1) == 1 ? l[0] : -1;
}

}  // namespace

int main(int argc, char** argv) {
    std::string scenario = "scenarios/demo/rainier.json", format = "mp4",
                passes = "render,png,video,samepriority,previous";
    int width = 1920, height = 1080, frames = 60, rounds = 2;
    double fps = 30;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const bool more = i + 1 < argc;
        if (a == "--size" && more) {
            auto wh = parseSize(argv[++i]);
            if (!wh) return 2;
            width = wh->first;
            height = wh->second;
        } else if (a == "--frames" && more) {
            frames = std::atoi(argv[++i]);
        } else if (a == "--fps" && more) {
            fps = std::atof(argv[++i]);
        } else if (a == "--format" && more) {
            format = argv[++i];
        } else if (a == "--rounds" && more) {
            rounds = std::max(1, std::atoi(argv[++i]));
        } else if (a == "--passes" && more) {
            passes = argv[++i];
        } else if (a.rfind("--", 0) != 0) {
            scenario = a;
        } else {
            std::fprintf(stderr,
                         "usage: bench-export [SCENARIO] [--size WxH] [--frames N] [--fps F] "
                         "[--format mp4|mkv|webm] [--rounds R] "
                         "[--passes render,png,video,samepriority,previous]\n");
            return 2;
        }
    }
    auto scene = bench::openBenchScene(scenario, width, height);
    if (!scene) return scene.exitCode;
    app::Session& s = scene.s();
    gl::RenderTarget& rt = *scene.target;
    // The demo's first `frames` frames at `fps` of playback (its clock rate), as `render` does.
    const double rate = s.scenario().clock ? std::fabs(s.scenario().clock->rate) : 1.0;
    std::vector<double> times;
    for (int i = 0; i < frames; ++i) times.push_back(s.startTime() + double(i) / fps * rate);

    const auto dir =
        std::filesystem::temp_directory_path() / ("bench-export-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir / "png");
    video::VideoOptions vo;
    vo.path = dir / ("out." + format);
    const auto vf = video::videoFormatForPath(vo.path);
    if (!vf) {
        std::fprintf(stderr, "bench-export: unknown --format %s\n", format.c_str());
        return 2;
    }
    vo.format = *vf;
    vo.width = width;
    vo.height = height;
    vo.fps = fps;

    // The previous default (libx264 veryfast, CRF 15): the same-run baseline of the preset.
    video::VideoOptions previous = vo;
    previous.path = dir / "previous.mp4";
    previous.preset = "veryfast";
    previous.crf = 15;
    video::VideoOptions samePriority = vo;
    samePriority.path = dir / "same-priority.mp4";
    samePriority.encoderNice = 0;

    const double loadBefore = loadAverage();
    pass(s, rt, times, Output::None, {}, vo);  // warm-up: every pass then finds the same tiles
    // --passes word, reported name, what is done after drawing each frame.
    const std::tuple<const char*, const char*, Output, const video::VideoOptions*> kinds[] = {
        {"render", "render_only", Output::None, &vo},
        {"rgba", "readback_rgba", Output::Rgba, &vo},
        {"png", "render_png", Output::Png, &vo},
        {"video", "export", Output::Video, &vo},
        {"samepriority", "export_same_priority", Output::Video, &samePriority},
        {"previous", "export_previous", Output::VideoPrevious, &previous}};
    std::map<std::string, PassTime> best;
    std::uintmax_t bytes = 0, previousBytes = 0;
    for (int r = 0; r < rounds; ++r)
        for (const auto& [word, name, kind, options] : kinds) {
            if (("," + passes + ",").find(std::string(",") + word + ",") == std::string::npos)
                continue;
            if (kind == Output::VideoPrevious && vo.format != video::VideoFormat::H264Mp4) continue;
            const PassTime p = pass(s, rt, times, kind, dir / "png", *options);
            auto it = best.find(name);
            if (it == best.end() || p.wall < it->second.wall) best[name] = p;
            if (options == &vo && kind == Output::Video)
                bytes = std::filesystem::file_size(vo.path);
            if (kind == Output::VideoPrevious)
                previousBytes = std::filesystem::file_size(previous.path);
        }
    const double loadAfter = loadAverage();
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);

    const double n = double(frames);
    nlohmann::json j;
    j["benchmark"] = "export";
    j["scenario"] = scenario;
    j["size"] = std::to_string(width) + "x" + std::to_string(height);
    j["frames"] = frames;
    j["rounds"] = rounds;
    j["fps_playback"] = fps;
    j["format"] = video::videoFormatName(vo.format);
    j["crf"] = video::defaultCrf(vo.format);
    if (vo.format == video::VideoFormat::H264Mp4) j["preset"] = video::defaultPreset();
    for (const auto& [name, p] : best) {
        j["frame_ms"][name] = p.wall / n * 1000;
        j["cpu_ms_per_frame"][name] = p.cpuMs / n;
        j["cores_busy"][name] = p.cpuMs / 1000 / p.wall;
        j[std::string(name) + "_fps"] = n / p.wall;
    }
    if (best.count("render_only")) {
        const double render = best["render_only"].wall;
        if (best.count("export"))
            j["export_overhead_pct"] = (best["export"].wall - render) / render * 100.0;
        if (best.count("export_same_priority"))
            j["export_same_priority_overhead_pct"] =
                (best["export_same_priority"].wall - render) / render * 100.0;
        if (best.count("export_previous"))
            j["export_previous_overhead_pct"] =
                (best["export_previous"].wall - render) / render * 100.0;
        if (best.count("render_png"))
            j["png_overhead_pct"] = (best["render_png"].wall - render) / render * 100.0;
    }
    j["goal_overhead_pct"] = 10.0;
    if (bytes) j["video_bytes"] = bytes;
    if (previousBytes) j["video_bytes_previous"] = previousBytes;
    j["hardware_threads"] = std::thread::hardware_concurrency();
    j["load_average"] = {loadBefore, loadAfter};
    std::printf("%s\n", j.dump().c_str());
    return 0;
}
