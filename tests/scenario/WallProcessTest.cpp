// Display walls end to end (issue 17): several geokiosk processes on one machine, headless,
// synced over ipc:// (docs/wall.md). Tiny screens (64x36) keep each test to seconds; every
// process is started and stopped here with bounded waits (and dies with the test: PDEATHSIG).
#include "tests/support/EglTestContext.h"
#include "tests/support/GoldenImage.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace kiosk {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
const char* const kScreens[] = {"tl", "tr", "bl", "br"};

/** One geokiosk process: output to a log file, SIGKILL if the test dies. */
class Proc {
public:
    Proc() = default;
    Proc(const Proc&) = delete;
    ~Proc() { kill(SIGKILL); }
    void start(const std::vector<std::string>& args, const fs::path& log) {
        std::vector<char*> argv;
        for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        const pid_t parent = getpid();
        mPid = fork();
        if (mPid == 0) {
            prctl(PR_SET_PDEATHSIG, SIGKILL);
            if (getppid() != parent) _exit(127);
            const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            if (fd >= 0) dup2(fd, 1), dup2(fd, 2);
            execv(argv[0], argv.data());
            _exit(127);
        }
    }
    /** Exit status, or -1 if it did not end within `timeout` (then it is killed). */
    int wait(std::chrono::milliseconds timeout) {
        const auto until = Clock::now() + timeout;
        while (mPid > 0) {
            int status = 0;
            if (waitpid(mPid, &status, WNOHANG) == mPid) {
                mPid = -1;
                return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            }
            if (Clock::now() > until) break;
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        kill(SIGKILL);
        return -1;
    }
    /** Send `sig`; the exit status, or -1 if it did not end within 10 s (then it is killed). */
    int signalAndWait(int sig) {
        if (mPid > 0) ::kill(mPid, sig);
        return wait(std::chrono::seconds(10));
    }
    /** Send `sig` and reap (SIGKILL after 5 s if it does not end). */
    void kill(int sig) {
        if (mPid <= 0) return;
        ::kill(mPid, sig);
        if (sig != SIGKILL) wait(std::chrono::seconds(5));  // kills and reaps on timeout
        if (mPid <= 0) return;
        ::kill(mPid, SIGKILL);
        waitpid(mPid, nullptr, 0);
        mPid = -1;
    }

private:
    pid_t mPid = -1;
};

std::vector<nlohmann::json> readLog(const fs::path& file) {
    std::vector<nlohmann::json> out;
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) {
        auto j = nlohmann::json::parse(line, nullptr, false);
        if (j.is_object()) out.push_back(std::move(j));  // a line being written is skipped
    }
    return out;
}

