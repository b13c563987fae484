#include "runtime/service/ServiceState.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace kiosk::service {
namespace {

TEST(HealthTest, NoFrameYetIs503) {
    ServiceSnapshot s;
    const HealthVerdict v = evaluateHealth(s, 10.0, 5.0);
    EXPECT_EQ(v.status, 503);
    EXPECT_EQ(nlohmann::json::parse(v.body)["reason"], "no frame yet");
}

TEST(HealthTest, RecentFrameIs200WithState) {
    ServiceSnapshot s;
    s.lastFrameAt = 9.0;
    s.frames = 3;
    s.scenario = "a.json";
    s.layers = {{"base", "ready", ""}, {"flood", "failed", "store gone"}};
    s.warnings = {"entry 2 skipped"};
    const HealthVerdict v = evaluateHealth(s, 10.0, 5.0);
    EXPECT_EQ(v.status, 200);
    const auto body = nlohmann::json::parse(v.body);
    EXPECT_EQ(body["status"], "ok");
    EXPECT_EQ(body["frames"], 3);
    ASSERT_EQ(body["degraded_layers"].size(), 1u);
    EXPECT_EQ(body["degraded_layers"][0]["layer"], "flood");
    EXPECT_EQ(body["warnings"][0], "entry 2 skipped");
}

TEST(HealthTest, StalledFramesAre503WithTheReason) {
    ServiceSnapshot s;
    s.lastFrameAt = 1.0;
    const HealthVerdict v = evaluateHealth(s, 7.5, 5.0);
    EXPECT_EQ(v.status, 503);
    const auto body = nlohmann::json::parse(v.body);
    EXPECT_EQ(body["status"], "stalled");
    EXPECT_EQ(body["reason"], "no frame for 6.5 s (limit 5.0 s)");
}

TEST(HealthTest, AHoldingLoopNamesItsCauseWhenStalled) {
    ServiceSnapshot s;
    s.lastFrameAt = 1.0;
    s.holding = "no frame state from the wall leader";
    EXPECT_EQ(evaluateHealth(s, 3.0, 5.0).status, 200);  // within the limit: nothing to report
    const HealthVerdict v = evaluateHealth(s, 7.5, 5.0);
    EXPECT_EQ(v.status, 503);
    EXPECT_EQ(nlohmann::json::parse(v.body)["reason"],
              "no frame state from the wall leader: no frame for 6.5 s (limit 5.0 s), last frame "
              "kept");
}

TEST(HealthTest, SnapshotBoxHandsOverACopy) {
    SnapshotBox box;
    ServiceSnapshot s;
    s.frames = 5;
    box.publish(s);
    s.frames = 6;
    EXPECT_EQ(box.read().frames, 5u);
}

}  // namespace
}  // namespace kiosk::service
