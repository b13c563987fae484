// bench/common/PhaseTimes.h: the per-phase report the frame and replay benchmarks print.
#include <gtest/gtest.h>

#include "bench/common/PhaseTimes.h"

namespace kiosk::bench {
namespace {

TEST(PhaseTimesTest, FinishIsWhatTheMainThreadPhasesDoNotExplain) {
    app::FrameRecord r;
    r.updateMs = 2;
    r.uploadMs = 1.5;
    r.uploads = 3;
    r.drawMs = 10;
    r.overlayMs = 1;
    r.triangles = 1234;
    const PhaseSample s = phaseSample(r, 20, 35);
    EXPECT_DOUBLE_EQ(s.finishMs, 7);
    EXPECT_DOUBLE_EQ(s.cpuMs, 35);
    EXPECT_EQ(s.triangles, 1234u);
    EXPECT_EQ(s.uploads, 3u);
    EXPECT_DOUBLE_EQ(phaseSample(r, 5).finishMs, 0) << "never negative";
}

TEST(PhaseTimesTest, SpikesAreFramesAboveOneAndAHalfMediansWorstFirst) {
    std::vector<PhaseSample> v(10);
    for (std::size_t i = 0; i < v.size(); ++i) v[i].frameMs = 100;
    v[3].frameMs = 400;
    v[3].uploadMs = 300;
    v[7].frameMs = 160;
    v[5].frameMs = 149;  // below 1.5 x the median: not a spike
    const auto j = phaseReport(v);
    EXPECT_DOUBLE_EQ(j["frame_ms_max"].get<double>(), 400);
    ASSERT_EQ(j["spike_frames"].get<std::size_t>(), 2u);
    EXPECT_EQ(j["spikes"][0]["frame"].get<std::size_t>(), 3u);
    EXPECT_DOUBLE_EQ(j["spikes"][0]["upload"].get<double>(), 300);
    EXPECT_EQ(j["spikes"][1]["frame"].get<std::size_t>(), 7u);
    EXPECT_DOUBLE_EQ(j["phase_ms"]["upload"]["max"].get<double>(), 300);
    EXPECT_TRUE(phaseReport({}).is_null());
}

}  // namespace
}  // namespace kiosk::bench
