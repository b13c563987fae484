#include "config/ReaderSupport.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace kiosk::config::reader {

const std::map<std::string, std::vector<std::string>>& propertyTable() {
    static const std::map<std::string, std::vector<std::string>> table = {
        {"Scenario",
         {"$schema", "version", "include", "title", "caption", "stores", "terrain", "layers",
          "transferFunctions", "clock", "lenses", "projectiveMappings", "viewpoints", "cameraPaths",
          "camera", "overlays", "lighting", "governor", "briefing"}},
        {"Governor", {"targetFps", "maxTauFactor", "minRenderScale"}},
        {"Terrain",
         {"store", "elevation", "tauGeom", "tauTex", "verticalExaggeration", "reference",
          "cacheBytes", "gpuBytes", "proceduralDetail", "occlusionCulling", "textureCompression"}},
        {"Layer",
         {"id", "kind", "source", "transfer", "operation", "enabled", "interpolate", "nodataAs",
          "product", "of"}},
        {"Product", {"threshold", "units", "timeUnits", "velocity", "isochrones"}},
        {"Source", {"store", "layer", "sequence"}},
        {"Operation", {"type", "weight", "opacity", "visibility"}},
        {"TransferFunction",
         {"label", "units", "space", "domain", "stops", "classes", "opacity", "nodata", "below",
          "above", "preset", "paraview", "gdal", "file"}},
        {"Stop", {"value", "color"}},
        {"ClassBreak", {"from", "color", "label"}},
        {"OpacityPoint", {"value", "opacity"}},
        {"ParaViewRef", {"file", "name"}},
        {"Clock", {"start", "end", "rate", "range", "paused", "waitForData"}},
        {"Lens",
         {"id", "kind", "shape", "center", "radius", "radii", "rotation", "softEdge", "raise",
          "lower", "inside", "outside", "enabled", "keys"}},
        {"LensKey", {"time", "center", "radius", "radii", "rotation"}},
        {"ProjectiveMapping",
         {"id", "origin", "u", "v", "textureMatrix", "data", "layer", "transfer", "colorMatrix",
          "blend", "opacity", "enabled", "keys", "image", "route", "contextMatrix"}},
        {"MappingBlend", {"src", "dst"}},
        {"MappingRoute", {"points", "width", "pointRadius"}},
        {"MappingKey", {"time", "origin", "u", "v", "textureMatrix", "colorMatrix", "opacity"}},
        {"Viewpoint", {"target", "heading", "pitch", "range"}},
        {"CameraPath", {"keys", "interpolation"}},
        {"CameraKey", {"time", "viewpoint", "target", "heading", "pitch", "range"}},
        {"Camera", {"viewpoint", "path", "interactive", "fovY"}},
        {"Overlays", {"legend", "timeLabel", "title", "status", "progress"}},
        {"Legend", {"enabled", "transfer", "position", "title", "layer"}},
        {"TimeLabel", {"enabled", "format", "timeZone", "showOffset", "position"}},
        {"SimpleOverlay", {"enabled", "position"}},
        {"Lighting",
         {"sunAzimuth", "sunAltitude", "ambient", "keys", "solar", "latitude", "longitude"}},
        {"LightingKey", {"time", "sunAzimuth", "sunAltitude"}},
        {"Briefing", {"chapters"}},
        {"Chapter",
         {"title", "time", "from", "to", "duration", "viewpoint", "path", "layers", "caption",
          "pause"}},
        {"ChapterLayer", {"enabled", "opacity"}},
    };
    return table;
}

std::string typeName(const json& j) {
    switch (j.type()) {
        case json::value_t::null:
            return "null";
        case json::value_t::boolean:
            return "boolean";
        case json::value_t::string:
            return "string";
        case json::value_t::array:
            return "array";
        case json::value_t::object:
            return "object";
        case json::value_t::discarded:
            return "invalid value";
        default:
            return "number";
    }
}

std::string quote(const std::string& s) {
    return "\"" + s + "\"";
}

std::string joined(const std::vector<std::string>& items) {
    std::string out;
    for (const auto& i : items) out += (out.empty() ? "" : ", ") + i;
    return out;
}

