#pragma once

#include <string>
#include <vector>

namespace kiosk::app {

/**
 * @brief `geokiosk play SCENARIO [--display ...] [--size WxH] [--windowed] [--max-fps N]
 * [--frames N]`: the kiosk loop. Runs until SIGINT/SIGTERM, a quit key, or N frames. Watches
 * the scenario and its includes: a valid edit is applied within a second, a broken one is
 * reported and the last good scenario stays on screen.
 */
int runPlayCommand(const std::vector<std::string>& args);

}  // namespace kiosk::app
