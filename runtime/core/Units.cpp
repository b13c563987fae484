#include "runtime/core/Units.h"

#include <algorithm>
#include <cctype>
#include <utility>
#include <vector>

namespace kiosk {

namespace {

// Words for one unit, as CF/UDUNITS and GDAL drivers spell them in the wild.
constexpr std::pair<std::string_view, std::string_view> kAliases[] = {
    {"metre", "m"},
    {"metres", "m"},
    {"meter", "m"},
    {"meters", "m"},
    {"millimetre", "mm"},
    {"millimetres", "mm"},
    {"millimeter", "mm"},
    {"millimeters", "mm"},
    {"centimetre", "cm"},
    {"centimetres", "cm"},
    {"centimeter", "cm"},
    {"centimeters", "cm"},
    {"kilometre", "km"},
    {"kilometres", "km"},
    {"kilometer", "km"},
    {"kilometers", "km"},
    {"foot", "ft"},
    {"feet", "ft"},
    {"second", "s"},
    {"seconds", "s"},
    {"sec", "s"},
    {"hour", "h"},
    {"hours", "h"},
    {"hr", "h"},
    {"minute", "min"},
    {"minutes", "min"},
    {"day", "d"},
    {"days", "d"},
    {"kelvin", "K"},
    {"Kelvin", "K"},
    {"celsius", "degC"},
    {"Celsius", "degC"},
    {"deg_C", "degC"},
    {"degree_Celsius", "degC"},
    {"degrees_Celsius", "degC"},
    {"degree_C", "degC"},
    {"degrees_C", "degC"},
    {"percent", "%"},
    {"kilogram", "kg"},
    {"kilograms", "kg"},
    {"\u00b0C", "degC"},
};

std::string_view alias(std::string_view w) {
    for (const auto& [from, to] : kAliases)
        if (w == from) return to;
    return w;
}

// "h-1", "h^-1", "h**-1" -> ("h", true): a reciprocal factor.
std::pair<std::string, bool> factor(std::string w) {
    for (std::string_view suffix : {"**-1", "^-1", "-1"}) {
        if (w.size() > suffix.size() &&
            w.compare(w.size() - suffix.size(), suffix.size(), suffix.data(), suffix.size()) == 0)
            return {std::string(alias(w.substr(0, w.size() - suffix.size()))), true};
    }
    return {std::string(alias(w)), false};
}

}  // namespace

std::optional<std::string> cleanUnits(std::string_view text, std::string* why) {
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front())))
        text.remove_prefix(1);
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
        text.remove_suffix(1);
    if (text.size() > 64) {
        if (why) *why = "longer than 64 characters";
        return std::nullopt;
    }
    for (char c : text) {
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
            if (why) *why = "contains control characters";
            return std::nullopt;
        }
    }
    return std::string(text);
}

std::string canonicalUnits(std::string_view text) {
    auto clean = cleanUnits(text);
    if (!clean) return std::string(text);
    // Split into factors: blanks and '.' multiply, one '/' divides what follows.
    std::vector<std::string> num, den;
    bool dividing = false;
    std::string word;
    auto flush = [&] {
        if (word.empty()) return;
        auto [f, reciprocal] = factor(word);
        (reciprocal != dividing ? den : num).push_back(f);
        word.clear();
    };
    for (char c : *clean) {
        if (c == ' ' || c == '\t' || c == '.' || c == '*') {
            // "**-1" is an exponent, not a product.
            if (c == '*' && !word.empty()) {
                word += c;
                continue;
            }
            flush();
        } else if (c == '/') {
            flush();
            dividing = true;
        } else {
            word += c;
        }
    }
    flush();
    if (num.empty() && den.empty()) return "";
    auto join = [](const std::vector<std::string>& v) {
        std::string s;
        for (const auto& f : v) s += (s.empty() ? "" : ".") + f;
        return s;
    };
    return (num.empty() ? std::string("1") : join(num)) + (den.empty() ? "" : "/" + join(den));
}

bool sameUnits(std::string_view a, std::string_view b) {
    const std::string ca = canonicalUnits(a), cb = canonicalUnits(b);
    return !ca.empty() && ca == cb;
}

}  // namespace kiosk
