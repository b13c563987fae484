#pragma once

#include <string>
#include <vector>

namespace kiosk::app {

/**
 * @brief `geokiosk import breaklines LINES --store STORE [--elevation LAYER] [--name NAME]
 * [--threads N] [--quiet]` and `geokiosk import model-mesh MODEL.sww --store STORE ...`: local
 * TINs in the store's elevation grid (docs/terrain.md "Local TINs"). `kind` is "breaklines" or
 * "model-mesh", `args` the words after it. Returns the exit status (docs/cli.md).
 */
int runImportLocalTins(const std::string& kind, const std::vector<std::string>& args);

}  // namespace kiosk::app
