#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kiosk {

/** @brief Levenshtein distance, for "did you mean" hints. */
std::size_t editDistance(std::string_view a, std::string_view b);

/** @brief A number for messages: printf "%g" (3, 0.25, 1e+06). */
std::string shortNumber(double v);

/** @brief The candidate closest to `word` if it is plausibly a typo of it, else nullopt. */
std::optional<std::string> closestMatch(std::string_view word,
                                        const std::vector<std::string>& candidates);

/** @brief Parse `1280x720`; rejects zero, negative and absurd sizes (> 16384). */
std::optional<std::pair<int, int>> parseSize(std::string_view text);

}  // namespace kiosk
