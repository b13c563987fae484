#include "runtime/core/Diagnostics.h"

namespace kiosk {

std::string Diagnostic::format() const {
    std::string out = file.empty() ? std::string("geokiosk") : file;
    if (line > 0) {
        out += ":" + std::to_string(line);
        if (column > 0) out += ":" + std::to_string(column);
    }
    out += ": ";
    if (severity == Severity::Warning) out += "warning: ";
    if (!where.empty()) out += where + ": ";
    out += message;
    if (!hint.empty()) out += " (" + hint + ")";
    if (!code.empty()) out += " [" + code + "]";
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