std::string slurp(const fs::path& f) {
    std::ifstream in(f);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

class WallProcessTest : public ::testing::Test {
protected:
    void SetUp() override {
        if (!fs::exists("data/generated/rainier.gpkg"))
            KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_DATA",
                               "demo store missing: run tools/prepare-demo.sh");
        mDir = fs::temp_directory_path() / ("kiosk-wall-" + std::to_string(::getpid()));
        fs::create_directories(mDir);
        // The demo without overlays (they are placed per screen; the picture is compared here).
        std::ofstream(mDir / "scenario.json")
            << nlohmann::json{{"version", 1},
                              {"include", {fs::absolute("scenarios/demo/rainier.json").string()}},
                              {"title", ""},
                              {"caption", ""},
                              {"overlays",
                               {{"legend", {{"enabled", false}}},
                                {"timeLabel", {{"enabled", false}}},
                                {"progress", {{"enabled", false}}}}}};
    }
    void TearDown() override {
        std::error_code ec;
        if (!mDir.empty() && !HasFailure()) fs::remove_all(mDir, ec);
    }
    /** 2x2 screens of 64x36 px at 1 px/mm, 4 mm mullions, ipc:// sync in the test's folder. */
    fs::path writeWall(double deadlineMs) {
        const fs::path f = mDir / "wall.json";
        std::ofstream(f) << nlohmann::json{
            {"grid", {{"rows", 2}, {"columns", 2}}},
            {"screenDefaults", {{"pixels", {64, 36}}, {"activeMm", {64, 36}}}},
            {"mullionMm", {4, 4}},
            {"screens",
             {{{"id", "tl"}, {"row", 0}, {"column", 0}},
              {{"id", "tr"}, {"row", 0}, {"column", 1}},
              {{"id", "bl"}, {"row", 1}, {"column", 0}},
              {{"id", "br"}, {"row", 1}, {"column", 1}}}},
            {"nodes",
             {{{"id", "n1"}, {"screens", {"tl"}}},
              {{"id", "n2"}, {"screens", {"tr"}}},
              {{"id", "n3"}, {"screens", {"bl", "br"}}}}},
            {"leader", "n1"},
            {"sync",
             {{"state", "ipc://" + (mDir / "state").string()},
              {"ready", "ipc://" + (mDir / "ready").string()},
              {"deadlineMs", deadlineMs}}}};
        return f;
    }
    std::vector<std::string> play(const fs::path& wall, const std::string& screen,
                                  const std::vector<std::string>& extra) {
        std::vector<std::string> a = {KIOSK_GEOKIOSK_BIN,
                                      "play",
                                      (mDir / "scenario.json").string(),
                                      "--display",
                                      "headless",
                                      "--wall",
                                      wall.string(),
                                      "--screen",
                                      screen,
                                      "--wall-log",
                                      (mDir / (screen + ".jsonl")).string()};
        a.insert(a.end(), extra.begin(), extra.end());
        return a;
    }
    fs::path mDir;
};

// The four screens' images, placed on the canvas with the bezel gaps removed, equal one render
// of the whole virtual frustum at the combined size (132x76) within 1 DN.
TEST_F(WallProcessTest, FourScreensEqualTheWholeFrustum) {
    const fs::path wall = writeWall(500);
    Proc procs[5];
    for (int i = 0; i < 4; ++i)
        procs[i].start({KIOSK_GEOKIOSK_BIN, "render", (mDir / "scenario.json").string(), "--wall",
                        wall.string(), "--screen", kScreens[i], "--time", "+3h", "--out",
                        (mDir / (std::string(kScreens[i]) + ".png")).string()},
                       mDir / (std::string(kScreens[i]) + ".log"));
    procs[4].start({KIOSK_GEOKIOSK_BIN, "render", (mDir / "scenario.json").string(), "--size",
                    "132x76", "--time", "+3h", "--out", (mDir / "whole.png").string()},
                   mDir / "whole.log");
    for (int i = 0; i < 5; ++i) ASSERT_EQ(procs[i].wait(std::chrono::seconds(60)), 0) << i;
    const gl::Image whole = test::readImage((mDir / "whole.png").string());
    ASSERT_EQ(whole.width, 132);
    ASSERT_EQ(whole.height, 76);
    const int offsets[4][2] = {{0, 0}, {68, 0}, {0, 40}, {68, 40}};
    long varied = 0;
    for (int i = 0; i < 4; ++i) {
        const gl::Image s = test::readImage((mDir / (std::string(kScreens[i]) + ".png")).string());
        ASSERT_EQ(s.width, 64);
        ASSERT_EQ(s.height, 36);
        int worst = 0;
        for (int y = 0; y < 36; ++y)
            for (int x = 0; x < 64; ++x)
                for (int c = 0; c < 3; ++c) {
                    const int a = s.pixel(x, y)[c];
                    const int b = whole.pixel(x + offsets[i][0], y + offsets[i][1])[c];
                    worst = std::max(worst, std::abs(a - b));
                    varied += a != s.pixel(0, 0)[c];
                }
        EXPECT_LE(worst, 1) << kScreens[i];
    }
    EXPECT_GT(varied, 1000);  // real terrain, not four blank images
}

