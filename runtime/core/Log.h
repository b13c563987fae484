#pragma once

#include <cstdarg>
#include <string>
#include <vector>

namespace kiosk::log {

enum class Level { Error = 3, Warn = 4, Info = 6, Debug = 7 };

/**
 * @brief printf-style logging to stderr with sd-daemon level prefixes (`<3>` ...), which
 * journald maps to priorities. Formats into a fixed stack buffer: no heap in the frame loop.
 * Thread-safe. Lines below the threshold (default Info; GEOKIOSK_LOG=debug) are dropped.
 */
void write(Level level, const char* tag, const char* fmt, ...) __attribute__((format(printf, 3, 4)));
void vwrite(Level level, const char* tag, const char* fmt, std::va_list args);

void setThreshold(Level level) noexcept;
Level threshold() noexcept;
/** @brief Prefix lines with `<N>` for journald (on when stderr is not a terminal). */
void setSyslogPrefix(bool on) noexcept;

/** @brief The last lines logged (for the status overlay), newest last. */
std::vector<std::string> recent(std::size_t maxLines);

}  // namespace kiosk::log

#define KIOSK_LOG_ERROR(tag, ...) ::kiosk::log::write(::kiosk::log::Level::Error, tag, __VA_ARGS__)
#define KIOSK_LOG_WARN(tag, ...) ::kiosk::log::write(::kiosk::log::Level::Warn, tag, __VA_ARGS__)
#define KIOSK_LOG_INFO(tag, ...) ::kiosk::log::write(::kiosk::log::Level::Info, tag, __VA_ARGS__)
#define KIOSK_LOG_DEBUG(tag, ...) ::kiosk::log::write(::kiosk::log::Level::Debug, tag, __VA_ARGS__)
