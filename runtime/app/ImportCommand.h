#pragma once

#include <string>
#include <vector>

namespace kiosk::app {

/**
 * @brief `geokiosk import elevation|imagery|sequence ...` (docs/cli.md); `args` are the words
 * after "import". Diagnostics go to stderr one per line (Diagnostic::format()).
 * Returns 0 on success, 1 on bad input (nothing written), 2 on a usage error.
 */
int runImportCommand(const std::vector<std::string>& args);

}  // namespace kiosk::app