// 200 frames of the demo on four synced processes: per swap every node reports the same frame
// number, data time and sequence step, and the sequence did step.
TEST_F(WallProcessTest, TwoHundredFramesInStep) {
    const fs::path wall = writeWall(3000);
    Proc procs[4];
    for (int i = 1; i < 4; ++i)
        procs[i].start(play(wall, kScreens[i], {}), mDir / (std::string(kScreens[i]) + ".log"));
    // At most 40 fps: the 200 frames take >= 5 s, i.e. >= 6000 s of data at the demo's rate 1200,
    // so the flood (a frame every 45 min) steps at least twice however fast this machine is.
    procs[0].start(play(wall, "tl", {"--frames", "200", "--max-fps", "40"}), mDir / "tl.log");
    for (int i = 0; i < 4; ++i)
        ASSERT_EQ(procs[i].wait(std::chrono::seconds(90)), 0)
            << kScreens[i] << ": " << slurp(mDir / (std::string(kScreens[i]) + ".log"));
    std::map<long, std::map<std::string, nlohmann::json>> byFrame;
    for (const char* s : kScreens) {
        const auto log = readLog(mDir / (std::string(s) + ".jsonl"));
        EXPECT_EQ(log.size(), 200u) << s;
        for (const auto& r : log) byFrame[r["frame"].get<long>()][s] = r;
    }
    ASSERT_EQ(byFrame.size(), 200u);
    std::set<std::vector<int>> steps;
    for (const auto& [frame, nodes] : byFrame) {
        ASSERT_EQ(nodes.size(), 4u) << "frame " << frame;
        const auto& ref = nodes.at("tl");
        steps.insert(ref["step"].get<std::vector<int>>());
        for (const auto& [screen, r] : nodes) {
            EXPECT_EQ(r["data_time"], ref["data_time"]) << screen << " frame " << frame;
            EXPECT_EQ(r["step"], ref["step"]) << screen << " frame " << frame;
            EXPECT_EQ(r["holding"], false) << screen << " frame " << frame;
        }
    }
    EXPECT_GE(steps.size(), 2u) << "the flood never stepped";
}

// The leader's first frame waits for the followers to join (here >= 5 s); that wait is start-up,
// not playback: the data time of the next frame moves on by one frame's time, not by the wait.
TEST_F(WallProcessTest, JoinWaitDoesNotAdvanceTheClock) {
    // A short deadline after the join: frame 2 cannot wait for slow followers as long as the
    // join did, so the two cases stay apart on a loaded machine.
    const fs::path wall = writeWall(500);
    Proc procs[4];
    procs[0].start(play(wall, "tl", {"--frames", "10", "--max-fps", "20"}), mDir / "tl.log");
    std::this_thread::sleep_for(std::chrono::seconds(5));
    for (int i = 1; i < 4; ++i)
        procs[i].start(play(wall, kScreens[i], {}), mDir / (std::string(kScreens[i]) + ".log"));
    for (int i = 0; i < 4; ++i)
        ASSERT_EQ(procs[i].wait(std::chrono::seconds(60)), 0)
            << kScreens[i] << ": " << slurp(mDir / (std::string(kScreens[i]) + ".log"));
    const auto leader = readLog(mDir / "tl.jsonl");
    ASSERT_EQ(leader.size(), 10u);
    const double joinWaitS = leader[0]["wait_us"].get<double>() / 1e6;
    ASSERT_GT(joinWaitS, 4.5) << "the followers joined before they were started?";
    // The demo's first briefing chapter plays 4 h of data in 8 s: 1800 data seconds per second.
    constexpr double kRate = 1800.0;
    const double dataStep =
        leader[1]["data_time"].get<double>() - leader[0]["data_time"].get<double>();
    const double swapGapS =
        (leader[1]["swap_us"].get<double>() - leader[0]["swap_us"].get<double>()) / 1e6;
    // Frame 2's dt runs from the end of frame 1's barrier to frame 2's start, within the swap gap
    // (+0.2 s for frame 1's own swap); counted from frame 1's start it would include the wait.
    EXPECT_LE(dataStep, kRate * (swapGapS + 0.2)) << "join wait " << joinWaitS << " s";
}

