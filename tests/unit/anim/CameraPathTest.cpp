#include "runtime/anim/CameraPath.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace kiosk::anim {
namespace {

math::Viewpoint vp(double x, double y, double z, double heading, double pitch, double range) {
    math::Viewpoint v;
    v.target = glm::dvec3(x, y, z);
    v.headingDeg = heading;
    v.pitchDeg = pitch;
    v.range = range;
    return v;
}

// Uneven key spacing on purpose (10 s, 40 s, 5 s, 25 s).
std::vector<CameraKey> tourKeys() {
    return {
        {1000.0, vp(0, 0, 100, 20, -30, 5000)},       {1010.0, vp(800, 200, 120, 60, -45, 2000)},
        {1050.0, vp(1500, -400, 90, 350, -60, 800)},  {1055.0, vp(1600, -300, 95, 10, -50, 900)},
        {1080.0, vp(3000, 1000, 150, 90, -35, 6000)},
    };
}

CameraPath makePath(std::vector<CameraKey> keys) {
    auto r = CameraPath::create(std::move(keys), "tour.json", "/cameraPaths/0");
    EXPECT_TRUE(r.ok()) << r.diagnostics.format();
    return r.ok() ? *r : CameraPath{};
}

// Channels compared for smoothness; heading unwrapped against a reference so 359 -> 1 is +2.
std::vector<double> channels(const math::Viewpoint& v, double headingRef) {
    return {v.target.x, v.target.y,
            v.target.z, headingRef + shortestHeadingDelta(headingRef, v.headingDeg),
            v.pitchDeg, v.range};
}

TEST(CameraPath, PassesThroughEveryKey) {
    const auto keys = tourKeys();
    const auto path = makePath(keys);
    for (const auto& k : keys) {
        const auto s = path.sample(k.time);
        EXPECT_NEAR(s.target.x, k.view.target.x, 1e-9);
        EXPECT_NEAR(s.target.y, k.view.target.y, 1e-9);
        EXPECT_NEAR(s.target.z, k.view.target.z, 1e-9);
        EXPECT_NEAR(shortestHeadingDelta(s.headingDeg, k.view.headingDeg), 0.0, 1e-9);
        EXPECT_NEAR(s.pitchDeg, k.view.pitchDeg, 1e-9);
        EXPECT_NEAR(s.range, k.view.range, 1e-6);
    }
    // Holds outside the keyed interval.
    EXPECT_EQ(path.sample(0.0).range, 5000.0);
    EXPECT_EQ(path.sample(1e10).range, 6000.0);
    EXPECT_EQ(path.startTime(), 1000.0);
    EXPECT_EQ(path.endTime(), 1080.0);
}

TEST(CameraPath, IsC1AcrossKeysAndEasesAtTheEnds) {
    const auto keys = tourKeys();
    const auto path = makePath(keys);
    const double h = 1e-4;
    for (std::size_t k = 0; k < keys.size(); ++k) {
        const double t = keys[k].time;
        const double ref = keys[k].view.headingDeg;
        const auto c0 = channels(path.sample(t), ref);
        const auto cl = channels(path.sample(t - h), ref);
        const auto cr = channels(path.sample(t + h), ref);
        // Scale: the steepest secant of the segments touching this key, per channel. A kink
        // (C0 only) differs by a sizeable fraction of it; one-sided differences err by O(h).
        std::vector<double> scale(c0.size(), 1e-9);
        for (std::size_t s2 : {k == 0 ? k : k - 1, k + 1 < keys.size() ? k : k - 1}) {
            const auto a = channels(keys[s2].view, ref), b = channels(keys[s2 + 1].view, ref);
            for (std::size_t c = 0; c < c0.size(); ++c)
                scale[c] = std::max(scale[c],
                                    std::fabs(b[c] - a[c]) / (keys[s2 + 1].time - keys[s2].time));
        }
        for (std::size_t c = 0; c < c0.size(); ++c) {
            const double left = (c0[c] - cl[c]) / h, right = (cr[c] - c0[c]) / h;
            const double tol = 1e-3 * scale[c];
            if (k == 0) {
                EXPECT_NEAR(right, 0.0, tol) << "eases out of the first key, ch " << c;
            } else if (k + 1 == keys.size()) {
                EXPECT_NEAR(left, 0.0, tol) << "eases into the last key, ch " << c;
            } else {
                EXPECT_NEAR(left, right, tol) << "key " << k << " channel " << c;
            }
        }
    }
    // No stop-and-go: where x keeps increasing through key 1 (0 -> 800 -> 1500) the camera
    // passes the key moving (zero tangents everywhere would be C1 too, but would jerk).
    const double vx =
        (path.sample(1010.0 + h).target.x - path.sample(1010.0 - h).target.x) / (2 * h);
    EXPECT_GT(vx, 20.0);
    // And no jumps anywhere: dense sampling, bounded first differences.
    double maxStep = 0.0;
    auto prev = channels(path.sample(1000.0), 20.0);
    for (double t = 1000.01; t <= 1080.0; t += 0.01) {
        const auto cur = channels(path.sample(t), prev[3]);
        maxStep = std::max(maxStep, std::fabs(cur[0] - prev[0]));
        prev = cur;
    }
    EXPECT_LT(maxStep, 5.0);  // < 500 m/s of target motion on a path moving ~100 m/s
}

TEST(CameraPath, DoesNotOvershootBetweenKeys) {
    const auto keys = tourKeys();
    const auto path = makePath(keys);
    for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
        const auto& a = keys[k].view;
        const auto& b = keys[k + 1].view;
        for (int i = 1; i < 50; ++i) {
            const double t = keys[k].time + (keys[k + 1].time - keys[k].time) * i / 50.0;
            const auto s = path.sample(t);
            EXPECT_GE(s.range, std::min(a.range, b.range) - 1e-9) << t;
            EXPECT_LE(s.range, std::max(a.range, b.range) + 1e-9) << t;
            EXPECT_GE(s.target.x, std::min(a.target.x, b.target.x) - 1e-9) << t;
            EXPECT_LE(s.target.x, std::max(a.target.x, b.target.x) + 1e-9) << t;
            EXPECT_GE(s.pitchDeg, std::min(a.pitchDeg, b.pitchDeg) - 1e-9) << t;
            EXPECT_LE(s.pitchDeg, std::max(a.pitchDeg, b.pitchDeg) + 1e-9) << t;
        }
    }
}

