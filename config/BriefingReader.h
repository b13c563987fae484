#pragma once

#include "config/Scenario.h"
#include "runtime/core/Diagnostics.h"

#include <nlohmann/json_fwd.hpp>

namespace kiosk::config {

/** @brief Limits of a briefing (hand-written; generous for a talk, bounded for hostile input). */
inline constexpr std::size_t kMaxChapters = 256;
inline constexpr std::size_t kMaxCaptionBytes = 2000;
inline constexpr std::size_t kMaxCaptionLines = 12;
inline constexpr double kMaxChapterSeconds = 3600;

/**
 * @brief Read the optional `briefing` member of a merged scenario document into
 * `scenario.briefing` (docs/scenario-format.md, "Briefings"). Runs after the rest of the
 * scenario was read: chapters refer to its viewpoints, camera paths, layers and clock. Messages
 * in the reader's style (`file:line:col: /briefing/chapters/1/viewpoint: ...`) go to `diags`.
 */
void readBriefing(const nlohmann::json& document, Scenario& scenario, Diagnostics& diags);

}  // namespace kiosk::config
