#include "runtime/service/Metrics.h"
#include "runtime/service/ServiceState.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace kiosk::service {
namespace {

TEST(MetricsTest, LabelValuesAreEscaped) {
    EXPECT_EQ(escapeLabelValue("a\"b\\c\nd"), "a\\\"b\\\\c\\nd");
    EXPECT_EQ(escapeLabelValue("plain"), "plain");
}

TEST(MetricsTest, ValuesUseTheFormatsSpellings) {
    EXPECT_EQ(formatValue(1.0 / 0.0), "+Inf");
    EXPECT_EQ(formatValue(-1.0 / 0.0), "-Inf");
    EXPECT_EQ(formatValue(0.0 / 0.0), "NaN");
    EXPECT_EQ(formatValue(16.7), "16.7");
    EXPECT_EQ(formatValue(3), "3");
}

TEST(MetricsTest, FamilyHasHelpTypeAndLabelledSamples) {
    MetricsWriter w;
    w.family("x_bytes", "Bytes.\nSecond line", MetricsWriter::Type::Gauge);
    w.sample("", {{"kind", "cpu"}, {"layer", "q\"x"}}, 42);
    EXPECT_EQ(w.text(),
              "# HELP x_bytes Bytes.\\nSecond line\n# TYPE x_bytes gauge\n"
              "x_bytes{kind=\"cpu\",layer=\"q\\\"x\"} 42\n");
}

TEST(MetricsTest, HistogramBucketsAreCumulativeWithInfSumAndCount) {
    const std::array<double, 3> bounds = {1, 10, 100};
    Histogram<3> h;
    for (double v : {0.5, 1.0, 5.0, 50.0, 500.0, 7.0}) h.observe(bounds, v);
    EXPECT_EQ(h.count, 6u);
    EXPECT_DOUBLE_EQ(h.sum, 563.5);
    MetricsWriter w;
    w.histogram("t_ms", "T.", bounds, h);
    EXPECT_EQ(w.text(),
              "# HELP t_ms T.\n# TYPE t_ms histogram\n"
              "t_ms_bucket{le=\"1\"} 2\n"
              "t_ms_bucket{le=\"10\"} 4\n"
              "t_ms_bucket{le=\"100\"} 5\n"
              "t_ms_bucket{le=\"+Inf\"} 6\n"
              "t_ms_sum 563.5\n"
              "t_ms_count 6\n");
}

TEST(MetricsTest, SnapshotRendersEveryFamilyOnce) {
    ServiceSnapshot s;
    s.frames = 7;
    s.layers = {{"flood", "degraded", "2 tiles unreadable"}};
    s.cache.gpuMeshes = 1234;
    s.playlistIndex = 2;
    const std::string text = renderMetrics(s, {4096, 8192, 12.5});
    for (const char* family :
         {"geokiosk_frame_time_ms", "geokiosk_frames_total", "geokiosk_held_frames_total",
          "geokiosk_sequence_missing_frames_total", "geokiosk_cache_bytes",
          "geokiosk_loader_queue_depth", "geokiosk_layer_state", "geokiosk_reloads_total",
          "geokiosk_reload_failures_total", "geokiosk_playlist_position",
          "geokiosk_resident_memory_bytes", "geokiosk_heap_in_use_bytes",
          "geokiosk_uptime_seconds"}) {
        const std::string type = std::string("# TYPE ") + family + " ";
        const auto first = text.find(type);
        EXPECT_NE(first, std::string::npos) << family;
        EXPECT_EQ(text.find(type, first + 1), std::string::npos) << family << " twice";
    }
    EXPECT_NE(text.find("geokiosk_frames_total 7\n"), std::string::npos);
    EXPECT_NE(text.find("geokiosk_cache_bytes{kind=\"gpu_meshes\"} 1234\n"), std::string::npos);
    EXPECT_NE(text.find("geokiosk_layer_state{layer=\"flood\",state=\"degraded\"} 1\n"),
              std::string::npos);
    EXPECT_NE(text.find("geokiosk_layer_state{layer=\"flood\",state=\"ready\"} 0\n"),
              std::string::npos);
    EXPECT_NE(text.find("geokiosk_playlist_position 2\n"), std::string::npos);
    EXPECT_NE(text.find("geokiosk_resident_memory_bytes 4096\n"), std::string::npos);
    EXPECT_NE(text.find("geokiosk_heap_in_use_bytes 8192\n"), std::string::npos);
}

TEST(MetricsTest, RssIsReadFromProc) {
    EXPECT_GT(readRssBytes(), 1u << 20);
}

TEST(MetricsTest, HeapInUseFollowsMallocAndFree) {
    const std::uint64_t before = readHeapInUseBytes();
    std::vector<char> block(std::size_t(8) << 20, 1);  // 8 MiB: counted while held
    EXPECT_GE(readHeapInUseBytes(), before + (std::uint64_t(8) << 20));
    block = std::vector<char>();
    EXPECT_LT(readHeapInUseBytes(), before + (std::uint64_t(1) << 20));
}

}  // namespace
}  // namespace kiosk::service
