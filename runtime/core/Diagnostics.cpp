#include "runtime/core/Diagnostics.h"

#include "runtime/core/MessageText.h"

namespace kiosk {

std::string Diagnostic::format() const {
    // Every field can carry user text (a JSON string, a key, a file name, a parser's echo of
    // the input): escaped and bounded here, once, so that a message is always one line of at
    // most ~1.3 KB that cannot forge a second line or drive the terminal.
    std::string out =
        file.empty() ? std::string("geokiosk") : escapeForMessage(file, kMaxMessageFileBytes);
    if (line > 0) {
        out += ":" + std::to_string(line);
        if (column > 0) out += ":" + std::to_string(column);
    }
    out += ": ";
    if (severity == Severity::Warning) out += "warning: ";
    if (!where.empty()) out += escapeForMessage(where, kMaxMessageWhereBytes) + ": ";
    out += escapeForMessage(message, kMaxMessageTextBytes);
    if (!hint.empty()) out += " (" + escapeForMessage(hint, kMaxMessageHintBytes) + ")";
    if (!code.empty()) out += " [" + escapeForMessage(code, 64) + "]";
    return out;
}

Diagnostic& Diagnostics::error(std::string code, std::string file, std::string where,
                               std::string message) {
    mItems.push_back(Diagnostic{Severity::Error, std::move(code), std::move(file), 0, 0,
                                std::move(where), std::move(message), {}});
    return mItems.back();
}

Diagnostic& Diagnostics::warning(std::string code, std::string file, std::string where,
                                 std::string message) {
    mItems.push_back(Diagnostic{Severity::Warning, std::move(code), std::move(file), 0, 0,
                                std::move(where), std::move(message), {}});
    return mItems.back();
}

void Diagnostics::append(const Diagnostics& other) {
    mItems.insert(mItems.end(), other.mItems.begin(), other.mItems.end());
}

bool Diagnostics::hasErrors() const noexcept { return firstError() != nullptr; }

bool Diagnostics::has(std::string_view code) const noexcept {
    for (const auto& d : mItems)
        if (d.code == code) return true;
    return false;
}

const Diagnostic* Diagnostics::firstError() const noexcept {
    for (const auto& d : mItems)
        if (d.severity == Severity::Error) return &d;
    return nullptr;
}

std::string Diagnostics::format() const {
    std::string out;
    for (const auto& d : mItems) {
        out += d.format();
        out += '\n';
    }
    return out;
}

}  // namespace kiosk