TEST(CameraPath, HeadingTakesTheShortWayAcrossNorth) {
    const auto path = makePath({{0.0, vp(0, 0, 0, 350, -45, 1000)},
                                {10.0, vp(0, 0, 0, 10, -45, 1000)},
                                {20.0, vp(0, 0, 0, 340, -45, 1000)}});
    for (double t = 0.0; t <= 20.0; t += 0.05) {
        const double hd = path.sample(t).headingDeg;
        EXPECT_GE(hd, 0.0);
        EXPECT_LT(hd, 360.0);
        EXPECT_TRUE(hd >= 339.999 || hd <= 10.001) << "t=" << t << " heading " << hd;
    }
    EXPECT_NEAR(path.sample(5.0).headingDeg, 0.0, 1e-9);  // symmetric segment: through north
}

TEST(CameraPath, SampleAheadAndAlong) {
    const auto path = makePath(tourKeys());
    const auto a = path.sampleAhead(1020.0, 7.5);
    const auto b = path.sample(1027.5);
    EXPECT_EQ(a.target, b.target);
    EXPECT_EQ(a.range, b.range);
    std::vector<math::Viewpoint> along;
    path.sampleAlong(1020.0, 10.0, 4, along);
    ASSERT_EQ(along.size(), 4u);
    EXPECT_EQ(along[0].target, path.sample(1022.5).target);
    EXPECT_EQ(along[3].target, path.sample(1030.0).target);
    path.sampleAlong(1020.0, 10.0, 0, along);
    EXPECT_TRUE(along.empty());
    EXPECT_EQ(path.sample(std::nan("")).range, math::Viewpoint{}.range);
}

