#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

// Which files a scenario may make geokiosk read (includes, stores, colour files, images): a
// scenario is data from whoever wrote it, and must not reach /etc/passwd, /proc/self/environ or
// another user's files. The rule (docs/scenario-format.md, "Paths"): a path, after `..` and
// symbolic links are resolved, must lie under the folder of the scenario file that was opened,
// the current working directory (unless that is `/`), or a folder of the allow-list, which
// whoever runs geokiosk sets (GEOKIOSK_ALLOW_PATHS, `--allow-path`). The scenario cannot widen it.
namespace kiosk::config {

/** @brief Add a folder to the process-wide allow-list (the `--allow-path` option). Any thread. */
void allowPath(const std::filesystem::path& folder);

/** @brief Forget folders added with allowPath() (tests). */
void clearAllowedPaths();

/**
 * @brief The folders paths in the scenario `rootScenario` may reach: its folder, the working
 * directory unless it is `/`, every entry of GEOKIOSK_ALLOW_PATHS (`:`-separated) and every
 * folder given to allowPath(); each made absolute and canonical. Any thread.
 */
std::vector<std::filesystem::path> allowedRoots(const std::filesystem::path& rootScenario);

/**
 * @brief nullopt if `file` (absolute or relative to the working directory) lies under one of
 * `roots` once `..` and symbolic links are resolved; otherwise the reason, e.g. "is outside the
 * scenario's folder and the allow-list (GEOKIOSK_ALLOW_PATHS, --allow-path)".
 */
std::optional<std::string> checkContained(const std::filesystem::path& file,
                                          const std::vector<std::filesystem::path>& roots);

}  // namespace kiosk::config
