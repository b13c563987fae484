#pragma once

#include <string>
#include <vector>

namespace kiosk::app {

/**
 * @brief The importer executable's command line: `geokiosk-import KIND ...`, where the words are
 * exactly those after `geokiosk import` (elevation|imagery|sequence ..., topographic ...).
 * Same exit statuses and messages as docs/cli.md; third-party exceptions become one line.
 */
int runImportCli(const std::vector<std::string>& args);

}  // namespace kiosk::app
