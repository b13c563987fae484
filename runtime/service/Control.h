#pragma once

#include "runtime/core/TimeParse.h"

#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

// Remote control of a running kiosk: the bearer-token guard and the command queue between the
// HTTP thread (producer) and the frame loop (consumer). Pure logic plus a mutex.
namespace kiosk::service {

/** @brief Compare two strings in time that depends only on their lengths, not their contents. */
bool constantTimeEquals(std::string_view a, std::string_view b) noexcept;

/**
 * @brief The control token. Without a configured token every control request gets 403; with
 * one, a request without `Authorization: Bearer <token>` or with a wrong token gets 401.
 */
class TokenGuard {
public:
    TokenGuard() = default;
    explicit TokenGuard(std::string token) : mToken(std::move(token)) {}
    /**
     * @brief Read the token from a file (first line, surrounding whitespace trimmed). Empty
     * files and unreadable files are errors (`why` set), never an open control port.
     */
    static std::optional<TokenGuard> fromFile(const std::filesystem::path& file, std::string& why);
    bool configured() const noexcept { return !mToken.empty(); }
    /** @brief HTTP status for a request carrying this Authorization header value: 200, 401, 403. */
    int check(std::string_view authorizationHeader) const noexcept;

private:
    std::string mToken;
};

enum class ControlAction { Pause, Play, Seek, Rate, Next, Previous, Reload, Lens };
const char* controlActionName(ControlAction a) noexcept;

/** @brief POST /control/lens: what to change of a lens (absent: keep). */
struct LensMove {
    std::string id;                  ///< empty: the first comparison lens (else the first lens)
    std::optional<double> x, y;      ///< new centre, map coordinates (store CRS metres)
    std::optional<double> radius;    ///< circle radius; an ellipse keeps its aspect
    std::optional<double> rotation;  ///< degrees counter-clockwise (swipe: inside direction)
    std::optional<bool> enabled;
};

struct ControlCommand {
    ControlAction action = ControlAction::Pause;
    TimeSpec time;      ///< Seek: ISO 8601 or an offset from the scenario start (+3h)
    double rate = 1.0;  ///< Rate: data seconds per wall second
    LensMove lens;      ///< Lens
};

/**
 * @brief Parse `/control/<name>` with its query parameter (`t` for seek, `r` for rate). On a
 * bad request returns nullopt with a one-line reason in `why` (HTTP 400); an unknown name sets
 * `notFound` (HTTP 404).
 */
std::optional<ControlCommand> parseControl(std::string_view name, std::string_view t,
                                           std::string_view r, std::string& why, bool& notFound);

/**
 * @brief The parameters of POST /control/lens: `param(name)` gives a query parameter (nullopt
 * when absent) among id, x, y, radius, rotation, enabled. False with a one-line reason in `why`
 * (HTTP 400) for a bad number or when none of the changes is given.
 */
bool parseLensMove(LensMove& out,
                   const std::function<std::optional<std::string>(const char*)>& param,
                   std::string& why);

/** @brief Commands from the HTTP thread, taken by the frame loop once per frame. */
class ControlQueue {
public:
    /** @brief At most this many commands wait; more are refused (HTTP 503), memory stays bounded.
     */
    static constexpr std::size_t kMaxPending = 64;
    bool push(const ControlCommand& c);
    /** @brief Move all waiting commands into `out` (cleared first). */
    void drain(std::vector<ControlCommand>& out);

private:
    std::mutex mMutex;
    std::deque<ControlCommand> mQueue;
};

}  // namespace kiosk::service
