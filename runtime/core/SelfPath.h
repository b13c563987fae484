#pragma once

#include <filesystem>

namespace kiosk::core {

/** The folder holding the running executable (from /proc/self/exe), or an empty path when the
 * link cannot be read. The importer, the FFmpeg module and the installed package's data are
 * found beside it, so a relocated install works without configuration. */
std::filesystem::path executableDir();

}  // namespace kiosk::core
