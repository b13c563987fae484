#include "runtime/service/Control.h"

#include <cmath>
#include <cstdlib>
#include <fstream>

namespace kiosk::service {

bool constantTimeEquals(std::string_view a, std::string_view b) noexcept {
    // Walk the longer length either way so the time does not reveal the matching prefix.
    const std::size_t n = std::max(a.size(), b.size());
    unsigned diff = a.size() == b.size() ? 0u : 1u;
    for (std::size_t i = 0; i < n; ++i) {
        const unsigned char x = i < a.size() ? static_cast<unsigned char>(a[i]) : 0;
        const unsigned char y = i < b.size() ? static_cast<unsigned char>(b[i]) : 0;
        diff |= unsigned(x ^ y);
    }
    // volatile read keeps the compiler from turning the loop into an early-exit compare.
    volatile unsigned result = diff;
    return result == 0;
}

std::optional<TokenGuard> TokenGuard::fromFile(const std::filesystem::path& file,
                                               std::string& why) {
    std::ifstream in(file);
    if (!in) {
        why = file.string() + ": control token file cannot be read";
        return std::nullopt;
    }
    std::string line;
    std::getline(in, line);
    const auto first = line.find_first_not_of(" \t\r\n");
    const auto last = line.find_last_not_of(" \t\r\n");
    if (first == std::string::npos) {
        why = file.string() + ": control token file is empty";
        return std::nullopt;
    }
    return TokenGuard(line.substr(first, last - first + 1));
}

int TokenGuard::check(std::string_view header) const noexcept {
    if (!configured()) return 403;
    constexpr std::string_view kScheme = "Bearer ";
    if (header.size() < kScheme.size() || header.substr(0, kScheme.size()) != kScheme) return 401;
    return constantTimeEquals(header.substr(kScheme.size()), mToken) ? 200 : 401;
}

const char* controlActionName(ControlAction a) noexcept {
    switch (a) {
        case ControlAction::Pause:
            return "pause";
        case ControlAction::Play:
            return "play";
        case ControlAction::Seek:
            return "seek";
        case ControlAction::Rate:
            return "rate";
        case ControlAction::Next:
            return "next";
        case ControlAction::Previous:
            return "previous";
        case ControlAction::Reload:
            return "reload";
        case ControlAction::Lens:
            return "lens";
    }
    return "?";
}

std::optional<ControlCommand> parseControl(std::string_view name, std::string_view t,
                                           std::string_view r, std::string& why, bool& notFound) {
    notFound = false;
    ControlCommand c;
    static constexpr ControlAction kAll[] = {
        ControlAction::Pause, ControlAction::Play,     ControlAction::Seek,   ControlAction::Rate,
        ControlAction::Next,  ControlAction::Previous, ControlAction::Reload, ControlAction::Lens};
    bool known = false;
    for (ControlAction a : kAll)
        if (name == controlActionName(a)) {
            c.action = a;
            known = true;
        }
    if (!known) {
        notFound = true;
        why = "unknown control '" + std::string(name) + "'";
        return std::nullopt;
    }
    if (c.action == ControlAction::Seek) {
        auto spec = parseTimeSpec(t);
        if (t.empty() || !spec) {
            why =
                "seek wants t=TIME (ISO 8601 or an offset like +3h), got '" + std::string(t) + "'";
            return std::nullopt;
        }
        c.time = *spec;
    }
    if (c.action == ControlAction::Rate) {
        const std::string text(r);
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end || !std::isfinite(v) || std::abs(v) > 1e7) {
            why = "rate wants r=X (data seconds per wall second), got '" + text + "'";
            return std::nullopt;
        }
        c.rate = v;
    }
    return c;
}

bool parseLensMove(LensMove& out,
                   const std::function<std::optional<std::string>(const char*)>& param,
                   std::string& why) {
    struct Number {
        const char* name;
        std::optional<double>* to;
        double min, max;
    };
    const Number numbers[] = {{"x", &out.x, -1e9, 1e9},
                              {"y", &out.y, -1e9, 1e9},
                              {"radius", &out.radius, 1e-3, 1e9},
                              {"rotation", &out.rotation, -360, 360}};
    for (const Number& n : numbers) {
        const auto text = param(n.name);
        if (!text) continue;
        char* end = nullptr;
        const double v = std::strtod(text->c_str(), &end);
        if (text->empty() || *end || !std::isfinite(v) || v < n.min || v > n.max) {
            why = std::string("lens wants ") + n.name + " in [" + std::to_string(n.min) + ", " +
                  std::to_string(n.max) + "], got '" + *text + "'";
            return false;
        }
        *n.to = v;
    }
    if (const auto e = param("enabled")) {
        if (*e == "1" || *e == "true")
            out.enabled = true;
        else if (*e == "0" || *e == "false")
            out.enabled = false;
        else {
            why = "lens wants enabled=0|1 (or false|true), got '" + *e + "'";
            return false;
        }
    }
    if (const auto id = param("id")) out.id = *id;
    if (!out.x && !out.y && !out.radius && !out.rotation && !out.enabled) {
        why = "lens wants at least one of x, y, radius, rotation, enabled";
        return false;
    }
    return true;
}

bool ControlQueue::push(const ControlCommand& c) {
    std::lock_guard lock(mMutex);
    if (mQueue.size() >= kMaxPending) return false;
    mQueue.push_back(c);
    return true;
}

void ControlQueue::drain(std::vector<ControlCommand>& out) {
    out.clear();
    std::lock_guard lock(mMutex);
    while (!mQueue.empty()) {
        out.push_back(mQueue.front());
        mQueue.pop_front();
    }
}

}  // namespace kiosk::service
