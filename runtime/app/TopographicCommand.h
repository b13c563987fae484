#pragma once

#include <string>
#include <vector>

namespace kiosk::app {

/**
 * @brief `geokiosk import topographic --store STORE [--elevation LAYER] [--name NAME]
 * [--azimuth DEG] [--altitude DEG] [--z-factor F] [--variant default|multidirectional|combined]
 * [--shadows] [--quiet]`: a hillshade layer computed from the store's elevation.
 * `args` are the words after "topographic". Returns the exit status.
 */
int runImportTopographic(const std::vector<std::string>& args);

}  // namespace kiosk::app
