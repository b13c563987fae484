#pragma once

#include <string>
#include <vector>

namespace kiosk::app {

/**
 * @brief `geokiosk render SCENARIO --out OUT [--time T | --from T0 --to T1 --fps N]
 * [--size WxH] [--viewpoint NAME] [--stats STATS.json]`: offscreen, deterministic (each frame is
 * drawn only once every tile it needs is resident). Returns the exit status.
 */
int runRenderCommand(const std::vector<std::string>& args);

}  // namespace kiosk::app
