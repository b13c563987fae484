// play's hot reload off the frame loop (issue 13): an include bomb saved into a running kiosk,
// then a good edit. The loop below is play's: draw a frame, take a finished reload if any (the
// same ScenarioReloader + Session::create as runtime/app/PlayCommand.cpp).
#include "runtime/app/ScenarioReloader.h"
#include "runtime/app/Session.h"
#include "tests/support/EglTestContext.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>
#include <unistd.h>

namespace kiosk::app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

class ScenarioReload : public test::EglTest {};

void writeFile(const fs::path& p, const std::string& text) {
    const fs::path tmp = p.string() + ".tmp";
    std::ofstream(tmp, std::ios::binary) << text;
    fs::rename(tmp, p);  // an editor's atomic save: the reloader never sees half a file
}

std::string scenario(const std::string& title, const std::string& include) {
    return R"({"version": 1, "title": ")" + title + R"(", "stores": {"s": "s.gpkg"},
        "terrain": {"store": "s", "elevation": "elevation"},
        "layers": [{"id": "shade", "kind": "topographic",
                    "source": {"store": "s", "layer": "hillshade"}}])" +
           (include.empty() ? "" : ", \"include\": [" + include + "]") + "}";
}

TEST_F(ScenarioReload, IncludeBombNeverStopsTheFramesAndALaterEditIsTaken) {
    if (!fs::exists("data/generated/rainier.gpkg"))
        KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_DATA", "demo store missing: run tools/prepare-demo.sh");
    const fs::path dir = fs::temp_directory_path() / ("kiosk-reload-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::copy_file("data/generated/rainier.gpkg", dir / "s.gpkg");
    const fs::path main = dir / "main.json";
    writeFile(main, scenario("first", ""));

    auto rt = gl::RenderTarget::create(96, 54);
    ASSERT_TRUE(rt.ok());
    auto opened = Session::open(main, mCaps);
    ASSERT_TRUE(opened.ok()) << opened.diagnostics.format();
    std::unique_ptr<Session> session = std::move(*opened.value);
    ScenarioReloader reloader(main, session->scenario().sourceFiles, 0.05);

    // The bomb: ten includes per level, six levels (10^6 loads without the limits), each file
    // padded with a 400 KB caption so that the loads the reader does make take real time.
    const std::string pad(400 << 10, 'x');
    for (int level = 0; level < 6; ++level) {
        std::string inc;
        for (int i = 0; i < 10 && level < 5; ++i)
            inc += std::string(i ? "," : "") + "\"b" + std::to_string(level + 1) + ".json\"";
        writeFile(dir / ("b" + std::to_string(level) + ".json"),
                  R"({"caption": ")" + pad + R"(", "include": [)" + inc + "]}");
    }

    double worstGapMs = 0;
    bool bombSaved = false, goodSaved = false, rejected = false, tookGood = false;
    const auto start = Clock::now();
    auto last = start;
    while (Clock::now() - start < std::chrono::seconds(20) && !tookGood) {
        const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
        if (!bombSaved && elapsed > 0.3) {
            writeFile(main, scenario("bomb", R"("b0.json", "b0.json", "b0.json")"));
            bombSaved = true;
        }
        if (bombSaved && rejected && !goodSaved) {
            writeFile(main, scenario("second", ""));
            goodSaved = true;
        }
        if (auto loaded = reloader.take()) {
            auto next = loaded->ok() ? Session::create(std::move(*loaded->value), mCaps)
                                     : Result<std::unique_ptr<Session>>(loaded->diagnostics);
            if (next) {
                session = std::move(*next.value);
                tookGood = session->scenario().title == "second";
            } else {
                rejected = true;
                EXPECT_TRUE(next.diagnostics.has("SCENARIO_LIMIT")) << next.diagnostics.format();
            }
        }
        // The old scenario stays on screen until a valid one is ready.
        EXPECT_NE(session->scenario().title, "bomb");
        const double t = session->startTime();
        auto vp = session->viewpointAt(t, "");
        ASSERT_TRUE(vp.ok());
        rt->bind();
        session->drawFrame(makeCamera(*vp, session->terrain().bounds(), 96, 54, 45), t, 96, 54);
        glFinish();
        const auto now = Clock::now();
        worstGapMs =
            std::max(worstGapMs, std::chrono::duration<double, std::milli>(now - last).count());
        last = now;
    }
    EXPECT_TRUE(rejected) << "the bomb should have been refused";
    EXPECT_TRUE(tookGood) << "the good edit after the bomb should have been taken";
    EXPECT_LT(worstGapMs, 200.0);
    std::printf("worst frame gap %.1f ms, %d loads\n", worstGapMs, reloader.loadsStarted());
    session.reset();
    std::error_code ec;
    fs::remove_all(dir, ec);
}

}  // namespace
}  // namespace kiosk::app