std::string numberText(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

std::optional<double> readNumber(Ctx& c, const json& j, const std::string& ptr, const Range& r,
                                 const std::string& name) {
    if (!j.is_number()) {
        c.error("SCENARIO_TYPE", ptr, "expected number, got " + typeName(j));
        return std::nullopt;
    }
    const double v = j.get<double>();
    if (!std::isfinite(v) || !r.contains(v)) {
        c.error("SCENARIO_RANGE", ptr, name + " must be " + r.text() + ", got " + numberText(v));
        return std::nullopt;
    }
    return v;
}

std::optional<color::Rgba> readColor(Ctx& c, const json& j, const std::string& ptr) {
    if (j.is_string()) {
        const std::string text = j.get<std::string>();
        if (auto col = color::parseColor(text)) return col;
        auto& e = c.error("SCENARIO_BAD_COLOR", ptr,
                          "bad colour " + quote(text) +
                              " (expected #rrggbb, #rrggbbaa, [r, g, b(, a)] in 0..1 or a name)");
        if (!text.empty() && text[0] != '#') {
            std::vector<std::string> names;
            for (auto n : color::colorNames()) names.emplace_back(n);
            c.didYouMean(e, text, names);
        }
        return std::nullopt;
    }
    if (j.is_array() && (j.size() == 3 || j.size() == 4)) {
        float v[4] = {0, 0, 0, 1};
        for (std::size_t i = 0; i < j.size(); ++i) {
            if (!j[i].is_number() || !(j[i].get<double>() >= 0 && j[i].get<double>() <= 1)) {
                c.error("SCENARIO_BAD_COLOR", childPointer(ptr, i),
                        "colour components must be numbers in 0..1");
                return std::nullopt;
            }
            v[i] = float(j[i].get<double>());
        }
        return color::Rgba{v[0], v[1], v[2], v[3]};
    }
    c.error("SCENARIO_BAD_COLOR", ptr,
            "expected a colour string or [r, g, b(, a)], got " + typeName(j));
    return std::nullopt;
}

bool hasZone(std::string_view s) {
    if (s.empty()) return false;
    if (s.back() == 'Z' || s.back() == 'z') return true;
    const auto t = s.find('T');
    if (t == std::string_view::npos) return false;
    return s.find_first_of("+-", t) != std::string_view::npos;
}

std::optional<double> readInstant(Ctx& c, const json& j, const std::string& ptr) {
    if (!j.is_string()) {
        c.error("SCENARIO_TYPE", ptr, "expected an ISO 8601 time string, got " + typeName(j));
        return std::nullopt;
    }
    const std::string s = j.get<std::string>();
    auto t = parseIso8601(s);
    if (!t || !hasZone(s)) {
        c.error("SCENARIO_BAD_TIME", ptr,
                "bad time " + quote(s) + " (expected ISO 8601 UTC like \"2026-03-14T06:40:00Z\")");
        return std::nullopt;
    }
    return t;
}

std::optional<TimeSpec> readTimeSpec(Ctx& c, const json& j, const std::string& ptr) {
    if (!j.is_string()) {
        c.error("SCENARIO_TYPE", ptr, "expected a time string, got " + typeName(j));
        return std::nullopt;
    }
    const std::string s = j.get<std::string>();
    auto t = parseTimeSpec(s);
    if (!t || (!t->isOffset && !hasZone(s))) {
        c.error("SCENARIO_BAD_TIME", ptr,
                "bad time " + quote(s) +
                    " (expected ISO 8601 UTC like \"2026-03-14T06:40:00Z\" or an offset from the "
                    "clock start like \"+1h30m\")");
        return std::nullopt;
    }
    return t;
}

std::optional<std::int64_t> readBytes(Ctx& c, const json& j, const std::string& ptr) {
    constexpr double kMin = double(1 << 20), kMax = double(1ll << 40);
    double value = 0;
    if (j.is_number()) {
        value = j.get<double>();
    } else if (j.is_string()) {
        const std::string s = j.get<std::string>();
        const char* b = s.data();
        const char* e = s.data() + s.size();
        auto [p, ec] = std::from_chars(b, e, value);
        std::string unit(p, e);
        unit.erase(std::remove(unit.begin(), unit.end(), ' '), unit.end());
        static const std::map<std::string, double> units = {
            {"", 1},     {"B", 1},    {"KiB", 1024.0}, {"MiB", 1048576.0}, {"GiB", 1073741824.0},
            {"KB", 1e3}, {"MB", 1e6}, {"GB", 1e9}};
        auto u = units.find(unit);
        if (ec != std::errc{} || u == units.end()) {
            c.error("SCENARIO_BAD_VALUE", ptr,
                    "bad size " + quote(s) + " (expected bytes or e.g. \"512 MiB\", \"2 GiB\")");
            return std::nullopt;
        }
        value *= u->second;
    } else {
        c.error("SCENARIO_TYPE", ptr, "expected a byte count or a size string, got " + typeName(j));
        return std::nullopt;
    }
    if (!std::isfinite(value) || value < kMin || value > kMax) {
        c.error("SCENARIO_RANGE", ptr,
                "byte budget must be between 1 MiB and 1 TiB, got " + numberText(value));
        return std::nullopt;
    }
    return std::int64_t(value);
}

}  // namespace kiosk::config::reader
