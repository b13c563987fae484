#pragma once

#include "config/SourceMap.h"
#include "runtime/core/Diagnostics.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

// Internal to config/: turns a scenario file and its includes into one merged JSON document
// plus a SourceMap that still knows, for every value, which file and line:col it came from.
namespace kiosk::config {

/** @brief The merged document; `value` is null when loading failed (errors are in diags). */
struct LoadedDocument {
    nlohmann::json value;
    SourceMap sourceMap;
    std::vector<std::filesystem::path> files;  ///< root first, then includes in reading order
};

/**
 * @brief Read a regular file of at most `maxBytes`. On failure returns nullopt and sets `why`
 * ("does not exist", "is not a regular file", "is larger than 16 MiB", "cannot be read").
 * Refusing non-regular files keeps `"include": ["/dev/zero"]` from hanging the reader.
 */
std::optional<std::string> readTextFile(const std::filesystem::path& file, std::uintmax_t maxBytes,
                                        std::string& why);

/**
 * @brief Parse `text` (the root file, named `name`) and everything it includes; see
 * readScenario() for the merge rule. Never throws.
 */
LoadedDocument loadDocument(std::string_view text, const std::filesystem::path& name,
                            Diagnostics& diags);

}  // namespace kiosk::config
