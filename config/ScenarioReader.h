#pragma once

#include "config/Scenario.h"
#include "runtime/core/Result.h"

#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

// Reading scenarios: JSON (comments allowed) -> includes merged -> typed, validated Scenario.
// Every message is `file:line:col: /json/pointer: what is wrong (did you mean "x"?) [CODE]`.
// Never throws and never crashes on any input (a fuzz target holds it to that); any thread.
namespace kiosk::config {

/**
 * @brief Read a scenario file, its includes and the transfer-function files it references.
 *
 * Includes: `"include": ["common.json", ...]` (paths relative to the including file) are read
 * first, in order, then the including file is merged over them: objects merge member by member
 * (recursively), except that an entry of `stores`, `transferFunctions`, `viewpoints` or
 * `cameraPaths` replaces the entry of the same name whole; arrays (`layers`, `lenses`, ...) and
 * scalars replace. Includes may nest; cycles are an error (SCENARIO_INCLUDE_CYCLE).
 *
 * `filesRead`, when given, receives every file the reader looked at (the scenario, includes,
 * colour files) also when reading fails, so that hot reload can keep watching a broken include;
 * on success it equals Scenario::sourceFiles.
 *
 * Codes: SCENARIO_FILE, SCENARIO_PARSE, SCENARIO_TYPE, SCENARIO_UNKNOWN_PROPERTY,
 * SCENARIO_MISSING, SCENARIO_BAD_VALUE, SCENARIO_RANGE, SCENARIO_BAD_TIME, SCENARIO_BAD_COLOR,
 * SCENARIO_VERSION, SCENARIO_DUPLICATE_ID, SCENARIO_UNKNOWN_REFERENCE, SCENARIO_CONFLICT,
 * SCENARIO_INCLUDE_MISSING, SCENARIO_INCLUDE_CYCLE, SCENARIO_TRANSFER (with the TF_/COLOR_ code
 * of the underlying problem in the message); warnings SCENARIO_DUPLICATE_KEY.
 */
Result<Scenario> readScenario(const std::filesystem::path& file,
                              std::vector<std::filesystem::path>* filesRead = nullptr);

/**
 * @brief Same, from text already in memory. `nameForMessages` is used in messages and as the
 * base for relative paths (includes, stores, colour files).
 */
Result<Scenario> parseScenario(std::string_view text, const std::filesystem::path& nameForMessages,
                               std::vector<std::filesystem::path>* filesRead = nullptr);

/**
 * @brief The properties the reader accepts, per object kind. "Scenario" is the document root;
 * the other kinds are the `$defs` of config/schema/scenario.schema.json (a unit test keeps the
 * two identical).
 */
const std::map<std::string, std::vector<std::string>>& acceptedProperties();

/** @brief Largest file the reader accepts (scenarios are hand-written; 16 MiB is plenty). */
inline constexpr std::uintmax_t kMaxScenarioFileBytes = 16u << 20;
/** @brief Deepest JSON nesting accepted (a real scenario needs about 6). */
inline constexpr int kMaxScenarioDepth = 64;

}  // namespace kiosk::config
