#pragma once

#include "runtime/core/Result.h"
#include "runtime/wall/Wall.h"

#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

// Reading wall files: JSON (comments allowed) with config/schema/wall.schema.json. Messages are
// the scenarios' `file:line:col: /json/pointer: what is wrong (did you mean "x"?) [CODE]`
// (config/DocumentLoader + SourceMap). Never throws; any thread.
namespace kiosk::wall {

/**
 * @brief Read and check a wall file: types and ranges, unique ids, screens inside the grid and
 * not overlapping, mullions > 0 mm, every screen driven by exactly one node, known leader,
 * tcp:// or ipc:// endpoints, overlay placements on known screens.
 *
 * Codes: WALL_FILE, WALL_PARSE (SCENARIO_PARSE from the shared loader), WALL_TYPE,
 * WALL_UNKNOWN_PROPERTY, WALL_MISSING, WALL_RANGE, WALL_DUPLICATE_ID, WALL_UNKNOWN_SCREEN,
 * WALL_UNKNOWN_NODE, WALL_OVERLAP, WALL_BEZEL, WALL_UNDRIVEN, WALL_ENDPOINT.
 */
Result<Wall> readWall(const std::filesystem::path& file);
/** @brief Accepted properties per object kind ("Wall" is the root; the others are the `$defs`
 * of config/schema/wall.schema.json, which a unit test keeps identical). */
const std::map<std::string, std::vector<std::string>>& acceptedWallProperties();
Result<Wall> parseWall(std::string_view text, const std::filesystem::path& nameForMessages);

}  // namespace kiosk::wall
