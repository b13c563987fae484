#pragma once

#include <optional>
#include <string>
#include <vector>

namespace kiosk::app {

/**
 * @brief Take every `--allow-path DIR` (or `--allow-path=DIR`) out of a command's arguments and
 * add DIR to the folders scenario paths may reach (config/PathPolicy.h). Returns the other
 * arguments in order, or nullopt after printing a usage error (DIR missing or not a folder).
 * Shared by `play`, `render` and `validate`.
 */
std::optional<std::vector<std::string>> takeAllowPathOptions(const std::vector<std::string>& args);

}  // namespace kiosk::app
