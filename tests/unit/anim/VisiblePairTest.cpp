#include "runtime/anim/VisiblePair.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace kiosk::anim {
namespace {

const std::vector<double> kTimes = {0.0, 10.0, 25.0, 30.0, 60.0, 65.0, 90.0, 120.0};

TEST(VisiblePair, NothingIsShownUntilAFirstPairIsComplete) {
    VisiblePair vp;
    const auto wanted = bracketFrames(kTimes, 5.0, Interpolation::Data);
    auto d = vp.update(wanted, kTimes, 5.0, [](std::size_t) { return false; });
    EXPECT_FALSE(d.hasPair);
    EXPECT_TRUE(d.holding);
    EXPECT_EQ(d.heldFrames, 1u);
    d = vp.update(wanted, kTimes, 5.0, [](std::size_t f) { return f == 0; });
    EXPECT_FALSE(d.hasPair) << "frame 1 is not complete yet";
    d = vp.update(wanted, kTimes, 5.0, [](std::size_t f) { return f <= 1; });
    EXPECT_TRUE(d.hasPair);
    EXPECT_FALSE(d.holding);
    EXPECT_EQ(d.heldFrames, 0u);
    EXPECT_EQ(d.i0, 0u);
    EXPECT_EQ(d.i1, 1u);
    EXPECT_DOUBLE_EQ(d.alpha, 0.5);
    EXPECT_EQ(vp.totalHeldFrames(), 2u);
    EXPECT_EQ(vp.switches(), 1u);
}

TEST(VisiblePair, HoldsThePreviousPairAndTracksTimeWithinIt) {
    VisiblePair vp;
    auto all = [](std::size_t) { return true; };
    vp.update(bracketFrames(kTimes, 15.0, Interpolation::Data), kTimes, 15.0, all);
    // Time moves into (25, 30): frame 3 is not loaded. (1, 2) stays, at its end (frame 2).
    auto notThree = [](std::size_t f) { return f != 3; };
    auto d = vp.update(bracketFrames(kTimes, 27.0, Interpolation::Data), kTimes, 27.0, notThree);
    EXPECT_TRUE(d.holding);
    EXPECT_EQ(d.i0, 1u);
    EXPECT_EQ(d.i1, 2u);
    EXPECT_DOUBLE_EQ(d.alpha, 1.0);
    d = vp.update(bracketFrames(kTimes, 28.0, Interpolation::Data), kTimes, 28.0, notThree);
    EXPECT_EQ(d.heldFrames, 2u);
    // A seek back inside the held interval shows the held pair at the right blend.
    d = vp.update(bracketFrames(kTimes, 27.0, Interpolation::Data), kTimes, 13.0, notThree);
    EXPECT_DOUBLE_EQ(d.alpha, 0.2);
    d = vp.update(bracketFrames(kTimes, 28.0, Interpolation::Data), kTimes, 28.0, all);
    EXPECT_FALSE(d.holding);
    EXPECT_EQ(d.i0, 2u);
    EXPECT_EQ(d.i1, 3u);
    EXPECT_DOUBLE_EQ(d.alpha, 0.6);
    EXPECT_EQ(vp.displayed().i0, 2u);
    vp.reset();
    EXPECT_FALSE(vp.displayed().hasPair);
    EXPECT_EQ(vp.switches(), 0u);
}

TEST(VisiblePair, StepModeNeedsOnlyOneFrame) {
    VisiblePair vp;
    const auto wanted = bracketFrames(kTimes, 27.0, Interpolation::None);
    int asked3 = 0;
    auto d = vp.update(wanted, kTimes, 27.0, [&](std::size_t f) {
        asked3 += f == 3;
        return f == 2;
    });
    EXPECT_TRUE(d.hasPair);
    EXPECT_EQ(d.i0, 2u);
    EXPECT_EQ(d.i1, 2u);
    EXPECT_EQ(asked3, 0);
}

// Property: under a randomly changing residency (loads, evictions of unpinned frames, seeks,
// irregular clock steps) the screen never combines tiles of different time steps: every tile the
// view needs is resident for both displayed frames, and the displayed pair is always either the
// wanted pair (when complete) or the pair shown the frame before.
TEST(VisiblePair, NeverShowsAMixUnderRandomResidency) {
    constexpr int kTiles = 9;
    constexpr int kSteps = 20000;
    const std::size_t frames = kTimes.size();
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<std::vector<bool>> resident(frames, std::vector<bool>(kTiles, false));
    auto complete = [&](std::size_t f) {
        for (int tile = 0; tile < kTiles; ++tile)
            if (!resident[f][tile]) return false;
        return true;
    };

    VisiblePair vp;
    DisplayPair before;
    double t = 0.0;
    int switches = 0, holds = 0, seeks = 0;
    for (int step = 0; step < kSteps; ++step) {
        // Clock: mostly forward at a varying rate, sometimes a scrub anywhere.
        if (u(rng) < 0.01) {
            t = u(rng) * 130.0 - 5.0;
            ++seeks;
        } else {
            t += u(rng) * 1.5;
            if (t > 120.0) t = 0.0;  // loop
        }
        // Loader: mostly tiles of the frames around t (like the prefetcher), some strays;
        // cache: evicts random tiles of frames not on screen.
        const auto near = bracketFrames(kTimes, t, Interpolation::Data);
        for (int n = 0; n < 6; ++n) {
            std::size_t f = rng() % frames;
            if (u(rng) < 0.8) f = std::min(frames - 1, near.i0 + rng() % 3);
            resident[f][static_cast<int>(rng() % kTiles)] = true;
        }
        for (int n = 0; n < 2; ++n) {
            const std::size_t f = rng() % frames;
            const bool pinned =
                vp.displayed().hasPair && (f == vp.displayed().i0 || f == vp.displayed().i1);
            if (!pinned) resident[f][static_cast<int>(rng() % kTiles)] = false;
        }

        const auto wanted = bracketFrames(kTimes, t, Interpolation::Data);
        const bool wantedComplete = complete(wanted.i0) && complete(wanted.i1);
        const DisplayPair d = vp.update(wanted, kTimes, t, complete);

        if (wantedComplete) {
            ASSERT_TRUE(d.hasPair);
            ASSERT_EQ(d.i0, wanted.i0);
            ASSERT_EQ(d.i1, wanted.i1);
            ASSERT_FALSE(d.holding);
            ASSERT_EQ(d.alpha, wanted.alpha);
        } else {
            ASSERT_TRUE(d.holding);
            ASSERT_EQ(d.hasPair, before.hasPair);
            if (d.hasPair) {
                ASSERT_EQ(d.i0, before.i0) << "step " << step;
                ASSERT_EQ(d.i1, before.i1) << "step " << step;
            }
            ASSERT_EQ(d.heldFrames, before.heldFrames + 1);
        }
        if (d.hasPair) {
            ASSERT_TRUE(d.i1 == d.i0 || d.i1 == d.i0 + 1);
            ASSERT_GE(d.alpha, 0.0);
            ASSERT_LE(d.alpha, 1.0);
            // The renderer stamps every tile with the times it sampled: all must agree.
            for (int tile = 0; tile < kTiles; ++tile) {
                ASSERT_TRUE(resident[d.i0][tile]) << "step " << step << " tile " << tile;
                ASSERT_TRUE(resident[d.i1][tile]) << "step " << step << " tile " << tile;
            }
        }
        switches +=
            d.hasPair && !d.holding && (!before.hasPair || before.i0 != d.i0 || before.i1 != d.i1);
        holds += d.holding;
        before = d;
    }
    // The run must have exercised both branches many times, or it proves nothing.
    EXPECT_GT(switches, 300);
    EXPECT_GT(holds, 500);
    EXPECT_GT(seeks, 50);
    EXPECT_EQ(vp.totalHeldFrames(), static_cast<std::uint64_t>(holds));
}

}  // namespace
}  // namespace kiosk::anim
