// The encoder thread, and every thread the codec starts from it, runs kEncoderNice nice steps
// below the caller's priority, so an export yields the cores to the rasterizer
// (docs/performance.md §7). Read back from /proc, the way an operator would check it.
#include "runtime/export/VideoEncoder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>

namespace kiosk::video {
namespace {

namespace fs = std::filesystem;

std::set<int> threadIds() {
    std::set<int> ids;
    for (const auto& e : fs::directory_iterator("/proc/self/task")) {
        ids.insert(std::stoi(e.path().filename().string()));
    }
    return ids;
}

std::string readLine(const fs::path& file) {
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);
    return line;
}

/** Field 19 of /proc/self/task/TID/stat (after the parenthesised name, which may hold spaces). */
int niceOf(int tid) {
    const std::string stat = readLine(fs::path("/proc/self/task") / std::to_string(tid) / "stat");
    std::istringstream rest(stat.substr(stat.rfind(')') + 2));
    std::string field;
    for (int i = 3; i <= 19; ++i) rest >> field;  // fields 3 (state) .. 19 (nice)
    return std::stoi(field);
}

TEST(EncoderPriorityTest, TheEncoderAndTheCodecThreadsRunAtTheLowerPriority) {
    const auto before = threadIds();
    const int callerNice = niceOf(int(::gettid()));
    const int expected = std::min(19, callerNice + kEncoderNice);
    const fs::path file =
        fs::temp_directory_path() / ("kiosk-encoder-nice-" + std::to_string(::getpid()) + ".mp4");
    VideoOptions options;
    options.path = file;
    options.width = 640;  // tall enough for x264 to start frame threads on a multi-core machine
    options.height = 360;
    auto opened = VideoEncoder::open(options);
    ASSERT_TRUE(opened.ok()) << opened.diagnostics.format();
    auto& encoder = **opened.value;

    int encoderThreads = 0, named = 0;
    for (const int tid : threadIds()) {
        if (before.count(tid)) continue;
        ++encoderThreads;
        EXPECT_EQ(niceOf(tid), expected) << "thread " << tid;
        const std::string comm =
            readLine(fs::path("/proc/self/task") / std::to_string(tid) / "comm");
        if (comm == kEncoderThreadName) ++named;
    }
    EXPECT_GE(encoderThreads, 1);
    EXPECT_EQ(named, encoderThreads) << "the codec's threads inherit the encoder thread's name";
    EXPECT_EQ(niceOf(int(::gettid())), callerNice) << "the caller's own priority is untouched";

    Diagnostics d;
    for (int i = 0; i < 3; ++i) {
        std::uint8_t* rgba = encoder.acquire(d);
        ASSERT_NE(rgba, nullptr) << d.format();
        std::fill(rgba, rgba + 640 * 360 * 4, std::uint8_t(40 * i));
        encoder.submit();
    }
    ASSERT_TRUE(encoder.finish(d)) << d.format();
    EXPECT_EQ(encoder.framesEncoded(), 3);
    EXPECT_GT(fs::file_size(file), 0u);
    fs::remove(file);
}

}  // namespace
}  // namespace kiosk::video