TEST(CameraPath, LinearAndStepModes) {
    std::vector<CameraKey> keys = {{0.0, vp(0, 0, 0, 350, -40, 100)},
                                   {10.0, vp(100, 0, 0, 30, -60, 10000)},
                                   {20.0, vp(100, 200, 0, 30, -60, 10000)}};
    auto lin = CameraPath::create(keys, "", "", PathInterpolation::Linear);
    ASSERT_TRUE(lin.ok());
    EXPECT_EQ(lin->interpolation(), PathInterpolation::Linear);
    const auto q = lin->sample(2.5);
    EXPECT_NEAR(q.target.x, 25.0, 1e-9);
    EXPECT_NEAR(q.headingDeg, 0.0, 1e-9);  // 350 -> 30 is +40: a quarter of the way is north
    EXPECT_NEAR(q.pitchDeg, -45.0, 1e-9);
    EXPECT_NEAR(lin->sample(5.0).range, 1000.0, 1e-6);  // geometric
    EXPECT_NEAR(lin->sample(15.0).target.y, 100.0, 1e-9);
    auto step = CameraPath::create(keys, "", "", PathInterpolation::Step);
    ASSERT_TRUE(step.ok());
    EXPECT_EQ(step->sample(9.99).target.x, 0.0);
    EXPECT_EQ(step->sample(10.0).target.x, 100.0);
    EXPECT_EQ(step->sample(19.0).target.y, 0.0);
    EXPECT_EQ(parsePathInterpolation("smooth"), PathInterpolation::Smooth);
    EXPECT_EQ(parsePathInterpolation("linear"), PathInterpolation::Linear);
    EXPECT_EQ(parsePathInterpolation("step"), PathInterpolation::Step);
    EXPECT_FALSE(parsePathInterpolation("spline").has_value());
}

TEST(CameraPath, SingleKeyIsStill) {
    const auto path = makePath({{5.0, vp(1, 2, 3, 45, -20, 300)}});
    EXPECT_EQ(path.sample(-100).range, 300.0);
    EXPECT_EQ(path.sample(100).headingDeg, 45.0);
}

struct BadPath {
    const char* name;
    std::vector<CameraKey> keys;
    const char* code;
    const char* where;
    const char* message;
};

class CameraPathBadKeys : public ::testing::TestWithParam<BadPath> {};

TEST_P(CameraPathBadKeys, ReportsCodeWhereAndMessage) {
    const auto& p = GetParam();
    auto r = CameraPath::create(p.keys, "tour.json", "/cameraPaths/1");
    ASSERT_FALSE(r.ok());
    const Diagnostic* e = r.diagnostics.firstError();
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->code, p.code);
    EXPECT_EQ(e->file, "tour.json");
    EXPECT_EQ(e->where, p.where);
    EXPECT_NE(e->message.find(p.message), std::string::npos) << e->message;
}

