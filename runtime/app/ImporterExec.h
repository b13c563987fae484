#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace kiosk::app {

/** @brief File name of the importer executable, installed beside `geokiosk`. */
inline constexpr const char* kImporterName = "geokiosk-import";

/** @brief Where `geokiosk import` looks for the importer: beside the running executable. */
std::filesystem::path importerPath();

/**
 * @brief `geokiosk import ...`: replace this process with geokiosk-import and the words after
 * "import" (same stdin/stdout/stderr, same exit status). Returns only if the exec failed: then it
 * prints one line naming the missing importer and returns 3 (cannot run here).
 */
int execImporter(const std::vector<std::string>& args);

}  // namespace kiosk::app
