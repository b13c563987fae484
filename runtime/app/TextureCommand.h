#pragma once

#include <string>
#include <vector>

namespace kiosk::app {

/**
 * @brief `geokiosk import textures --store STORE [--layers A,B] [--quality fast|medium|thorough]
 * [--threads N] [--quiet]`: ASTC 4x4 GPU blocks of the store's imagery layers beside their PNG
 * tiles (docs/terrain.md §11). `args` are the words after `textures`. Returns the exit status.
 */
int runImportTextures(const std::vector<std::string>& args);

}  // namespace kiosk::app
