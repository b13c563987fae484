#pragma once
// Render's deterministic wait for the tests: prepare one view until the loader has brought every
// tile it selects, so the pixels read back do not depend on how fast this machine loads.
#include "runtime/app/Session.h"

#include <chrono>
#include <thread>

namespace kiosk::test {

/** @brief Prepare `cam` at data time `time` until the terrain is settled (always at least once),
 * sleeping 1 ms between tries, at most `maxTries` times. Returns whether it settled. */
inline bool settleView(app::Session& s, const math::Camera& cam, double time,
                       int maxTries = 60000) {
    for (int k = 0; k < maxTries && (k == 0 || !s.terrain().settled()); ++k) {
        s.prepare(cam, time);
        if (!s.terrain().settled()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return s.terrain().settled();
}

}  // namespace kiosk::test
