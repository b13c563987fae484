#pragma once

namespace kiosk::app {

/** @brief Install SIGINT/SIGTERM handlers that only set a flag; the frame loop polls it. */
void installStopSignals();
/** @brief True once SIGINT or SIGTERM arrived. Async-signal-safe to set, cheap to read. */
bool stopRequested() noexcept;
/** @brief For tests. */
void resetStopRequest() noexcept;

}  // namespace kiosk::app
