#include "runtime/import/SequenceSources.h"

#include "runtime/core/TimeParse.h"
#include "runtime/import/CfTime.h"
#include "runtime/import/GdalRaster.h"
#include "runtime/import/ImportSteps.h"

#include <cpl_string.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace kiosk::import {

namespace fs = std::filesystem;

std::optional<double> timeFromFileName(const std::string& fileName) {
    static const std::regex re(R"((\d{4})-?(\d{2})-?(\d{2})[T_ -]?(\d{2}):?(\d{2})(?::?(\d{2}))?)");
    std::smatch m;
    const std::string name = fs::path(fileName).filename().string();
    if (!std::regex_search(name, m, re)) return std::nullopt;
    std::string iso = m[1].str() + "-" + m[2].str() + "-" + m[3].str() + "T" + m[4].str() + ":" +
                      m[5].str() + ":" + (m[6].matched ? m[6].str() : std::string("00")) + "Z";
    return parseIso8601(iso);
}

namespace {

std::optional<int> frameNumber(const std::string& file) {
    static const std::regex re(R"((\d+)(?!.*\d))");
    std::smatch m;
    const std::string stem = fs::path(file).stem().string();
    if (!std::regex_search(stem, m, re)) return std::nullopt;
    return int(std::strtol(m[1].str().c_str(), nullptr, 10) % 1000000000L);
}

}  // namespace

Result<std::vector<float>> readCsvGrid(const std::string& path, int& width, int& height) {
    Diagnostics d;
    std::ifstream in(path);
    if (!in) {
        d.error("IMPORT_UNREADABLE", path, "", "cannot read grid");
        return d;
    }
    std::vector<float> values;
    std::string line;
    width = 0;
    height = 0;
    while (std::getline(in, line)) {
        for (char& c : line)
            if (c == ',' || c == ';' || c == '\t' || c == '\r') c = ' ';
        std::istringstream ls(line);
        int n = 0;
        std::string tok;
        while (ls >> tok) {
            char* end = nullptr;
            const double v = std::strtod(tok.c_str(), &end);
            if (!end || *end != '\0') {
                auto& e =
                    d.error("IMPORT_UNREADABLE", path, "", "not a numeric grid: '" + tok + "'");
                e.line = height + 1;
                return d;
            }
            values.push_back(float(v));
            ++n;
        }
        if (n == 0) continue;
        if (width == 0) width = n;
        if (n != width) {
            auto& e = d.error(
                "IMPORT_UNREADABLE", path, "",
                "row has " + std::to_string(n) + " values, expected " + std::to_string(width));
            e.line = height + 1;
            return d;
        }
        ++height;
    }
    if (width == 0) {
        d.error("IMPORT_UNREADABLE", path, "", "empty grid");
        return d;
    }
    return values;
}

std::optional<std::string> findLike(const std::string& file) {
    fs::path dir = fs::path(file).parent_path();
    for (int i = 0; i < 3 && !dir.empty(); ++i) {
        std::error_code ec;
        if (fs::exists(dir / "elevation.asc", ec)) return (dir / "elevation.asc").string();
        dir = dir.parent_path();
    }
    return std::nullopt;
}