// A follower killed mid-run does not stall the wall longer than the deadline; restarted, it is
// back on the same frame as its peers within 5 of its frames.
TEST_F(WallProcessTest, KilledFollowerIsDroppedAndRejoins) {
    constexpr double kDeadlineMs = 300;
    const fs::path wall = writeWall(kDeadlineMs);
    Proc procs[4];
    for (int i = 1; i < 4; ++i)
        procs[i].start(play(wall, kScreens[i], {}), mDir / (std::string(kScreens[i]) + ".log"));
    procs[0].start(play(wall, "tl", {"--max-fps", "60"}), mDir / "tl.log");
    auto leaderFrames = [&] { return readLog(mDir / "tl.jsonl").size(); };
    auto waitFor = [&](auto pred, int seconds) {
        const auto until = Clock::now() + std::chrono::seconds(seconds);
        while (!pred() && Clock::now() < until)
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        return pred();
    };
    ASSERT_TRUE(waitFor([&] { return leaderFrames() >= 30; }, 60)) << slurp(mDir / "tl.log");
    procs[3].kill(SIGKILL);
    const std::size_t killedAt = leaderFrames();
    // The 50 frames after the kill are the window the deadline-release count below reads.
    constexpr std::size_t kAfterKill = 50;
    ASSERT_TRUE(waitFor([&] { return leaderFrames() >= killedAt + kAfterKill; }, 60))
        << "the wall stalled";
    fs::rename(mDir / "br.jsonl", mDir / "br-before.jsonl");
    procs[3].start(play(wall, "br", {}), mDir / "br-again.log");
    ASSERT_TRUE(waitFor([&] { return readLog(mDir / "br.jsonl").size() >= 15; }, 60))
        << slurp(mDir / "br-again.log");
    // A clean stop of the leader (SIGTERM) stops the followers too.
    procs[0].kill(SIGTERM);
    for (int i = 1; i < 4; ++i)
        EXPECT_EQ(procs[i].wait(std::chrono::seconds(10)), 0) << kScreens[i];

    const auto leader = readLog(mDir / "tl.jsonl");
    ASSERT_GE(leader.size(), killedAt + kAfterKill);
    // No stall: after it was ready, the leader never waited for the others longer than the
    // deadline (plus polling and scheduling slack on a loaded 2-core machine).
    double worstWaitMs = 0;
    for (std::size_t i = killedAt; i < leader.size(); ++i)
        worstWaitMs = std::max(worstWaitMs, leader[i]["wait_us"].get<double>() / 1000.0);
    EXPECT_LT(worstWaitMs, kDeadlineMs + 100.0);
    // The kill was noticed once (a deadline release), not on every frame after.
    int deadlineReleases = 0;
    for (std::size_t i = killedAt; i < killedAt + kAfterKill; ++i)
        deadlineReleases += leader[i]["by_deadline"].get<bool>();
    EXPECT_LE(deadlineReleases, 3);
    // Rejoined: from its 5th swap on (the first frames of a fresh process compile shaders and
    // load tiles) every swap is of the frame the leader swapped at the same moment.
    std::map<long, double> leaderSwap;
    for (const auto& r : leader) leaderSwap[r["frame"].get<long>()] = r["swap_us"].get<double>();
    const auto again = readLog(mDir / "br.jsonl");
    ASSERT_GE(again.size(), 15u);
    auto inStep = [&](const nlohmann::json& r) {
        const auto it = leaderSwap.find(r["frame"].get<long>());
        return it != leaderSwap.end() &&
               std::abs(it->second - r["swap_us"].get<double>()) < kDeadlineMs * 1000.0;
    };
    for (std::size_t i = 4; i < again.size(); ++i)
        EXPECT_TRUE(inStep(again[i])) << "swap " << i + 1;
}

