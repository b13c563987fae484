// bench-wall: the display wall's swap barrier on loopback (docs/wall.md). The leader runs here
// with the real SwapBarrier and ZeroMQ transport; 4 and then 16 follower *processes* (this
// bench-wall-follower) run FollowerSync and report ready as soon as a state arrives, so the
// figures are the protocol's cost, not drawing. Baseline in the same run: one node's headless
// frame time on the demo scenario (drawFrame + glFinish at 1280x720, tiles resident).
//   bench-wall SCENARIO [--frames N] [--size WxH]      prints ONE JSON object
#include "runtime/app/FrameStats.h"
#include "runtime/app/Session.h"
#include "runtime/core/Clock.h"
#include "runtime/core/Strings.h"
#include "runtime/gl/RenderTarget.h"
#include "runtime/wall/SwapBarrier.h"
#include "runtime/wall/ZmqTransport.h"

#include "bench/common/BenchScene.h"
#include "bench/common/SteadyTime.h"
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <signal.h>
#include <string>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

using namespace kiosk;
using Us = std::chrono::microseconds;

namespace {

using bench::nowUs;

struct BarrierRun {
    std::vector<double> barrierUs;  ///< state published -> release published
    std::vector<double> skewUs;     ///< latest minus earliest swap of one frame over all nodes
    int deadlineReleases = 0;
    int joined = 0;  ///< followers ready at the first frame (all of them, or the figures are void)
};

BarrierRun runLeader(const std::string& followerBin, int followers, int frames) {
    BarrierRun run;
    auto leader = wall::LeaderTransport::bind({"tcp://127.0.0.1:*", "tcp://127.0.0.1:*", 100.0});
    if (!leader) {
        std::fprintf(stderr, "%s", leader.diagnostics.format().c_str());
        return run;
    }
    const auto [stateEp, readyEp] = (*leader)->endpoints();
    const std::string dir = "/tmp/kiosk-bench-wall-" + std::to_string(::getpid());
    std::vector<pid_t> pids;
    std::vector<std::uint32_t> screens;
    for (int i = 0; i < followers; ++i) {
        screens.push_back(std::uint32_t(i + 1));
        const std::string out = dir + "-" + std::to_string(i + 1);
        const pid_t pid = fork();
        if (pid == 0) {
            prctl(PR_SET_PDEATHSIG, SIGKILL);
            execl(followerBin.c_str(), followerBin.c_str(), stateEp.c_str(), readyEp.c_str(),
                  std::to_string(i + 1).c_str(), out.c_str(), static_cast<char*>(nullptr));
            _exit(127);
        }
        pids.push_back(pid);
    }
    wall::SwapBarrier barrier(screens, 0.1);
    std::vector<double> leaderSwap(std::size_t(frames) + 1, 0.0);
    for (int frame = 1; frame <= frames; ++frame) {
        wall::FrameState s;
        s.frame = std::uint64_t(frame);
        s.scenarioId = "bench";
        const double t0 = nowUs();
        (*leader)->publish(wall::encode(s));
        // Frame 1 waits for every follower process to start and join (not timed).
        barrier.begin(s.frame, t0 / 1e6, frame == 1 ? 120.0 : 0.1);
        barrier.leaderReady(true);
        double lastSend = t0;
        while (!barrier.releasable(nowUs() / 1e6)) {
            if (frame == 1 && nowUs() - lastSend > 50000) {
                (*leader)->publish(wall::encode(s));
                lastSend = nowUs();
            }
            if (auto m = (*leader)->receive(Us(1000)))
                if (auto r = wall::decodeReady(*m)) barrier.onReady(*r);
        }
        const wall::Release r = barrier.release();
        if (frame == 1) run.joined = int(r.readyNodes) - 1;
        (*leader)->publish(wall::encode(r));
        leaderSwap[std::size_t(frame)] = nowUs();
        if (frame > 1) {
            run.barrierUs.push_back(leaderSwap[std::size_t(frame)] - t0);
            run.deadlineReleases += r.byDeadline ? 1 : 0;
        }
    }
    (*leader)->publish(wall::encodeStop());
    std::vector<double> earliest(leaderSwap), latest(leaderSwap);
    for (int i = 0; i < followers; ++i) {
        int status = 0;
        waitpid(pids[std::size_t(i)], &status, 0);
        const std::string path = dir + "-" + std::to_string(i + 1);
        std::ifstream in(path);
        std::uint64_t frame = 0;
        double us = 0;
        while (in >> frame >> us)
            if (frame < earliest.size()) {
                earliest[frame] = std::min(earliest[frame], us);
                latest[frame] = std::max(latest[frame], us);
            }
        std::remove(path.c_str());
    }
    for (int frame = 2; frame <= frames; ++frame)
        run.skewUs.push_back(latest[std::size_t(frame)] - earliest[std::size_t(frame)]);
    return run;
}

nlohmann::json summary(std::vector<double> v) {
    return {{"p50", app::percentile(v, 50)},
            {"p95", app::percentile(v, 95)},
            {"p99", app::percentile(v, 99)}};
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench-wall SCENARIO [--frames N] [--size WxH]\n");
        return 2;
    }
    int frames = 300, width = 1280, height = 720;
    for (int i = 2; i + 1 < argc; i += 2) {
        if (std::strcmp(argv[i], "--frames") == 0) frames = std::max(10, std::atoi(argv[i + 1]));
        if (std::strcmp(argv[i], "--size") == 0)
            if (auto wh = parseSize(argv[i + 1])) width = wh->first, height = wh->second;
    }
    nlohmann::json out{{"benchmark", "wall"}, {"frames", frames}, {"transport", "tcp://127.0.0.1"}};

    // Baseline: one node's frame on the demo (tiles resident, time moving).
    {
        auto scene = bench::openBenchScene(argv[1], width, height);
        if (!scene) return scene.exitCode;
        app::Session& s = scene.s();
        const auto vp = s.viewpointAt(s.startTime(), "");
        const math::Camera cam = app::makeCamera(vp ? *vp : s.terrain().overviewViewpoint(),
                                                 s.terrain().bounds(), width, height, 45.0);
        for (int k = 0; k < 20000 && !s.terrain().settled(); ++k)
            s.drawFrame(cam, s.startTime(), width, height);
        glFinish();
        std::vector<double> ms;
        RealClock clock;
        const int baseFrames = std::min(frames, 60);
        for (int i = 0; i < baseFrames; ++i) {
            const double t0 = clock.now();
            s.drawFrame(cam, s.startTime() + 60.0 * i, width, height);
            glFinish();
            ms.push_back((clock.now() - t0) * 1000.0);
        }
        out["baseline"] = {{"what", "one node, drawFrame + glFinish, demo at " +
                                        std::to_string(width) + "x" + std::to_string(height)},
                           {"frame_ms", summary(ms)}};
    }
    // The follower processes: bench-wall-follower next to this binary (sync only, no GL).
    const std::string self = argv[0];
    const std::string followerBin =
        self.substr(0, self.find_last_of('/') + 1) + "bench-wall-follower";
    nlohmann::json runs = nlohmann::json::array();
    for (int followers : {4, 16}) {
        const BarrierRun r = runLeader(followerBin, followers, frames);
        runs.push_back({{"followers", followers},
                        {"joined", r.joined},
                        {"barrier_us", summary(r.barrierUs)},
                        {"swap_skew_us", summary(r.skewUs)},
                        {"deadline_releases", r.deadlineReleases}});
    }
    out["barrier"] = runs;
    std::printf("%s\n", out.dump().c_str());
    return 0;
}
