#pragma once

#include <string>
#include <vector>

namespace kiosk::app {

/**
 * @brief `geokiosk info STORE [--json]`: layers, CRS, extent, levels, tile counts, sequences
 * (first/last time, frame count) and size on disk, on stdout. Errors to stderr; returns 0, 1 for
 * an unreadable store, 2 for a usage error.
 */
int runInfoCommand(const std::vector<std::string>& args);

}  // namespace kiosk::app
