#pragma once

#include <string>
#include <vector>

namespace kiosk::app {

/**
 * @brief The geokiosk command line (docs/cli.md): dispatch to play, render, import, validate,
 * info. Returns the process exit status (kExit*). Never throws; every failure is one line on
 * stderr naming the file, JSON path or tile.
 */
int runCli(const std::vector<std::string>& args);

/** @brief Top-level help text. */
std::string usageText();

}  // namespace kiosk::app