// Overlays on a wall (read back from the rendered screens): each is drawn once, on the screen the
// wall file names, inside its box, and never across a bezel. A 2x1 wall of 320x180 screens with a
// 10 mm mullion; the same screens rendered without overlays are the reference, so every pixel
// that differs belongs to an overlay panel.
// A follower whose leader never comes keeps waiting; SIGTERM during that wait (a signal
// interrupts ZeroMQ's poll) is a clean stop, not an internal error.
TEST_F(WallProcessTest, LeaderlessFollowerStopsCleanlyOnSigterm) {
    const fs::path wall = writeWall(100);
    Proc follower;
    follower.start(play(wall, "tr", {}), mDir / "tr.log");
    const auto until = Clock::now() + std::chrono::seconds(30);
    while (slurp(mDir / "tr.log").find("(follower)") == std::string::npos && Clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_NE(slurp(mDir / "tr.log").find("(follower)"), std::string::npos)
        << slurp(mDir / "tr.log");
    std::this_thread::sleep_for(std::chrono::seconds(1));  // inside its wait for the leader
    EXPECT_EQ(follower.signalAndWait(SIGTERM), 0) << slurp(mDir / "tr.log");
    EXPECT_EQ(slurp(mDir / "tr.log").find("internal error"), std::string::npos)
        << slurp(mDir / "tr.log");
}

TEST_F(WallProcessTest, OverlaysStayOnTheirScreens) {
    // Positions the canvas anchors must override (legend keeps its own: it is placed by screen).
    std::ofstream(mDir / "overlays.json") << nlohmann::json{
        {"version", 1},
        {"include", {fs::absolute("scenarios/demo/rainier.json").string()}},
        {"title", "Wall"},
        {"caption", ""},
        {"overlays",
         {{"legend", {{"transfer", "depth"}, {"position", "top-left"}}},
          {"timeLabel", {{"format", "%H:%M"}, {"timeZone", "UTC"}, {"position", "bottom-left"}}},
          {"title", {{"position", "bottom-left"}}},
          {"progress", {{"enabled", false}}}}}};
    const fs::path wall = mDir / "wall2.json";
    std::ofstream(wall) << nlohmann::json{
        {"grid", {{"rows", 1}, {"columns", 2}}},
        {"screenDefaults", {{"pixels", {320, 180}}, {"activeMm", {320, 180}}}},
        {"mullionMm", {10, 10}},
        {"screens",
         {{{"id", "l"}, {"row", 0}, {"column", 0}}, {{"id", "r"}, {"row", 0}, {"column", 1}}}},
        {"nodes", {{{"id", "n1"}, {"screens", {"l", "r"}}}}},
        {"leader", "n1"},
        {"sync",
         {{"state", "ipc://" + (mDir / "state").string()},
          {"ready", "ipc://" + (mDir / "ready").string()}}},
        // Canvas 650x180 mm. Title: x = 328.25 mm lies on the mullion (320..330), nearer to "r":
        // its top-left corner goes to r's left edge, 18 px down. Time label: top-right corner at
        // the middle of "l" (160, 90).
        {"overlays",
         {{"legend", {{"screen", "l"}}},
          {"title", {{"canvas", {0.505, 0.1}}}},
          {"timeLabel", {{"canvas", {0.25, 0.5}}}}}}};
    Proc procs[4];
    const std::string screens[] = {"l", "r"};
    for (int i = 0; i < 4; ++i) {
        const std::string scenario = i < 2 ? "overlays.json" : "scenario.json";
        const std::string name = screens[i % 2] + (i < 2 ? "-on" : "-off");
        procs[i].start({KIOSK_GEOKIOSK_BIN, "render", (mDir / scenario).string(), "--wall",
                        wall.string(), "--screen", screens[i % 2], "--time", "+3h", "--out",
                        (mDir / (name + ".png")).string()},
                       mDir / (name + ".log"));
    }
    for (int i = 0; i < 4; ++i) ASSERT_EQ(procs[i].wait(std::chrono::seconds(60)), 0) << i;
    // The pixels an overlay changed, as a bounding box per region of interest.
    struct Box {
        int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
        long n = 0;
        void add(int x, int y) {
            x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
            ++n;
        }
    };
    auto changed = [&](const std::string& screen, auto&& where) {
        const gl::Image on = test::readImage((mDir / (screen + "-on.png")).string());
        const gl::Image off = test::readImage((mDir / (screen + "-off.png")).string());
        EXPECT_EQ(on.width, 320);
        EXPECT_EQ(on.height, 180);
        Box b;
        for (int y = 0; y < std::min(on.height, off.height); ++y)
            for (int x = 0; x < std::min(on.width, off.width); ++x) {
                int d = 0;
                for (int c = 0; c < 3; ++c)
                    d = std::max(d, std::abs(int(on.pixel(x, y)[c]) - int(off.pixel(x, y)[c])));
                if (d > 8 && where(x, y)) b.add(x, y);
            }
        return b;
    };
    // Screen "l": the legend at the scenario's top-left (a screen placement keeps positions)...
    const Box legend = changed("l", [](int, int y) { return y < 89; });
    EXPECT_GT(legend.n, 200);
    EXPECT_LE(legend.x0, 16);
    EXPECT_LE(legend.y0, 16);
    // ...the time label in its box below and left of its anchor (160, 90), at the box's top-right
    // corner although the scenario says bottom-left.
    const Box label = changed("l", [](int, int y) { return y >= 89; });
    EXPECT_GT(label.n, 100);
    EXPECT_LT(label.x1, 160);
    EXPECT_GT(label.x1, 140);
    EXPECT_GE(label.y0, 89);
    EXPECT_LT(label.y1, 140);
    // Screen "r": only the title, all of it inside r, top-left corner just right of the mullion
    // and 18 px down (the scenario said bottom-left); "l" has nothing near the mullion.
    const Box title = changed("r", [](int, int) { return true; });
    EXPECT_GT(title.n, 100);
    EXPECT_GE(title.x0, 1);
    EXPECT_LE(title.x0, 16);
    EXPECT_GE(title.y0, 18);
    EXPECT_LE(title.y0, 34);
    EXPECT_LT(title.y1, 90);
    const Box nearMullion = changed("l", [](int x, int) { return x >= 200; });
    EXPECT_EQ(nearMullion.n, 0);
}

// Bad wall files and screen ids: one clear line, documented exit codes.
TEST_F(WallProcessTest, BadWallFilesGiveClearErrors) {
    const fs::path good = writeWall(100);
    auto run = [&](const fs::path& wall, const std::string& screen, std::string& out) {
        Proc p;
        p.start({KIOSK_GEOKIOSK_BIN, "render", (mDir / "scenario.json").string(), "--wall",
                 wall.string(), "--screen", screen, "--out", (mDir / "x.png").string()},
                mDir / "bad.log");
        const int rc = p.wait(std::chrono::seconds(30));
        out = slurp(mDir / "bad.log");
        return rc;
    };
    std::string out;
    EXPECT_EQ(run(good, "bx", out), 2);
    EXPECT_NE(out.find(R"(--screen "bx": no such screen in the wall file (did you mean)"),
              std::string::npos)
        << out;
    auto variant = [&](const std::string& from, const std::string& to) {
        std::string text = slurp(good);
        const auto at = text.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        text.replace(at, from.size(), to);
        const fs::path f = mDir / "bad.json";
        std::ofstream(f) << text;
        return f;
    };
    EXPECT_EQ(run(variant(R"("mullionMm":[4,4])", R"("mullionMm":[0,4])"), "tl", out), 1);
    EXPECT_NE(out.find("bad.json:1:"), std::string::npos) << out;
    EXPECT_NE(out.find("/mullionMm/0: mullion (bezel gap) between columns must be > 0"),
              std::string::npos)
        << out;
    EXPECT_EQ(run(variant(R"("column":1,"id":"tr")", R"("column":0,"id":"tr")"), "tl", out), 1);
    EXPECT_NE(out.find(R"(/screens/1: screens "tl" and "tr" overlap)"), std::string::npos) << out;
    EXPECT_EQ(run(variant(R"("screens":["tr"])", R"("screens":["trr"])"), "tl", out), 1);
    EXPECT_NE(out.find(R"(/nodes/1/screens/0: unknown screen id "trr" (did you mean "tr"?))"),
              std::string::npos)
        << out;
}

}  // namespace
}  // namespace kiosk
