#pragma once

// Small text helpers shared by the colour-map file readers (ColorImport.cpp, ColorMapFiles.cpp).
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

namespace kiosk::color::detail {

/** @brief A whole file as text, nullopt when unreadable. */
inline std::optional<std::string> readText(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/** @brief A finite number filling all of `s` (a leading '+' allowed), else nullopt. */
inline std::optional<double> toNumber(std::string_view s) {
    if (s.empty()) return std::nullopt;
    if (s.front() == '+') s.remove_prefix(1);
    double v = 0;
    auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc{} || p != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
    return v;
}

}  // namespace kiosk::color::detail
