#pragma once

#include <cstddef>
#include <string>
#include <string_view>

// Text from users and files inside messages: a message is one line, at most a few hundred bytes,
// and never drives a terminal or a kiosk screen (issue 13: a `\n` in a JSON value forged a
// second "ok" line, ESC/BEL reached the terminal raw, a 4 MiB key gave an 8 MB message).
namespace kiosk {

/**
 * @brief `text` made safe for a one-line message: control characters (C0, DEL, C1) become `\n`,
 * `\r`, `\t`, `\xHH` or `\u{HH}`, invalid UTF-8 bytes become `\xHH`, and text longer than
 * `maxBytes` is cut at a character boundary and ends in `…`.
 */
std::string escapeForMessage(std::string_view text, std::size_t maxBytes);

/// Longest field texts Diagnostic::format() prints (bytes; longer ones end in "…").
inline constexpr std::size_t kMaxMessageFileBytes = 300;
inline constexpr std::size_t kMaxMessageWhereBytes = 200;
inline constexpr std::size_t kMaxMessageTextBytes = 500;
inline constexpr std::size_t kMaxMessageHintBytes = 200;

}  // namespace kiosk
