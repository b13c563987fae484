#include "runtime/core/TimeParse.h"
#include "runtime/import/Importer.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>

// The `--times CSV` reader and the frame-time check, on their own so that a fuzz target can hold it
// to its contract (never crash, every failure one IMPORT_TIMES line) without linking GDAL.
namespace kiosk::import {

namespace {

std::optional<double> parseTimeText(std::string s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.erase(0, 1);
    if (s.empty()) return std::nullopt;
    if (auto t = parseIso8601(s)) return t;
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (end && *end == '\0' && std::isfinite(v)) return v;
    return std::nullopt;
}

}  // namespace

Result<std::vector<std::pair<std::string, double>>> readTimesCsv(const std::string& path) {
    Diagnostics d;
    std::ifstream in(path);
    if (!in) {
        d.error("IMPORT_UNREADABLE", path, "", "cannot read times file");
        return d;
    }
    std::vector<std::pair<std::string, double>> out;
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty() || line[0] == '#') continue;
        std::string file, time = line;
        const auto comma = line.find(',');
        if (comma != std::string::npos) {
            file = line.substr(0, comma);
            time = line.substr(comma + 1);
        }
        auto t = parseTimeText(time);
        if (!t) {
            if (out.empty() && lineNo == 1) continue;  // header
            auto& e = d.error("IMPORT_TIMES", path, "", "cannot parse time '" + time + "'");
            e.line = lineNo;
            return d;
        }
        out.emplace_back(file, *t);
    }
    if (out.empty()) {
        d.error("IMPORT_TIMES", path, "", "no times in file");
        return d;
    }
    return out;
}

Diagnostics checkTimes(const std::vector<double>& times, const std::vector<std::string>& files) {
    Diagnostics d;
    for (std::size_t i = 1; i < times.size(); ++i) {
        if (times[i] > times[i - 1]) continue;
        const std::string a = i - 1 < files.size() ? files[i - 1] : "";
        const std::string b = i < files.size() ? files[i] : "";
        if (times[i] == times[i - 1])
            d.error("IMPORT_TIMES_DUPLICATE", b, "frame " + std::to_string(i),
                    "duplicate timestamp " + formatIso8601(times[i]) + " (also " + a + ")");
        else
            d.error("IMPORT_TIMES_UNSORTED", b, "frame " + std::to_string(i),
                    "timestamp " + formatIso8601(times[i]) + " is earlier than " +
                        formatIso8601(times[i - 1]) + " of " + a);
        return d;
    }
    return d;
}

}  // namespace kiosk::import
