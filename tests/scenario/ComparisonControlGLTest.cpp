// POST /control/lens moves the comparison lens (issue 19): the kiosk service is started on
// loopback, the request goes through its HTTP thread and queue, the frame loop's handler
// (app::applyLensMove, as `play` calls it) puts the lens there, and the next frame shows run B
// where run A was. Bad parameters are refused with 400 and one line; the service stops cleanly.
#include "runtime/app/LensControl.h"
#include "runtime/service/KioskService.h"
#include "tests/scenario/ComparisonFixture.h"

#include <cstdlib>
#include <httplib.h>

namespace kiosk::test {
namespace {

using namespace compare;

int maxDiff(const std::uint8_t* a, const std::uint8_t* b) {
    int d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(a[c]) - int(b[c])));
    return d;
}

class ComparisonControl : public ComparisonTest {};

TEST_F(ComparisonControl, ControlEndpointMovesTheLens) {
    std::ofstream(sDir / "token") << "s3cret\n";
    service::ServiceOptions opt;
    opt.listen = service::ListenAddress{"127.0.0.1", 0};
    opt.tokenFile = sDir / "token";
    std::string why;
    auto svc = service::KioskService::start(opt, why);
    ASSERT_TRUE(svc) << why;
    ASSERT_GT(svc->httpPort(), 0);

    auto s =
        open("control.json",
             scenario(kRuns, R"({ "id": "cmp", "kind": "comparison", "center": [500500, 4999500],
                                       "radius": 300, "inside": ["B"], "outside": ["A"] })"));
    ASSERT_TRUE(s);
    const math::Camera cam = camera(*s);
    const glm::ivec2 before = project(cam, 500500, 4999500, kW, kH);
    const glm::ivec2 after = project(cam, 501400, 4998500, kW, kH);
    const gl::Image first = settled(*s, 2);
    const std::uint8_t* runB = first.pixel(before.x, before.y);  // inside the lens
    const std::uint8_t* runA = first.pixel(after.x, after.y);    // outside it
    ASSERT_GT(maxDiff(runA, runB), 40);

    httplib::Client http("127.0.0.1", svc->httpPort());
    const httplib::Headers auth = {{"Authorization", "Bearer s3cret"}};
    auto bad = http.Post("/control/lens?x=east", auth, "", "text/plain");
    ASSERT_TRUE(bad);
    EXPECT_EQ(bad->status, 400);
    EXPECT_NE(bad->body.find("lens wants x"), std::string::npos) << bad->body;
    auto none = http.Post("/control/lens", auth, "", "text/plain");
    ASSERT_TRUE(none);
    EXPECT_EQ(none->status, 400) << none->body;
    auto ok =
        http.Post("/control/lens?id=cmp&x=501400&y=4998500&radius=250", auth, "", "text/plain");
    ASSERT_TRUE(ok);
    EXPECT_EQ(ok->status, 200) << ok->body;

    // The frame loop takes the queued command between frames (PlayCommand.cpp does the same).
    int moves = 0;
    for (const auto& c : svc->takeControl()) {
        ASSERT_EQ(c.action, service::ControlAction::Lens);
        std::string reason;
        EXPECT_TRUE(app::applyLensMove(s->terrain(), c.lens, reason)) << reason;
        ++moves;
    }
    EXPECT_EQ(moves, 1);
    const gl::Image moved = settled(*s, 2);
    EXPECT_LE(maxDiff(moved.pixel(after.x, after.y), runB), 1)
        << "run B now shows at the new centre";
    EXPECT_LE(maxDiff(moved.pixel(before.x, before.y), runA), 1) << "run A where the lens was";
    const auto p = s->terrain().lensPlacement(0);
    ASSERT_TRUE(p);
    EXPECT_DOUBLE_EQ(p->radii.x, 250.0);

    // Turned off from the endpoint: run A everywhere.
    ASSERT_TRUE(http.Post("/control/lens?enabled=0", auth, "", "text/plain"));
    for (const auto& c : svc->takeControl()) {
        std::string reason;
        EXPECT_TRUE(app::applyLensMove(s->terrain(), c.lens, reason)) << reason;
    }
    const gl::Image off = settled(*s, 2);
    EXPECT_LE(maxDiff(off.pixel(after.x, after.y), runA), 1);
    const int port = svc->httpPort();
    svc.reset();  // stops the HTTP thread and closes the port
    httplib::Client gone("127.0.0.1", port);
    gone.set_connection_timeout(1, 0);
    EXPECT_FALSE(gone.Get("/health")) << "the service must stop listening";
}

TEST_F(ComparisonControl, PlayKeysMoveResizeTurnAndToggleTheLens) {
    auto s =
        open("keys.json", scenario(kRuns, R"({ "id": "cmp", "kind": "comparison", "shape": "swipe",
                                       "center": [500960, 4999040], "rotation": 0,
                                       "inside": ["B"], "outside": ["A"] })"));
    ASSERT_TRUE(s);
    const math::Camera cam = camera(*s);
    // 1/20 of the larger side (1920 m) per key: two presses of d move the line 192 m east.
    const glm::ivec2 probe = project(cam, kCentreX + 100, kCentreY, kW, kH);
    const gl::Image first = settled(*s, 1);
    const std::uint8_t* runB = first.pixel(probe.x, probe.y);  // east of the line: inside
    platform::InputState keys;
    keys.lensX = 2;
    app::applyLensKeys(s->terrain(), keys);
    const gl::Image moved = settled(*s, 1);
    const std::uint8_t* runA = moved.pixel(probe.x, probe.y);  // now west of it
    EXPECT_GT(maxDiff(runA, runB), 40) << "the line must have moved east past the probe";
    auto p = s->terrain().lensPlacement(0);
    ASSERT_TRUE(p);
    EXPECT_NEAR(p->centre.x, kCentreX + 192.0, 1e-6);
    keys = {};
    keys.lensTurn = 12;  // 180 degrees: the inside is now west of the line
    keys.lensSize = 1;
    app::applyLensKeys(s->terrain(), keys);
    p = s->terrain().lensPlacement(0);
    EXPECT_NEAR(p->rotationDeg, 180.0, 1e-9);
    const gl::Image turned = settled(*s, 1);
    EXPECT_LE(maxDiff(turned.pixel(probe.x, probe.y), runB), 1) << "west of the line is inside";
    keys = {};
    keys.lensToggle = true;
    app::applyLensKeys(s->terrain(), keys);
    const gl::Image off = settled(*s, 1);
    EXPECT_LE(maxDiff(off.pixel(probe.x, probe.y), runA), 1) << "lens off: run A everywhere";
}

}  // namespace
}  // namespace kiosk::test
