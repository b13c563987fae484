#pragma once

namespace kiosk::app {

/**
 * @brief Ask the running `play` to go `delta` briefing chapters forward (negative: back), as
 * the `.` / `,` keys do. Thread-safe and non-blocking: for the kiosk control endpoint's thread.
 * Ignored when the scenario has no briefing.
 */
void requestChapterStep(int delta) noexcept;

/** @brief Render thread: the chapter steps requested since the last call (net). */
int takeChapterSteps() noexcept;

}  // namespace kiosk::app
