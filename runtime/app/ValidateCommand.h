#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace kiosk::app {

/**
 * @brief `geokiosk validate [--no-stores] [--quiet] SCENARIO...` (docs/cli.md).
 *
 * For each scenario: reads it with its includes (schema and reference checks, config/), then
 * opens every store it names (io::StoreReader, read-only) and runs the meaning checks (layers,
 * sequences, time ranges, units, transfer function domains). Diagnostics go to stderr, one line
 * each, `file:line:col: /json/pointer: what is wrong (hint) [CODE]`; a valid scenario prints
 * `SCENARIO: ok (...)` on stdout unless --quiet. `--no-stores` skips the store checks.
 *
 * Returns 0 when every scenario is valid (warnings allowed), 1 when any is invalid, 2 on a usage
 * error. Never throws, never crashes on any input. Main thread.
 */
int runValidateCommand(const std::vector<std::string>& args);

/** @brief Same, writing to the given streams (tests). */
int runValidateCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace kiosk::app
