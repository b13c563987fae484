#pragma once

#include "config/SourceMap.h"
#include "runtime/core/Diagnostics.h"

#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <cstdint>

// How much a scenario may ask for. A scenario is small hand-written JSON; each limit is far
// above what a real one needs and low enough that reading, validating and drawing what passes
// stays within seconds and a few hundred MB on a weak kiosk (docs/scenario-format.md, "Limits").
// `validate` refuses what `render` could not draw, with the JSON pointer, instead of letting the
// GPU or the frame loop find out.
namespace kiosk::config {

/** @brief Files read for one scenario: the scenario and every include, counted each time. */
inline constexpr int kMaxIncludeFiles = 64;
/** @brief Includes nested inside includes (the scenario itself is depth 0). */
inline constexpr int kMaxIncludeDepth = 8;
/** @brief Bytes of the scenario and all its includes together. */
inline constexpr std::uintmax_t kMaxScenarioTotalBytes = 32u << 20;

/** @brief Layers in the stack. */
inline constexpr std::size_t kMaxLayers = 12;
/**
 * @brief Texture units the layer stack may need: OpenGL ES 3.0 guarantees 16 per fragment
 * shader. 1 (elevation LUT) + per `data` layer 2 (LUT + data), per `sequence` layer 3 (LUT +
 * frame pair) and 1 more with `"interpolate": "arrival"`, per other layer 1, plus 2 when there
 * are projective mappings (render::textureUnitsNeeded counts the same).
 */
inline constexpr int kMaxTextureUnits = 16;
/** @brief Lenses (each one is evaluated per pixel; 128 already cost seconds per frame). */
inline constexpr std::size_t kMaxLenses = 16;
/** @brief Projective mappings (render::MappingSet::kMaxMappings: what one uniform block holds). */
inline constexpr std::size_t kMaxMappings = 64;
/** @brief Keys of one lens, mapping, camera path or the lighting. */
inline constexpr std::size_t kMaxKeys = 4096;
/** @brief Points of one route, stops/classes/opacity points of one transfer function. */
inline constexpr std::size_t kMaxPoints = 4096;
/** @brief Entries of `stores`, `transferFunctions`, `viewpoints`, `cameraPaths`. */
inline constexpr std::size_t kMaxNamedEntries = 256;
static_assert(kMaxIndexedItems > kMaxPoints && kMaxIndexedItems > kMaxKeys,
              "positions of items within every limit must be kept (SourceMap.h)");

/** @brief Texture units the layers of `doc` need (see kMaxTextureUnits). Never throws. */
int textureUnitsNeeded(const nlohmann::json& doc);

/**
 * @brief Report every count above its limit as SCENARIO_LIMIT at the culprit's pointer (with
 * file:line:col from `map`). Run on the merged document before it is read, so that a scenario
 * with a million keys is refused without reading them. Never throws.
 */
void checkLimits(const nlohmann::json& doc, const SourceMap& map, Diagnostics& diags);

}  // namespace kiosk::config
