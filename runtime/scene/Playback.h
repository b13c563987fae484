#pragma once

#include "runtime/anim/ScenarioClock.h"

#include <cstdint>

namespace kiosk::scene {

/**
 * @brief How the scenario clock is playing, as TerrainScene::update needs it to plan the
 * sequences' prefetch ahead of the playhead (docs/animation.md "Prefetch").
 *
 * `rate` is data seconds per wall second (negative plays backwards); 0 (or `paused`) plans the
 * current pair plus neighbours on both sides, for stepping. `seekSerial` is the clock's
 * ScenarioClock::seekSerial(): when it changes (scrubbing, key steps), queued prefetch of the
 * old playhead is dropped. Plain data; any thread.
 */
struct Playback {
    double rate = 0.0;
    anim::RangeMode range = anim::RangeMode::Clamp;
    double start = 0.0;  ///< range start (loop start), epoch seconds
    double end = 0.0;    ///< range end (loop end), epoch seconds
    std::uint64_t seekSerial = 0;
    bool paused = false;
};

/** @brief The playback state of a running clock. */
inline Playback playbackOf(const anim::ScenarioClock& clock) noexcept {
    Playback p;
    p.rate = clock.rate();
    p.range = clock.rangeMode();
    p.start = clock.start();
    p.end = clock.end();
    p.seekSerial = clock.seekSerial();
    p.paused = clock.paused();
    return p;
}

}  // namespace kiosk::scene
