// The frame-rate governor against an artificial per-frame cost: a model of a frame whose time
// falls with tau (fewer triangles) and with the square of the render scale (fewer pixels).
#include "runtime/anim/FrameGovernor.h"

#include <gtest/gtest.h>

#include <functional>

namespace kiosk::anim {
namespace {

constexpr double kTauGeom = 2.0, kTauTex = 1.0;

/** ms of a frame rendered with `s`: `full` at the scenario's settings. */
double modelCost(double full, const GovernorState& s) {
    const double tauFactor = s.tauGeom / kTauGeom;
    return full * (0.4 + 0.6 / tauFactor) * s.renderScale * s.renderScale;
}

struct Flight {
    int changes = 0;
    int lastChange = -1;
};

Flight fly(FrameGovernor& g, int frames, const std::function<double(const GovernorState&)>& cost) {
    Flight r;
    for (int i = 0; i < frames; ++i) {
        const int before = g.state().level;
        const GovernorState& s = g.frameDone(cost(g.state()));
        EXPECT_GE(s.renderScale, 0.5);
        EXPECT_LE(s.tauGeom, 4 * kTauGeom);
        if (s.level != before) {
            ++r.changes;
            r.lastChange = i;
        }
    }
    return r;
}

GovernorSettings at30() {
    GovernorSettings s;
    s.targetFps = 30.0;
    return s;
}

TEST(FrameGovernor, OffWithoutATarget) {
    FrameGovernor g(GovernorSettings{}, kTauGeom, kTauTex);
    EXPECT_FALSE(g.state().active);
    const Flight r = fly(g, 200, [](const GovernorState&) { return 500.0; });
    EXPECT_EQ(r.changes, 0);
    EXPECT_EQ(g.state().tauGeom, kTauGeom);
    EXPECT_EQ(g.state().renderScale, 1.0);
}

TEST(FrameGovernor, ConvergesToTheTargetAndHolds) {
    FrameGovernor g(at30(), kTauGeom, kTauTex);
    // 80 ms at the scenario's settings: tau alone reaches 80 * 0.55 = 44 ms, so the render
    // scale has to come down too.
    auto cost = [](const GovernorState& s) { return modelCost(80.0, s); };
    const Flight r = fly(g, 120, cost);
    EXPECT_LE(cost(g.state()), g.budgetMs()) << "level " << g.state().level;
    EXPECT_LT(g.state().renderScale, 1.0);
    EXPECT_EQ(g.state().tauGeom, 4 * kTauGeom);
    EXPECT_EQ(g.state().tauTex, 4 * kTauTex);
    // N: each rung costs overFrames + settleFrames frames at most.
    EXPECT_LE(r.lastChange, 8 * (3 + 4) + 2);
    // And it stays there: no change in the next 1000 frames at the same cost.
    EXPECT_EQ(fly(g, 1000, cost).changes, 0);
}

TEST(FrameGovernor, RecoversWhenTheCostGoesAway) {
    FrameGovernor g(at30(), kTauGeom, kTauTex);
    fly(g, 200, [](const GovernorState& s) { return modelCost(80.0, s); });
    ASSERT_GT(g.state().level, 0);
    const Flight r = fly(g, 600, [](const GovernorState& s) { return modelCost(10.0, s); });
    EXPECT_EQ(g.state().level, 0);
    EXPECT_EQ(g.state().tauGeom, kTauGeom);
    EXPECT_EQ(g.state().tauTex, kTauTex);
    EXPECT_EQ(g.state().renderScale, 1.0);
    EXPECT_LE(r.lastChange, 8 * (30 + 4) + 2);
}

TEST(FrameGovernor, CostBetweenTwoRungsDoesNotOscillate) {
    FrameGovernor g(at30(), kTauGeom, kTauTex);
    // Rung 1 (tau x1.5): 40 * 0.8 = 32 ms, just inside the budget but without headroom; rung 2:
    // 28 ms, still above 0.7 of it. Rung 0 is 40 ms, over. The governor settles on rung 1.
    auto cost = [](const GovernorState& s) { return modelCost(40.0, s); };
    fly(g, 100, cost);
    EXPECT_EQ(g.state().level, 1);
    EXPECT_EQ(fly(g, 2000, cost).changes, 0);
    // A cost with headroom on rung 1 (below 0.7 of the budget) but over budget on rung 0
    // (25 ms there, 35 below): the step down is tried, undone, and then tried ever more rarely.
    FrameGovernor h(at30(), kTauGeom, kTauTex);
    auto between = [](const GovernorState& s) { return s.level == 0 ? 35.0 : 22.0; };
    const Flight r = fly(h, 3000, between);
    EXPECT_LE(r.changes, 16) << "a try every ~30 frames would be 170 changes";
    EXPECT_GE(r.changes, 2);
}

TEST(FrameGovernor, StaysWithinItsLimits) {
    GovernorSettings s = at30();
    s.maxTauFactor = 2.0;
    s.minRenderScale = 0.7;
    FrameGovernor g(s, kTauGeom, kTauTex);
    fly(g, 300, [](const GovernorState&) { return 1000.0; });  // unreachable target
    EXPECT_EQ(g.state().tauGeom, 2 * kTauGeom);
    EXPECT_EQ(g.state().tauTex, 2 * kTauTex);
    EXPECT_EQ(g.state().renderScale, 0.7);
    // maxTau caps the factor: a scenario tau of 40 may only rise to 64.
    FrameGovernor c(at30(), 40.0, 40.0);
    for (int i = 0; i < 300; ++i) c.frameDone(1000.0);
    EXPECT_EQ(c.state().tauGeom, 64.0);
    EXPECT_EQ(c.state().renderScale, 0.5);
}

}  // namespace
}  // namespace kiosk::anim