INSTANTIATE_TEST_SUITE_P(
    Table, CameraPathBadKeys,
    ::testing::Values(
        BadPath{"empty", {}, "ANIM_PATH_EMPTY", "/cameraPaths/1/keys", "has no keys"},
        BadPath{
            "unsorted",
            {{1773446400.0, vp(0, 0, 0, 0, -45, 100)}, {1773446400.0, vp(0, 0, 0, 0, -45, 100)}},
            "ANIM_PATH_KEYS_UNSORTED",
            "/cameraPaths/1/keys/1/time",
            "camera key time 2026-03-14T00:00:00Z is not after the previous key's"},
        BadPath{"zero range",
                {{0.0, vp(0, 0, 0, 0, -45, 100)}, {1.0, vp(0, 0, 0, 0, -45, 0)}},
                "ANIM_PATH_RANGE_INVALID",
                "/cameraPaths/1/keys/1/range",
                "camera range must be > 0 m, got 0"},
        BadPath{"pitch",
                {{0.0, vp(0, 0, 0, 0, -120, 100)}},
                "ANIM_PATH_PITCH_INVALID",
                "/cameraPaths/1/keys/0/pitch",
                "within [-90, 90] degrees, got -120"},
        BadPath{"nan target",
                {{0.0, vp(std::numeric_limits<double>::quiet_NaN(), 0, 0, 0, -45, 100)}},
                "ANIM_PATH_NOT_FINITE",
                "/cameraPaths/1/keys/0/view",
                "non-finite target"},
        BadPath{"inf time",
                {{std::numeric_limits<double>::infinity(), vp(0, 0, 0, 0, -45, 100)}},
                "ANIM_PATH_NOT_FINITE",
                "/cameraPaths/1/keys/0/time",
                "not a finite time"}),
    [](const auto& testInfo) {
        std::string n = testInfo.param.name;
        for (char& c : n)
            if (c == ' ') c = '_';
        return n;
    });

TEST(FlyTo, EasesFromStartToDestination) {
    const auto from = vp(0, 0, 0, 350, -30, 1000);
    const auto to = vp(100, 50, 10, 20, -60, 4000);
    const FlyTo fly(from, to, 10.0, 4.0);
    EXPECT_EQ(fly.sample(5.0).target, from.target);
    EXPECT_EQ(fly.sample(10.0).range, from.range);
    EXPECT_EQ(fly.sample(14.0).target, to.target);
    EXPECT_EQ(fly.sample(99.0).headingDeg, to.headingDeg);
    EXPECT_FALSE(fly.finished(13.9));
    EXPECT_TRUE(fly.finished(14.0));
    // Zero velocity at both ends (smootherstep), moving in the middle.
    const double h = 1e-3;
    EXPECT_NEAR(fly.sample(10.0 + h).target.x - fly.sample(10.0).target.x, 0.0, 1e-6);
    EXPECT_NEAR(fly.sample(14.0).target.x - fly.sample(14.0 - h).target.x, 0.0, 1e-6);
    EXPECT_GT(fly.sample(12.0 + h).target.x - fly.sample(12.0).target.x, 0.01);
    // Heading goes through north (350 -> 0 -> 20), range geometric mean at the midpoint.
    const auto mid = fly.sample(12.0);
    EXPECT_NEAR(mid.headingDeg, 5.0, 1e-9);
    EXPECT_NEAR(mid.range, 2000.0, 1e-6);  // sqrt(1000 * 4000); targets are close: no arc
    EXPECT_NEAR(mid.pitchDeg, -45.0, 1e-9);
}

TEST(FlyTo, ArcsUpBetweenDistantTargets) {
    const auto from = vp(0, 0, 0, 0, -45, 1000);
    const auto to = vp(40000, 0, 0, 0, -45, 1000);
    const FlyTo fly(from, to, 0.0, 6.0);
    EXPECT_NEAR(fly.sample(3.0).range, 30000.0, 1e-6);  // 0.75 x distance at mid-flight
    EXPECT_GT(fly.sample(1.5).range, 1000.0);
    EXPECT_NEAR(fly.sample(6.0).range, 1000.0, 1e-9);
}

TEST(FlyTo, ZeroDurationJumps) {
    const auto to = vp(5, 5, 5, 90, -10, 10);
    EXPECT_EQ(FlyTo(vp(0, 0, 0, 0, -45, 100), to, 0.0, 0.0).sample(0.0).target, to.target);
    EXPECT_EQ(FlyTo(vp(0, 0, 0, 0, -45, 100), to, 0.0, std::nan("")).sample(-1).range, 10.0);
    EXPECT_TRUE(FlyTo().finished(0.0));
}

}  // namespace
}  // namespace kiosk::anim
