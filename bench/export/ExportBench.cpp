// Video export benchmark (issue 18): the same frames of a scenario rendered headless at 1080p
// three ways in one run, and ONE JSON object printed: frames/s of rendering alone (draw, no
// output), of `render` to PNG (draw + readback + PNG file) and of export to H.264 MP4 (draw +
// readback + encoder queue, encoding on its own thread, the file finished), and the encode
// overhead relative to the frame time of rendering alone (goal < 10 %). A warm-up pass first
// makes every pass start with the same resident tiles.
//
// usage: bench-export [SCENARIO] [--size 1920x1080] [--frames N] [--fps 30] [--format mp4|mkv|webm]
#include "runtime/anim/ScenarioClock.h"
#include "runtime/app/FrameOutput.h"
#include "runtime/app/Session.h"
#include "runtime/core/Strings.h"
#include "runtime/gl/RenderTarget.h"

#include "bench/common/HeadlessGl.h"
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

using namespace kiosk;

namespace {

enum class Output { None, Png, Video };

/** Wall seconds for all frames, output included (the video's finish() too). */
double pass(app::Session& s, gl::RenderTarget& rt, const std::vector<double>& times, Output kind,
            const std::filesystem::path& out, const video::VideoOptions& vo) {
    std::optional<app::FrameOutput> output;
    if (kind == Output::Png) output.emplace(app::FrameOutput::folder(out));
    if (kind == Output::Video) {
        auto v = app::FrameOutput::video(vo);
        if (!v) {
            std::fprintf(stderr, "%s\n", v.diagnostics.format().c_str());
            std::exit(1);
        }
        output.emplace(std::move(*v.value));
    }
    const int w = rt.width(), h = rt.height();
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
        const gl::Image img = rt.readColor();
        Diagnostics d;
        if (!output->write(img, d)) {
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
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
    std::string scenario = "scenarios/demo/rainier.json", format = "mp4";
    int width = 1920, height = 1080, frames = 60;
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
        } else if (a.rfind("--", 0) != 0) {
            scenario = a;
        } else {
            std::fprintf(stderr,
                         "usage: bench-export [SCENARIO] [--size WxH] [--frames N] [--fps F] "
                         "[--format mp4|mkv|webm]\n");
            return 2;
        }
    }
    auto gl = bench::openHeadlessGl();
    if (!gl) return 3;
    auto opened = app::Session::open(scenario, gl->caps);
    if (!opened) {
        std::fprintf(stderr, "%s\n", opened.diagnostics.format().c_str());
        return 1;
    }
    app::Session& s = **opened;
    auto rt = gl::RenderTarget::create(width, height);
    if (!rt) return 3;
    // The demo's first `frames` frames at `fps` of playback (its clock rate), as `render` does.
    const double rate = s.scenario().clock ? std::fabs(s.scenario().clock->rate) : 1.0;
    std::vector<double> times;
    for (int i = 0; i < frames; ++i) times.push_back(s.startTime() + double(i) / fps * rate);

    const auto dir =
        std::filesystem::temp_directory_path() / ("bench-export-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir / "png");
    video::VideoOptions vo;
    vo.path = dir / ("out." + format);
    vo.format = *video::videoFormatForPath(vo.path);
    vo.width = width;
    vo.height = height;
    vo.fps = fps;

    pass(s, *rt, times, Output::None, {}, vo);  // warm-up: every pass then finds the same tiles
    const double render = pass(s, *rt, times, Output::None, {}, vo);
    const double png = pass(s, *rt, times, Output::Png, dir / "png", vo);
    const double video = pass(s, *rt, times, Output::Video, {}, vo);
    const auto bytes = std::filesystem::file_size(vo.path);
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);

    const double n = double(frames);
    nlohmann::json j;
    j["benchmark"] = "export";
    j["scenario"] = scenario;
    j["size"] = std::to_string(width) + "x" + std::to_string(height);
    j["frames"] = frames;
    j["fps_playback"] = fps;
    j["format"] = video::videoFormatName(vo.format);
    j["crf"] = video::defaultCrf(vo.format);
    j["render_only_fps"] = n / render;
    j["render_png_fps"] = n / png;
    j["export_fps"] = n / video;
    j["frame_ms"] = {{"render_only", render / n * 1000},
                     {"render_png", png / n * 1000},
                     {"export", video / n * 1000}};
    j["export_overhead_pct"] = (video - render) / render * 100.0;
    j["png_overhead_pct"] = (png - render) / render * 100.0;
    j["goal_overhead_pct"] = 10.0;
    j["video_bytes"] = bytes;
    j["hardware_threads"] = std::thread::hardware_concurrency();
    std::printf("%s\n", j.dump().c_str());
    return 0;
}