Result<std::vector<Frame>> expandSources(const std::vector<std::string>& sources,
                                         const ImportOptions& o) {
    Diagnostics d;
    std::vector<Frame> frames;
    std::vector<std::string> files;
    for (const auto& s : sources) {
        std::error_code ec;
        if (fs::is_directory(s, ec)) {
            std::vector<std::string> inDir;
            for (const auto& e : fs::directory_iterator(s, ec))
                if (e.is_regular_file()) inDir.push_back(e.path().string());
            std::sort(inDir.begin(), inDir.end());
            files.insert(files.end(), inDir.begin(), inDir.end());
        } else {
            files.push_back(s);
        }
    }
    for (const auto& f : files) {
        std::error_code ec;
        if (!fs::exists(f, ec)) {
            d.error("IMPORT_UNREADABLE", f, "", "file does not exist");
            return d;
        }
        if (lowerExt(f) == ".csv") {
            frames.push_back({f, f, 1, std::nullopt, true});
            continue;
        }
        const std::string ext = lowerExt(f);
        if (ext == ".nc" || ext == ".nc4" || ext == ".cdf") {
            std::string open = o.variable.empty() ? f : "NETCDF:\"" + f + "\":" + o.variable;
            auto ds = openRaster(open);
            if (!ds) {
                Diagnostics e;
                e.error("IMPORT_UNREADABLE", f, o.variable.empty() ? "" : o.variable,
                        ds.diagnostics.firstError()->message);
                return e;
            }
            const int bands = GDALGetRasterCount(raw(*ds));
            char** md = GDALGetMetadata(raw(*ds), nullptr);
            const char* dimExtra = CSLFetchNameValue(md, "NETCDF_DIM_EXTRA");
            std::string timeDim = "time";
            if (dimExtra) {
                std::string s = dimExtra;
                s.erase(std::remove(s.begin(), s.end(), '{'), s.end());
                s.erase(std::remove(s.begin(), s.end(), '}'), s.end());
                if (!s.empty()) timeDim = s.substr(0, s.find(','));
            }
            const char* units = CSLFetchNameValue(md, (timeDim + "#units").c_str());
            const char* cal = CSLFetchNameValue(md, (timeDim + "#calendar").c_str());
            std::vector<double> values;
            for (int b = 1; b <= bands; ++b) {
                const char* v = GDALGetMetadataItem(GDALGetRasterBand(raw(*ds), b),
                                                    ("NETCDF_DIM_" + timeDim).c_str(), nullptr);
                if (v) values.push_back(std::strtod(v, nullptr));
            }
            if (units && int(values.size()) == bands) {
                // Forecast files (CAMS regional: `time:units = "hours"`) keep the reference date
                // elsewhere; --start names it, else the message says to.
                std::string unitText = units;
                std::string lowered = unitText;
                for (char& c : lowered) c = char(std::tolower(static_cast<unsigned char>(c)));
                if (lowered.find(" since ") == std::string::npos) {
                    if (!o.start) {
                        d.error("CF_TIME_UNITS", f, timeDim + ":units",
                                "time units '" + unitText +
                                    "' name no reference date ('<unit> since <date>'); give the "
                                    "forecast's reference time with --start TIME")
                            .hint = "e.g. --start 2026-03-14T00:00:00Z; the values are then " +
                                    unitText + " after it";
                        return d;
                    }
                    unitText += " since " + formatIso8601(*o.start);
                }
                auto times = cfTimesToEpoch(values, unitText, cal ? cal : "standard");
                if (!times) {
                    for (auto item : times.diagnostics.items()) {
                        item.file = f;
                        d.add(item);
                    }
                    return d;
                }
                for (int b = 1; b <= bands; ++b)
                    frames.push_back({f, open, b, (*times)[std::size_t(b - 1)], false});
                continue;
            }
            for (int b = 1; b <= bands; ++b) frames.push_back({f, open, b, std::nullopt, false});
            continue;
        }
        frames.push_back({f, f, 1, std::nullopt, false});
    }
    if (frames.empty()) {
        d.error("IMPORT_USAGE", "", "", "no sequence sources given");
        return d;
    }
    // Times not given by the data: a CSV, a pattern in names, or numbered from --start.
    const bool haveAll =
        std::all_of(frames.begin(), frames.end(), [](const Frame& f) { return bool(f.time); });
    if (o.timesCsv) {
        auto csv = readTimesCsv(*o.timesCsv);
        if (!csv) return csv.diagnostics;
        const bool byName = !csv->front().first.empty();
        if (!byName && csv->size() != frames.size()) {
            d.error("IMPORT_TIMES", *o.timesCsv, "",
                    std::to_string(csv->size()) + " times for " + std::to_string(frames.size()) +
                        " frames");
            return d;
        }
        for (std::size_t i = 0; i < frames.size(); ++i) {
            if (!byName) {
                frames[i].time = (*csv)[i].second;
                continue;
            }
            const std::string name = fs::path(frames[i].file).filename().string();
            auto it = std::find_if(csv->begin(), csv->end(), [&](const auto& e) {
                return fs::path(e.first).filename().string() == name;
            });
            if (it == csv->end()) {
                d.error("IMPORT_TIMES", *o.timesCsv, "", "no time for " + name);
                return d;
            }
            frames[i].time = it->second;
        }
    } else if (!haveAll) {
        for (std::size_t i = 0; i < frames.size(); ++i) {
            if (frames[i].time) continue;
            if (auto t = timeFromFileName(frames[i].file)) {
                frames[i].time = t;
                continue;
            }
            if (o.start) {
                const auto n = frameNumber(frames[i].file);
                const bool multiBand = frames[i].band > 1 || (i + 1 < frames.size() &&
                                                              frames[i + 1].file == frames[i].file);
                const double k = multiBand || !n ? double(i) : double(*n);
                frames[i].time = *o.start + k * o.step;
                continue;
            }
            d.error("IMPORT_NO_TIMES", frames[i].file, "",
                    "no timestamp for this frame (give --times TIMES.csv, --start TIME [--step "
                    "SECONDS], or a date-time in the file name)");
            return d;
        }
    }
    return frames;
}

}  // namespace kiosk::import
