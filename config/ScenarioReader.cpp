#include "config/ScenarioReader.h"

#include "config/BriefingReader.h"
#include "config/DocumentLoader.h"
#include "runtime/color/ColorImport.h"
#include "runtime/color/ColorMapFiles.h"
#include "runtime/core/Assert.h"
#include "runtime/core/Strings.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <set>

namespace kiosk::config {

namespace {

using nlohmann::json;

// ---------------------------------------------------------------------------------------------
// The property table: the single list the reader checks unknown keys against and the schema
// test compares with config/schema/scenario.schema.json.

const std::map<std::string, std::vector<std::string>>& propertyTable() {
    static const std::map<std::string, std::vector<std::string>> table = {
        {"Scenario",
         {"$schema", "version", "include", "title", "caption", "stores", "terrain", "layers",
          "transferFunctions", "clock", "lenses", "projectiveMappings", "viewpoints", "cameraPaths",
          "camera", "overlays", "lighting", "governor", "briefing"}},
        {"Governor", {"targetFps", "maxTauFactor", "minRenderScale"}},
        {"Terrain",
         {"store", "elevation", "tauGeom", "tauTex", "verticalExaggeration", "reference", "cacheBytes",
          "gpuBytes", "proceduralDetail"}},
        {"Layer",
         {"id", "kind", "source", "transfer", "operation", "enabled", "interpolate", "nodataAs"}},
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
         {"id", "origin", "u", "v", "textureMatrix", "data", "transfer", "colorMatrix", "blend",
          "opacity", "enabled", "keys", "image", "route", "contextMatrix"}},
        {"MappingBlend", {"src", "dst"}},
        {"MappingRoute", {"points", "width", "pointRadius"}},
        {"MappingKey", {"time", "origin", "u", "v", "textureMatrix", "colorMatrix", "opacity"}},
        {"Viewpoint", {"target", "heading", "pitch", "range"}},
        {"CameraPath", {"keys", "interpolation"}},
        {"CameraKey", {"time", "viewpoint", "target", "heading", "pitch", "range"}},
        {"Camera", {"viewpoint", "path", "interactive", "fovY"}},
        {"Overlays", {"legend", "timeLabel", "title", "status", "progress"}},
        {"Legend", {"enabled", "transfer", "position", "title"}},
        {"TimeLabel", {"enabled", "format", "timeZone", "showOffset", "position"}},
        {"SimpleOverlay", {"enabled", "position"}},
        {"Lighting", {"sunAzimuth", "sunAltitude", "ambient", "keys", "solar", "latitude", "longitude"}},
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

// ---------------------------------------------------------------------------------------------
// Reading context: every message goes through here so that each one carries file:line:col.

class Ctx {
public:
    Ctx(const SourceMap& map, Diagnostics& diags) : mMap(map), mDiags(diags) {}

    Diagnostic& error(const char* code, const std::string& ptr, std::string message,
                      bool atKey = false) {
        const Location l = atKey ? mMap.key(ptr) : mMap.value(ptr);
        auto& d = mDiags.error(code, l.file, ptr, std::move(message));
        d.line = l.line;
        d.column = l.column;
        return d;
    }
    Diagnostic& warning(const char* code, const std::string& ptr, std::string message) {
        const Location l = mMap.value(ptr);
        auto& d = mDiags.warning(code, l.file, ptr, std::move(message));
        d.line = l.line;
        d.column = l.column;
        return d;
    }
    void didYouMean(Diagnostic& d, const std::string& word,
                    const std::vector<std::string>& candidates) {
        if (auto m = closestMatch(word, candidates)) d.hint = "did you mean " + quote(*m) + "?";
    }
    /** @brief Relative paths in a file are relative to that file (which may be an include). */
    std::filesystem::path resolve(const std::string& ptr, const std::string& path) const {
        const std::filesystem::path p(path);
        if (p.is_absolute()) return p;
        return (std::filesystem::path(mMap.file(ptr)).parent_path() / p).lexically_normal();
    }
    const SourceMap& map() const { return mMap; }
    Diagnostics& diags() { return mDiags; }

private:
    const SourceMap& mMap;
    Diagnostics& mDiags;
};

struct Range {
    double min = -HUGE_VAL;
    double max = HUGE_VAL;
    bool minOpen = false;
    bool maxOpen = false;

    bool contains(double v) const {
        return (minOpen ? v > min : v >= min) && (maxOpen ? v < max : v <= max);
    }
    std::string text() const {
        const bool lo = std::isfinite(min), hi = std::isfinite(max);
        if (lo && !hi) return std::string(minOpen ? "> " : ">= ") + numberText(min);
        if (!lo && hi) return std::string(maxOpen ? "< " : "<= ") + numberText(max);
        return std::string("in ") + (minOpen ? "(" : "[") + numberText(min) + ", " +
               numberText(max) + (maxOpen ? ")" : "]");
    }
};
const Range kAny{};
const Range kPositive{0, HUGE_VAL, true, false};
const Range kNonNegative{0, HUGE_VAL, false, false};
const Range kUnit{0, 1, false, false};

template <class E>
using EnumTable = std::vector<std::pair<std::string, E>>;

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

template <std::size_t N>
std::optional<std::array<double, N>> readNumbers(Ctx& c, const json& j, const std::string& ptr) {
    const std::string expect = "expected an array of " + std::to_string(N) + " numbers";
    if (!j.is_array() || j.size() != N) {
        c.error("SCENARIO_TYPE", ptr,
                expect + ", got " +
                    (j.is_array() ? "an array of " + std::to_string(j.size()) : typeName(j)));
        return std::nullopt;
    }
    std::array<double, N> out{};
    for (std::size_t i = 0; i < N; ++i) {
        if (!j[i].is_number() || !std::isfinite(j[i].get<double>())) {
            c.error("SCENARIO_TYPE", childPointer(ptr, i),
                    "expected number, got " + typeName(j[i]));
            return std::nullopt;
        }
        out[i] = j[i].get<double>();
    }
    return out;
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

// One JSON object of a known kind: unknown members are reported on construction (with a
// did-you-mean hint), then typed getters report missing members, wrong types and ranges.
class Obj {
public:
    Obj(Ctx& c, const json& j, std::string ptr, const char* kind)
        : mC(c), mJ(j), mPtr(std::move(ptr)), mKeys(propertyTable().at(kind)) {
        if (!j.is_object()) {
            mC.error("SCENARIO_TYPE", mPtr, "expected object, got " + typeName(j));
            mValid = false;
            return;
        }
        for (auto it = j.begin(); it != j.end(); ++it) {
            if (std::find(mKeys.begin(), mKeys.end(), it.key()) != mKeys.end()) continue;
            auto& e = mC.error("SCENARIO_UNKNOWN_PROPERTY", childPointer(mPtr, it.key()),
                               "unknown property " + quote(it.key()), true);
            mC.didYouMean(e, it.key(), mKeys);
        }
    }

    bool valid() const { return mValid; }
    const std::string& ptr() const { return mPtr; }
    std::string at(const std::string& key) const { return childPointer(mPtr, key); }

    const json* get(const std::string& key, bool required = false) const {
        KIOSK_ASSERT(std::find(mKeys.begin(), mKeys.end(), key) != mKeys.end());
        if (!mValid) return nullptr;
        auto it = mJ.find(key);
        if (it == mJ.end()) {
            if (required)
                mC.error("SCENARIO_MISSING", mPtr, "missing required property " + quote(key));
            return nullptr;
        }
        return &*it;
    }
    bool has(const std::string& key) const { return mValid && mJ.contains(key); }

    std::optional<std::string> str(const std::string& key, bool required = false) const {
        const json* j = get(key, required);
        if (!j) return std::nullopt;
        if (!j->is_string()) {
            mC.error("SCENARIO_TYPE", at(key), "expected string, got " + typeName(*j));
            return std::nullopt;
        }
        return j->get<std::string>();
    }
    /** @brief A non-empty identifier-like string. */
    std::optional<std::string> name(const std::string& key, bool required = false) const {
        auto s = str(key, required);
        if (s && s->empty()) {
            mC.error("SCENARIO_BAD_VALUE", at(key), quote(key) + " must not be empty");
            return std::nullopt;
        }
        return s;
    }
    std::optional<double> num(const std::string& key, const Range& r = kAny,
                              bool required = false) const {
        const json* j = get(key, required);
        return j ? readNumber(mC, *j, at(key), r, key) : std::nullopt;
    }
    std::optional<bool> boolean(const std::string& key) const {
        const json* j = get(key);
        if (!j) return std::nullopt;
        if (!j->is_boolean()) {
            mC.error("SCENARIO_TYPE", at(key), "expected boolean, got " + typeName(*j));
            return std::nullopt;
        }
        return j->get<bool>();
    }
    template <class E>
    std::optional<E> oneOf(const std::string& key, const EnumTable<E>& values,
                           bool required = false) const {
        const json* j = get(key, required);
        return j ? enumValue(*j, at(key), key, values) : std::nullopt;
    }
    template <class E>
    std::optional<E> enumValue(const json& j, const std::string& ptr, const std::string& key,
                               const EnumTable<E>& values) const {
        std::vector<std::string> names;
        for (const auto& v : values) names.push_back(v.first);
        if (!j.is_string()) {
            mC.error("SCENARIO_TYPE", ptr,
                     "expected one of " + joined(names) + ", got " + typeName(j));
            return std::nullopt;
        }
        const std::string s = j.get<std::string>();
        for (const auto& v : values)
            if (v.first == s) return v.second;
        auto& e =
            mC.error("SCENARIO_BAD_VALUE", ptr,
                     "unknown " + key + " " + quote(s) + "; expected one of " + joined(names));
        mC.didYouMean(e, s, names);
        return std::nullopt;
    }
    template <std::size_t N>
    std::optional<std::array<double, N>> numbers(const std::string& key,
                                                 bool required = false) const {
        const json* j = get(key, required);
        return j ? readNumbers<N>(mC, *j, at(key)) : std::nullopt;
    }
    std::optional<color::Rgba> color(const std::string& key, bool required = false) const {
        const json* j = get(key, required);
        return j ? readColor(mC, *j, at(key)) : std::nullopt;
    }
    const json* array(const std::string& key, bool required = false) const {
        const json* j = get(key, required);
        if (j && !j->is_array()) {
            mC.error("SCENARIO_TYPE", at(key), "expected array, got " + typeName(*j));
            return nullptr;
        }
        return j;
    }
    const json* object(const std::string& key, bool required = false) const {
        const json* j = get(key, required);
        if (j && !j->is_object()) {
            mC.error("SCENARIO_TYPE", at(key), "expected object, got " + typeName(*j));
            return nullptr;
        }
        return j;
    }
    std::optional<TimeSpec> time(const std::string& key, bool required = false) const {
        const json* j = get(key, required);
        return j ? readTimeSpec(mC, *j, at(key)) : std::nullopt;
    }

private:
    Ctx& mC;
    const json& mJ;
    std::string mPtr;
    const std::vector<std::string>& mKeys;
    bool mValid = true;
};

template <class T>
void assign(T& dst, const std::optional<T>& v) {
    if (v) dst = *v;
}

// ---------------------------------------------------------------------------------------------
// Enumerations as they are spelled in JSON.

const EnumTable<LayerKind> kLayerKinds = {{"thematic", LayerKind::Thematic},
                                          {"luminance", LayerKind::Luminance},
                                          {"topographic", LayerKind::Topographic},
                                          {"visibility", LayerKind::Visibility},
                                          {"data", LayerKind::Data},
                                          {"sequence", LayerKind::Sequence},
                                          {"normals", LayerKind::Normals}};
const EnumTable<OperationType> kOperations = {
    {"opacity", OperationType::Opacity}, {"blend", OperationType::Blend},
    {"add", OperationType::Add},         {"modulate", OperationType::Modulate},
    {"mask", OperationType::Mask},       {"replace", OperationType::Replace}};
const EnumTable<TerrainReference> kTerrainReferences = {{"lod", TerrainReference::Lod},
                                                        {"full", TerrainReference::Full}};
const EnumTable<SequenceInterpolation> kInterpolations = {
    {"data", SequenceInterpolation::Data},
    {"none", SequenceInterpolation::None},
    {"arrival", SequenceInterpolation::Arrival}};
const EnumTable<color::Space> kSpaces = {{"srgb", color::Space::Srgb},
                                         {"linear", color::Space::Linear},
                                         {"lab", color::Space::Lab},
                                         {"msh", color::Space::Msh}};
const EnumTable<RangeBehaviour> kRanges = {{"loop", RangeBehaviour::Loop},
                                           {"clamp", RangeBehaviour::Clamp},
                                           {"unbounded", RangeBehaviour::Unbounded}};
const EnumTable<LensKind> kLensKinds = {{"highlight", LensKind::Highlight},
                                        {"visibility", LensKind::Visibility}};
const EnumTable<LensShape> kLensShapes = {{"circle", LensShape::Circle},
                                          {"ellipse", LensShape::Ellipse}};
const EnumTable<BlendFactor> kBlendFactors = {
    {"zero", BlendFactor::Zero},         {"one", BlendFactor::One},
    {"srcColor", BlendFactor::SrcColor}, {"oneMinusSrcColor", BlendFactor::OneMinusSrcColor},
    {"dstColor", BlendFactor::DstColor}, {"oneMinusDstColor", BlendFactor::OneMinusDstColor},
    {"srcAlpha", BlendFactor::SrcAlpha}, {"oneMinusSrcAlpha", BlendFactor::OneMinusSrcAlpha},
    {"dstAlpha", BlendFactor::DstAlpha}, {"oneMinusDstAlpha", BlendFactor::OneMinusDstAlpha}};
const EnumTable<CameraInterpolation> kCameraInterpolations = {
    {"smooth", CameraInterpolation::Smooth},
    {"linear", CameraInterpolation::Linear},
    {"step", CameraInterpolation::Step}};
const EnumTable<Corner> kCorners = {{"top-left", Corner::TopLeft},
                                    {"top-right", Corner::TopRight},
                                    {"bottom-left", Corner::BottomLeft},
                                    {"bottom-right", Corner::BottomRight},
                                    {"top", Corner::Top},
                                    {"bottom", Corner::Bottom}};

// ---------------------------------------------------------------------------------------------
// Sections.

class Reader {
public:
    Reader(Ctx& c, Scenario& s) : mC(c), mS(s) {}

    void root(const json& doc) {
        Obj o(mC, doc, "", "Scenario");
        if (!o.valid()) return;
        if (const json* v = o.get("version", true)) {
            if (!v->is_number_integer() && !v->is_number_unsigned()) {
                mC.error("SCENARIO_TYPE", "/version", "expected integer, got " + typeName(*v));
            } else if (v->get<std::int64_t>() != kScenarioVersion) {
                mC.error("SCENARIO_VERSION", "/version",
                         "unsupported version " + v->dump() + " (this geokiosk reads version " +
                             std::to_string(kScenarioVersion) + ")");
                return;  // a different version's other properties would only add noise
            } else {
                mS.version = kScenarioVersion;
            }
        }
        o.str("$schema");
        assign(mS.title, o.str("title"));
        assign(mS.caption, o.str("caption"));
        if (const json* j = o.object("stores", true)) {
            stores(*j);
            mStoresGiven = true;
        }
        if (const json* j = o.object("transferFunctions")) transferFunctions(*j);
        if (const json* j = o.get("terrain", true)) terrain(*j);
        if (const json* j = o.object("clock")) clock(*j);
        if (const json* j = o.array("layers", true)) layers(*j);
        if (const json* j = o.array("lenses")) lenses(*j);
        if (const json* j = o.array("projectiveMappings")) mappings(*j);
        if (const json* j = o.object("viewpoints")) viewpoints(*j);
        if (const json* j = o.object("cameraPaths")) cameraPaths(*j);
        if (const json* j = o.get("camera")) camera(*j);
        if (const json* j = o.get("overlays")) overlays(*j);
        if (const json* j = o.get("lighting")) lighting(*j);
        if (const json* j = o.get("governor")) governor(*j);
        crossReferences();
    }

private:
    void stores(const json& j) {
        if (j.empty()) mC.error("SCENARIO_MISSING", "/stores", "declare at least one store");
        for (auto it = j.begin(); it != j.end(); ++it) {
            const std::string ptr = childPointer("/stores", it.key());
            if (!it->is_string() || it->get<std::string>().empty()) {
                mC.error("SCENARIO_TYPE", ptr,
                         "expected a store file path (string), got " + typeName(*it));
                continue;
            }
            mS.stores[it.key()] = StoreRef{it.key(), mC.resolve(ptr, it->get<std::string>()), ptr};
        }
    }

    void terrain(const json& j) {
        Obj o(mC, j, "/terrain", "Terrain");
        if (!o.valid()) return;
        Terrain& t = mS.terrain;
        assign(t.store, o.name("store", true));
        assign(t.elevation, o.name("elevation"));
        const Range tau{0, 64, true, false};
        assign(t.tauGeom, o.num("tauGeom", tau));
        assign(t.tauTex, o.num("tauTex", tau));
        assign(t.verticalExaggeration, o.num("verticalExaggeration", Range{0, 100, true, false}));
        assign(t.reference, o.oneOf("reference", kTerrainReferences));
        if (const json* b = o.get("cacheBytes"))
            assign(t.cacheBytes, readBytes(mC, *b, o.at("cacheBytes")));
        if (const json* b = o.get("gpuBytes"))
            assign(t.gpuBytes, readBytes(mC, *b, o.at("gpuBytes")));
        assign(t.proceduralDetail, o.boolean("proceduralDetail"));
    }

    std::optional<SourceRef> source(const json& j, const std::string& ptr) {
        Obj o(mC, j, ptr, "Source");
        if (!o.valid()) return std::nullopt;
        SourceRef s;
        assign(s.store, o.name("store", true));
        assign(s.layer, o.name("layer"));
        assign(s.sequence, o.name("sequence"));
        if (!s.layer.empty() && !s.sequence.empty())
            mC.error("SCENARIO_CONFLICT", ptr, "give either \"layer\" or \"sequence\", not both");
        return s;
    }

    void layers(const json& arr) {
        for (std::size_t i = 0; i < arr.size(); ++i) {
            const std::string ptr = childPointer("/layers", i);
            Obj o(mC, arr[i], ptr, "Layer");
            if (!o.valid()) continue;
            Layer l;
            l.pointer = ptr;
            assign(l.id, o.name("id", true));
            auto kind = o.oneOf("kind", kLayerKinds, true);
            assign(l.kind, kind);
            if (const json* s = o.get("source")) assign(l.source, source(*s, o.at("source")));
            assign(l.transfer, o.name("transfer"));
            assign(l.enabled, o.boolean("enabled"));
            if (const json* op = o.get("operation")) {
                if (op->is_string()) {
                    assign(l.operation.type, o.oneOf("operation", kOperations));
                } else {
                    Obj oo(mC, *op, o.at("operation"), "Operation");
                    if (oo.valid()) {
                        assign(l.operation.type, oo.oneOf("type", kOperations, true));
                        assign(l.operation.weight, oo.num("weight", Range{0, 16}));
                        assign(l.operation.opacity, oo.num("opacity", kUnit));
                        assign(l.operation.visibility, oo.name("visibility"));
                    }
                }
            }
            assign(l.interpolate, o.oneOf("interpolate", kInterpolations));
            if (auto v = o.num("nodataAs")) l.nodataAs = v;
            if (kind) {
                const bool isSeq = *kind == LayerKind::Sequence;
                if (!isSeq && (o.has("interpolate") || o.has("nodataAs")))
                    mC.error("SCENARIO_CONFLICT", ptr,
                             "\"interpolate\" and \"nodataAs\" apply to sequence layers only");
                if (!o.has("source") && *kind != LayerKind::Topographic)
                    mC.error("SCENARIO_MISSING", ptr, "missing required property \"source\"");
                if (o.has("source") && isSeq && l.source.sequence.empty())
                    mC.error("SCENARIO_MISSING", o.at("source"),
                             "a sequence layer needs \"sequence\" (the store's sequence name)");
                if (o.has("source") && !isSeq && l.source.layer.empty() && !l.source.store.empty())
                    mC.error("SCENARIO_MISSING", o.at("source"),
                             "missing required property \"layer\"");
                const bool needsTransfer = isSeq || *kind == LayerKind::Data;
                if (needsTransfer && l.transfer.empty() && !o.has("transfer"))
                    mC.error("SCENARIO_MISSING", ptr,
                             std::string("a ") + layerKindName(*kind) +
                                 " layer needs \"transfer\" (a transfer function name)");
            }
            if (l.operation.type == OperationType::Blend && l.operation.visibility.empty())
                mC.error("SCENARIO_MISSING", o.at("operation"),
                         "a blend operation needs \"visibility\" (a visibility layer id)");
            mS.layers.push_back(std::move(l));
        }
    }

    void transferFunctions(const json& j) {
        for (auto it = j.begin(); it != j.end(); ++it) {
            const std::string ptr = childPointer("/transferFunctions", it.key());
            if (auto def = transfer(*it, ptr, it.key())) mS.transferFunctions[it.key()] = *def;
        }
    }

    void reemit(const Diagnostics& d, const std::string& ptr, const std::string& prefix) {
        for (const auto& item : d.items()) {
            std::string msg = prefix + item.message;
            if (item.line > 0) msg = "line " + std::to_string(item.line) + ": " + msg;
            Diagnostic& e = item.severity == Severity::Error
                                ? mC.error(item.code.c_str(), ptr, msg)
                                : mC.warning(item.code.c_str(), ptr, msg);
            e.hint = item.hint;
        }
    }

    std::optional<TransferFunctionDef> transfer(const json& j, const std::string& ptr,
                                                const std::string& name) {
        Obj o(mC, j, ptr, "TransferFunction");
        if (!o.valid()) return std::nullopt;
        TransferFunctionDef def;
        def.name = name;
        def.pointer = ptr;
        assign(def.label, o.str("label"));
        const std::vector<std::string> sources = {"stops",    "classes", "preset",
                                                  "paraview", "gdal",    "file"};
        std::vector<std::string> given;
        for (const auto& s : sources)
            if (o.has(s)) given.push_back(s);
        if (given.empty()) {
            mC.error(
                "SCENARIO_MISSING", ptr,
                "transfer function " + quote(name) +
                    " needs one of \"stops\", \"classes\", \"preset\", \"paraview\", \"gdal\" or "
                    "\"file\"");
            return std::nullopt;
        }
        if (given.size() > 1) {
            mC.error("SCENARIO_CONFLICT", ptr,
                     "transfer function " + quote(name) + " has both " + quote(given[0]) + " and " +
                         quote(given[1]) + "; give exactly one");
            return std::nullopt;
        }
        std::optional<std::pair<double, double>> domain;
        if (auto d = o.numbers<2>("domain")) {
            if (!((*d)[0] < (*d)[1]))
                mC.error("SCENARIO_RANGE", o.at("domain"),
                         "domain must be [min, max] with min < max");
            else
                domain = std::pair{(*d)[0], (*d)[1]};
        } else if (o.has("domain")) {
            return std::nullopt;
        }
        const std::size_t errorsBefore = errorCount();
        color::TransferFunction& tf = def.function;
        const std::string& source = given[0];
        if (source == "stops") {
            def.origin = TransferFunctionDef::Origin::Stops;
            const json* arr = o.array("stops");
            if (!arr) return std::nullopt;
            if (arr->size() < 2)
                mC.error("SCENARIO_RANGE", o.at("stops"),
                         "a transfer function needs at least two stops");
            std::optional<double> last;
            for (std::size_t i = 0; i < arr->size(); ++i) {
                Obj s(mC, (*arr)[i], childPointer(o.at("stops"), i), "Stop");
                auto v = s.num("value", kAny, true);
                auto c = s.color("color", true);
                if (v && c) tf.stops.push_back({*v, *c});
                if (v && last && *last > *v)
                    mC.error("SCENARIO_RANGE", s.at("value"),
                             "stops must be in increasing value order (" + numberText(*v) +
                                 " after " + numberText(*last) + ")");
                if (v) last = v;
            }
        } else if (source == "classes") {
            def.origin = TransferFunctionDef::Origin::Classes;
            const json* arr = o.array("classes");
            if (!arr) return std::nullopt;
            if (arr->empty())
                mC.error("SCENARIO_RANGE", o.at("classes"), "give at least one class");
            std::optional<double> last;
            for (std::size_t i = 0; i < arr->size(); ++i) {
                Obj s(mC, (*arr)[i], childPointer(o.at("classes"), i), "ClassBreak");
                auto v = s.num("from", kAny, true);
                auto c = s.color("color", true);
                auto label = s.str("label");
                if (v && c) tf.classes.push_back({*v, *c, label.value_or("")});
                if (v && last && *last >= *v)
                    mC.error("SCENARIO_RANGE", s.at("from"),
                             "classes must be in strictly increasing \"from\" order");
                if (v) last = v;
            }
        } else if (source == "preset") {
            def.origin = TransferFunctionDef::Origin::Preset;
            auto p = o.str("preset");
            if (!p) return std::nullopt;
            auto m = color::namedMap(*p);
            if (!m) {
                auto& e = mC.error("SCENARIO_UNKNOWN_REFERENCE", o.at("preset"),
                                   "unknown preset " + quote(*p) + "; built-in maps are " +
                                       joined(color::namedMapNames()));
                mC.didYouMean(e, *p, color::namedMapNames());
                return std::nullopt;
            }
            tf = *m;
            if (domain) tf = tf.rescaled(domain->first, domain->second);
        } else if (source == "paraview") {
            def.origin = TransferFunctionDef::Origin::ParaView;
            const json* pj = o.get("paraview");
            Obj pv(mC, *pj, o.at("paraview"), "ParaViewRef");
            auto file = pv.name("file", true);
            auto preset = pv.name("name", true);
            if (!file || !preset) return std::nullopt;
            def.file = mC.resolve(pv.at("file"), *file);
            if (!fileExists(def.file, pv.at("file"))) return std::nullopt;
            auto r = color::importParaViewFile(def.file, *preset);
            reemit(r.diagnostics, o.at("paraview"), def.file.filename().string() + ": ");
            if (!r) return std::nullopt;
            tf = *r.value;
            if (domain) tf = tf.rescaled(domain->first, domain->second);
        } else {
            // "gdal" names gdaldem / GRASS colour rules, "file" any colour-map file; both read
            // the format from extension and content (a .cpt under "gdal" is read as GMT too).
            def.origin = source == "gdal" ? TransferFunctionDef::Origin::Gdal
                                          : TransferFunctionDef::Origin::File;
            auto file = o.name(source);
            if (!file) return std::nullopt;
            def.file = mC.resolve(o.at(source), *file);
            if (!fileExists(def.file, o.at(source))) return std::nullopt;
            color::ColorFileFormat format{};
            auto r = color::importColorMapFile(def.file, domain, &format);
            reemit(r.diagnostics, o.at(source), def.file.filename().string() + ": ");
            if (!r) return std::nullopt;
            tf = *r.value;
            // Maps without data units (float lists, ParaView) are rescaled like presets.
            if (domain && !color::hasDataUnits(format))
                tf = tf.rescaled(domain->first, domain->second);
        }
        if (def.origin == TransferFunctionDef::Origin::ParaView ||
            def.origin == TransferFunctionDef::Origin::Gdal ||
            def.origin == TransferFunctionDef::Origin::File)
            mFiles.push_back(def.file);

        tf.name = name;
        assign(tf.units, o.str("units"));
        assign(tf.space, o.oneOf("space", kSpaces));
        const auto nodata = o.color("nodata"), below = o.color("below"), above = o.color("above");
        assign(tf.nodata, nodata);
        assign(tf.below, below);
        assign(tf.above, above);
        if (const json* arr = o.array("opacity")) {
            tf.opacity.clear();
            for (std::size_t i = 0; i < arr->size(); ++i) {
                Obj p(mC, (*arr)[i], childPointer(o.at("opacity"), i), "OpacityPoint");
                auto v = p.num("value", kAny, true);
                auto a = p.num("opacity", kUnit, true);
                if (v && a) tf.opacity.push_back({*v, *a});
            }
        }
        if (domain) {
            tf.domainMin = domain->first;
            tf.domainMax = domain->second;
            def.explicitDomain = true;
        }
        // Only finalize what was read cleanly; errors above already explain the rest.
        if (errorCount() != errorsBefore) return std::nullopt;
        Diagnostics fin = tf.finalize(def.explicitDomain, below.has_value(), above.has_value());
        if (fin.hasErrors()) {
            reemit(fin, ptr, "");
            return std::nullopt;
        }
        return def;
    }

    std::size_t errorCount() const {
        std::size_t n = 0;
        for (const auto& d : mC.diags().items())
            if (d.severity == Severity::Error) ++n;
        return n;
    }

    bool fileExists(const std::filesystem::path& file, const std::string& ptr) {
        std::error_code ec;
        if (std::filesystem::is_regular_file(file, ec)) return true;
        mC.error(
            "SCENARIO_FILE", ptr,
            "file " + quote(file.string()) +
                (std::filesystem::exists(file, ec) ? " is not a regular file" : " does not exist"));
        return false;
    }

    void clock(const json& j) {
        Obj o(mC, j, "/clock", "Clock");
        if (!o.valid()) return;
        Clock c;
        std::optional<double> start, end;
        if (const json* s = o.get("start", true)) start = readInstant(mC, *s, o.at("start"));
        assign(c.range, o.oneOf("range", kRanges));
        if (const json* e = o.get("end", c.range != RangeBehaviour::Unbounded))
            end = readInstant(mC, *e, o.at("end"));
        assign(c.rate, o.num("rate", Range{-1e9, 1e9}));
        assign(c.paused, o.boolean("paused"));
        assign(c.waitForData, o.boolean("waitForData"));
        if (start && end && !(*start < *end))
            mC.error("SCENARIO_RANGE", o.at("end"), "clock end must be after its start");
        if (!start || (c.range != RangeBehaviour::Unbounded && !end)) return;
        c.start = *start;
        c.end = end.value_or(*start);
        mS.clock = c;
    }

    void lenses(const json& arr) {
        for (std::size_t i = 0; i < arr.size(); ++i) {
            const std::string ptr = childPointer("/lenses", i);
            Obj o(mC, arr[i], ptr, "Lens");
            if (!o.valid()) continue;
            Lens l;
            l.pointer = ptr;
            assign(l.id, o.name("id", true));
            assign(l.kind, o.oneOf("kind", kLensKinds, true));
            auto shape = o.oneOf("shape", kLensShapes);
            assign(l.center, o.numbers<2>("center", true));
            auto radius = o.num("radius", kPositive);
            auto radii = o.numbers<2>("radii");
            if (radii && !((*radii)[0] > 0 && (*radii)[1] > 0)) {
                mC.error("SCENARIO_RANGE", o.at("radii"), "radii must be > 0");
                radii.reset();
            }
            l.shape = shape.value_or(o.has("radii") ? LensShape::Ellipse : LensShape::Circle);
            if (o.has("radius") && o.has("radii"))
                mC.error("SCENARIO_CONFLICT", ptr,
                         "give \"radius\" (circle) or \"radii\" (ellipse), not both");
            else if (l.shape == LensShape::Circle && !o.has("radius"))
                mC.error("SCENARIO_MISSING", ptr, "a circular lens needs \"radius\"");
            else if (l.shape == LensShape::Ellipse && !o.has("radii"))
                mC.error("SCENARIO_MISSING", ptr, "an elliptical lens needs \"radii\"");
            if (radius) l.radii = {*radius, *radius};
            if (radii) l.radii = *radii;
            assign(l.rotation, o.num("rotation", Range{-360, 360}));
            assign(l.softEdge, o.num("softEdge", kNonNegative));
            assign(l.raise, o.num("raise", kUnit));
            assign(l.lower, o.num("lower", kUnit));
            assign(l.inside, o.name("inside"));
            assign(l.outside, o.name("outside"));
            assign(l.enabled, o.boolean("enabled"));
            if (l.kind == LensKind::Visibility && l.inside.empty() && l.outside.empty() &&
                !o.has("inside") && !o.has("outside"))
                mC.error("SCENARIO_MISSING", ptr,
                         "a visibility lens needs \"inside\" and/or \"outside\" (layer ids)");
            if (const json* keys = o.array("keys")) {
                for (std::size_t k = 0; k < keys->size(); ++k) {
                    Obj ko(mC, (*keys)[k], childPointer(o.at("keys"), k), "LensKey");
                    if (!ko.valid()) continue;
                    LensKey key;
                    key.pointer = ko.ptr();
                    assign(key.time, ko.time("time", true));
                    key.center = ko.numbers<2>("center");
                    if (auto r = ko.num("radius", kPositive)) key.radii = Vec2{*r, *r};
                    if (auto r = ko.numbers<2>("radii")) key.radii = r;
                    key.rotation = ko.num("rotation", Range{-360, 360});
                    l.keys.push_back(key);
                }
                keyOrder(l.keys, o.at("keys"));
            }
            mS.lenses.push_back(std::move(l));
        }
    }

    void mappings(const json& arr) {
        for (std::size_t i = 0; i < arr.size(); ++i) {
            const std::string ptr = childPointer("/projectiveMappings", i);
            Obj o(mC, arr[i], ptr, "ProjectiveMapping");
            if (!o.valid()) continue;
            ProjectiveMapping m;
            m.pointer = ptr;
            assign(m.id, o.name("id", true));
            // A route brings its own geometry; an image or a route its own data layer.
            const bool routed = o.has("route");
            assign(m.origin, o.numbers<3>("origin", !routed));
            assign(m.u, o.numbers<3>("u", !routed));
            assign(m.v, o.numbers<3>("v", !routed));
            assign(m.textureMatrix, o.numbers<9>("textureMatrix"));
            if (auto img = o.str("image")) {
                m.image = mC.resolve(o.at("image"), *img);
                fileExists(m.image, o.at("image"));
            }
            if (const json* r = o.object("route")) m.route = route(*r, o.at("route"));
            m.contextMatrix = o.numbers<16>("contextMatrix");
            if (const json* d = o.get("data", !routed && !o.has("image")))
                assign(m.data, source(*d, o.at("data")));
            assign(m.transfer, o.name("transfer"));
            assign(m.colorMatrix, o.numbers<16>("colorMatrix"));
            if (const json* b = o.get("blend")) {
                Obj bo(mC, *b, o.at("blend"), "MappingBlend");
                assign(m.src, bo.oneOf("src", kBlendFactors));
                assign(m.dst, bo.oneOf("dst", kBlendFactors));
            }
            assign(m.opacity, o.num("opacity", kUnit));
            assign(m.enabled, o.boolean("enabled"));
            const Vec3 &u = m.u, &v = m.v;
            const Vec3 cross{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                             u[0] * v[1] - u[1] * v[0]};
            if (o.has("u") && o.has("v") &&
                std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]) <= 0)
                mC.error("SCENARIO_RANGE", o.at("v"), "u and v must be non-zero and not parallel");
            if (const json* keys = o.array("keys")) {
                for (std::size_t k = 0; k < keys->size(); ++k) {
                    Obj ko(mC, (*keys)[k], childPointer(o.at("keys"), k), "MappingKey");
                    if (!ko.valid()) continue;
                    MappingKey key;
                    key.pointer = ko.ptr();
                    assign(key.time, ko.time("time", true));
                    key.origin = ko.numbers<3>("origin");
                    key.u = ko.numbers<3>("u");
                    key.v = ko.numbers<3>("v");
                    key.textureMatrix = ko.numbers<9>("textureMatrix");
                    key.colorMatrix = ko.numbers<16>("colorMatrix");
                    key.opacity = ko.num("opacity", kUnit);
                    m.keys.push_back(key);
                }
                keyOrder(m.keys, o.at("keys"));
            }
            mS.projectiveMappings.push_back(std::move(m));
        }
    }

    MappingRoute route(const json& j, const std::string& ptr) {
        MappingRoute r;
        r.pointer = ptr;
        Obj o(mC, j, ptr, "MappingRoute");
        if (!o.valid()) return r;
        if (const json* pts = o.array("points", true)) {
            for (std::size_t i = 0; i < pts->size(); ++i)
                if (auto p = readNumbers<2>(mC, (*pts)[i], childPointer(o.at("points"), i)))
                    r.points.push_back(*p);
            if (pts->size() < 2)
                mC.error("SCENARIO_RANGE", o.at("points"), "a route needs at least 2 way points");
        }
        assign(r.width, o.num("width", Range{0, 1e6, true, false}));
        assign(r.pointRadius, o.num("pointRadius", Range{0, 1e6, false, false}));
        return r;
    }

    std::optional<Viewpoint> viewpoint(const Obj& o, bool targetRequired) {
        Viewpoint v;
        v.pointer = o.ptr();
        assign(v.target, o.numbers<3>("target", targetRequired));
        assign(v.heading, o.num("heading", Range{-360, 360}));
        assign(v.pitch, o.num("pitch", Range{-90, 90}));
        assign(v.range, o.num("range", kPositive));
        return v;
    }

    void viewpoints(const json& j) {
        for (auto it = j.begin(); it != j.end(); ++it) {
            Obj o(mC, *it, childPointer("/viewpoints", it.key()), "Viewpoint");
            if (!o.valid()) continue;
            if (auto v = viewpoint(o, true)) mS.viewpoints[it.key()] = *v;
        }
    }

    void cameraPaths(const json& j) {
        for (auto it = j.begin(); it != j.end(); ++it) {
            const std::string ptr = childPointer("/cameraPaths", it.key());
            Obj o(mC, *it, ptr, "CameraPath");
            if (!o.valid()) continue;
            CameraPath path;
            path.pointer = ptr;
            assign(path.interpolation, o.oneOf("interpolation", kCameraInterpolations));
            if (const json* keys = o.array("keys", true)) {
                if (keys->empty())
                    mC.error("SCENARIO_RANGE", o.at("keys"), "give at least one key");
                for (std::size_t k = 0; k < keys->size(); ++k) {
                    Obj ko(mC, (*keys)[k], childPointer(o.at("keys"), k), "CameraKey");
                    if (!ko.valid()) continue;
                    CameraKey key;
                    key.pointer = ko.ptr();
                    assign(key.time, ko.time("time", true));
                    assign(key.viewpoint, ko.name("viewpoint"));
                    const bool inlineView =
                        ko.has("target") || ko.has("heading") || ko.has("pitch") || ko.has("range");
                    if (ko.has("viewpoint") && inlineView)
                        mC.error("SCENARIO_CONFLICT", key.pointer,
                                 "give \"viewpoint\" (a name) or an inline view, not both");
                    else if (!ko.has("viewpoint") && !ko.has("target"))
                        mC.error("SCENARIO_MISSING", key.pointer,
                                 "a camera key needs \"viewpoint\" or \"target\"");
                    if (inlineView) assign(key.view, viewpoint(ko, false));
                    path.keys.push_back(key);
                }
                keyOrder(path.keys, o.at("keys"));
            }
            mS.cameraPaths[it.key()] = std::move(path);
        }
    }

    void camera(const json& j) {
        Obj o(mC, j, "/camera", "Camera");
        if (!o.valid()) return;
        assign(mS.camera.viewpoint, o.name("viewpoint"));
        assign(mS.camera.path, o.name("path"));
        assign(mS.camera.interactive, o.boolean("interactive"));
        assign(mS.camera.fovY, o.num("fovY", Range{1, 170}));
    }

    void simpleOverlay(const json& j, const std::string& ptr, SimpleOverlay& out) {
        Obj o(mC, j, ptr, "SimpleOverlay");
        if (!o.valid()) return;
        out.enabled = o.boolean("enabled").value_or(true);
        assign(out.position, o.oneOf("position", kCorners));
    }

    void overlays(const json& j) {
        Obj o(mC, j, "/overlays", "Overlays");
        if (!o.valid()) return;
        Overlays& ov = mS.overlays;
        if (const json* l = o.get("legend")) {
            Obj lo(mC, *l, o.at("legend"), "Legend");
            if (lo.valid()) {
                ov.legend.enabled = lo.boolean("enabled").value_or(true);
                assign(ov.legend.transfer, lo.name("transfer"));
                assign(ov.legend.position, lo.oneOf("position", kCorners));
                assign(ov.legend.title, lo.str("title"));
            }
        }
        if (const json* t = o.get("timeLabel")) {
            Obj to(mC, *t, o.at("timeLabel"), "TimeLabel");
            if (to.valid()) {
                auto& tl = ov.timeLabel;
                tl.enabled = to.boolean("enabled").value_or(true);
                assign(tl.format, to.str("format"));
                if (auto tz = to.str("timeZone")) {
                    if (auto minutes = parseZone(*tz)) {
                        tl.timeZone = *tz;
                        tl.utcOffsetMinutes = *minutes;
                    } else {
                        mC.error("SCENARIO_BAD_VALUE", to.at("timeZone"),
                                 "time zone " + quote(*tz) +
                                     " is not supported; use \"UTC\" or an offset like \"+01:00\"");
                    }
                }
                assign(tl.showOffset, to.boolean("showOffset"));
                assign(tl.position, to.oneOf("position", kCorners));
            }
        }
        if (const json* t = o.get("title")) simpleOverlay(*t, o.at("title"), ov.title);
        if (const json* t = o.get("status")) simpleOverlay(*t, o.at("status"), ov.status);
        if (const json* t = o.get("progress")) simpleOverlay(*t, o.at("progress"), ov.progress);
    }

    static std::optional<int> parseZone(const std::string& tz) {
        if (tz == "UTC" || tz == "Z") return 0;
        if (tz.size() != 3 && tz.size() != 6) return std::nullopt;
        if (tz[0] != '+' && tz[0] != '-') return std::nullopt;
        auto digit = [&](std::size_t i) {
            return std::isdigit(static_cast<unsigned char>(tz[i])) != 0;
        };
        if (!digit(1) || !digit(2)) return std::nullopt;
        int minutes = 0;
        if (tz.size() == 6) {
            if (tz[3] != ':' || !digit(4) || !digit(5)) return std::nullopt;
            minutes = (tz[4] - '0') * 10 + (tz[5] - '0');
        }
        const int hours = (tz[1] - '0') * 10 + (tz[2] - '0');
        if (hours > 14 || minutes > 59) return std::nullopt;
        return (tz[0] == '-' ? -1 : 1) * (hours * 60 + minutes);
    }

    void governor(const json& j) {
        Obj o(mC, j, "/governor", "Governor");
        if (!o.valid()) return;
        Governor& g = mS.governor;
        assign(g.targetFps, o.num("targetFps", Range{0, 240}));
        assign(g.maxTauFactor, o.num("maxTauFactor", Range{1, 16}));
        assign(g.minRenderScale, o.num("minRenderScale", Range{0.25, 1}));
    }

    void lighting(const json& j) {
        Obj o(mC, j, "/lighting", "Lighting");
        if (!o.valid()) return;
        Lighting& l = mS.lighting;
        const Range azimuth{0, 360}, altitude{-90, 90};
        assign(l.sunAzimuth, o.num("sunAzimuth", azimuth));
        assign(l.sunAltitude, o.num("sunAltitude", altitude));
        assign(l.ambient, o.num("ambient", kUnit));
        assign(l.solar, o.boolean("solar"));
        if (auto v = o.num("latitude", Range{-90, 90})) l.latitude = v;
        if (auto v = o.num("longitude", Range{-180, 180})) l.longitude = v;
        if (l.latitude.has_value() != l.longitude.has_value())
            mC.error("SCENARIO_MISSING", o.at(l.latitude ? "latitude" : "longitude"),
                     "\"latitude\" and \"longitude\" go together");
        if (const json* keys = o.array("keys")) {
            for (std::size_t k = 0; k < keys->size(); ++k) {
                Obj ko(mC, (*keys)[k], childPointer(o.at("keys"), k), "LightingKey");
                if (!ko.valid()) continue;
                LightingKey key;
                key.pointer = ko.ptr();
                assign(key.time, ko.time("time", true));
                assign(key.sunAzimuth, ko.num("sunAzimuth", azimuth, true));
                assign(key.sunAltitude, ko.num("sunAltitude", altitude, true));
                l.keys.push_back(key);
            }
            keyOrder(l.keys, o.at("keys"));
        }
    }

    // Keys must not go back in time; offsets are compared with offsets (and with absolute times
    // once a clock gives them a start).
    template <class Key>
    void keyOrder(const std::vector<Key>& keys, const std::string& ptr) {
        mKeyLists.push_back({ptr, {}});
        for (const auto& k : keys) mKeyLists.back().second.push_back({k.time, k.pointer});
    }

    void checkKeyOrder() {
        for (const auto& [ptr, keys] : mKeyLists) {
            for (std::size_t i = 1; i < keys.size(); ++i) {
                const TimeSpec &a = keys[i - 1].first, &b = keys[i].first;
                if ((a.isOffset || b.isOffset) && !mS.clock) {
                    mC.error("SCENARIO_MISSING", keys[i].second + "/time",
                             "time offsets need a \"clock\" with a start");
                    break;
                }
                const double start = mS.clock ? mS.clock->start : 0.0;
                if (b.resolve(start) < a.resolve(start)) {
                    mC.error(
                        "SCENARIO_RANGE", keys[i].second + "/time",
                        "keys must be in time order (this key is earlier than the one before)");
                    break;
                }
            }
            if (keys.size() == 1 && keys[0].first.isOffset && !mS.clock)
                mC.error("SCENARIO_MISSING", keys[0].second + "/time",
                         "time offsets need a \"clock\" with a start");
        }
    }

    void reference(const std::string& ptr, const std::string& what, const std::string& name,
                   const std::vector<std::string>& candidates) {
        // Without a "stores" object that error already says it all; no per-reference echo.
        if (what == "store" && !mStoresGiven) return;
        if (std::find(candidates.begin(), candidates.end(), name) != candidates.end()) return;
        auto& e =
            mC.error("SCENARIO_UNKNOWN_REFERENCE", ptr, "unknown " + what + " " + quote(name));
        mC.didYouMean(e, name, candidates);
    }

    template <class Map>
    static std::vector<std::string> keysOf(const Map& m) {
        std::vector<std::string> out;
        for (const auto& kv : m) out.push_back(kv.first);
        return out;
    }

    void crossReferences() {
        const auto storeIds = keysOf(mS.stores);
        const auto tfNames = keysOf(mS.transferFunctions);
        // Transfer functions that failed to read still exist by name: do not also report every
        // reference to them as unknown.
        std::vector<std::string> tfDeclared = tfNames;
        tfDeclared.insert(tfDeclared.end(), mDeclaredTransfers.begin(), mDeclaredTransfers.end());
        if (!mS.terrain.store.empty())
            reference("/terrain/store", "store", mS.terrain.store, storeIds);

        std::vector<std::string> layerIds, visibilityIds;
        std::set<std::string> seen;
        for (const auto& l : mS.layers) {
            if (l.id.empty()) continue;
            if (!seen.insert(l.id).second)
                mC.error("SCENARIO_DUPLICATE_ID", l.pointer + "/id",
                         "layer id " + quote(l.id) + " is used twice");
            layerIds.push_back(l.id);
            if (l.kind == LayerKind::Visibility) visibilityIds.push_back(l.id);
        }
        for (const auto& l : mS.layers) {
            if (!l.source.store.empty())
                reference(l.pointer + "/source/store", "store", l.source.store, storeIds);
            if (!l.transfer.empty())
                reference(l.pointer + "/transfer", "transfer function", l.transfer, tfDeclared);
            if (!l.operation.visibility.empty())
                reference(l.pointer + "/operation/visibility", "visibility layer",
                          l.operation.visibility, visibilityIds);
        }
        seen.clear();
        for (const auto& lens : mS.lenses) {
            if (!lens.id.empty() && !seen.insert(lens.id).second)
                mC.error("SCENARIO_DUPLICATE_ID", lens.pointer + "/id",
                         "lens id " + quote(lens.id) + " is used twice");
            if (!lens.inside.empty())
                reference(lens.pointer + "/inside", "layer", lens.inside, layerIds);
            if (!lens.outside.empty())
                reference(lens.pointer + "/outside", "layer", lens.outside, layerIds);
        }
        seen.clear();
        for (const auto& m : mS.projectiveMappings) {
            if (!m.id.empty() && !seen.insert(m.id).second)
                mC.error("SCENARIO_DUPLICATE_ID", m.pointer + "/id",
                         "projective mapping id " + quote(m.id) + " is used twice");
            if (!m.data.store.empty())
                reference(m.pointer + "/data/store", "store", m.data.store, storeIds);
            if (!m.transfer.empty())
                reference(m.pointer + "/transfer", "transfer function", m.transfer, tfDeclared);
        }
        const auto viewpointNames = keysOf(mS.viewpoints);
        const auto pathNames = keysOf(mS.cameraPaths);
        if (!mS.camera.viewpoint.empty())
            reference("/camera/viewpoint", "viewpoint", mS.camera.viewpoint, viewpointNames);
        if (!mS.camera.path.empty())
            reference("/camera/path", "camera path", mS.camera.path, pathNames);
        for (auto& [name, path] : mS.cameraPaths) {
            for (auto& key : path.keys) {
                if (key.viewpoint.empty()) continue;
                auto it = mS.viewpoints.find(key.viewpoint);
                if (it == mS.viewpoints.end())
                    reference(key.pointer + "/viewpoint", "viewpoint", key.viewpoint,
                              viewpointNames);
                else
                    key.view = it->second;
            }
        }
        auto& legend = mS.overlays.legend;
        if (legend.enabled && legend.transfer.empty()) {
            for (const auto& l : mS.layers)
                if (!l.transfer.empty()) {
                    legend.transfer = l.transfer;
                    break;
                }
            if (legend.transfer.empty())
                mC.error("SCENARIO_MISSING", "/overlays/legend",
                         "the legend needs \"transfer\" (no layer uses a transfer function)");
        } else if (!legend.transfer.empty()) {
            reference("/overlays/legend/transfer", "transfer function", legend.transfer,
                      tfDeclared);
        }
        checkKeyOrder();
    }

public:
    std::vector<std::filesystem::path> mFiles;
    std::vector<std::string> mDeclaredTransfers;

private:
    Ctx& mC;
    Scenario& mS;
    std::vector<std::pair<std::string, std::vector<std::pair<TimeSpec, std::string>>>> mKeyLists;
    bool mStoresGiven = false;
};

Result<Scenario> build(LoadedDocument doc, Diagnostics diags,
                       std::vector<std::filesystem::path>* filesRead) {
    Scenario s;
    s.sourceFiles = doc.files;
    if (diags.hasErrors() || doc.value.is_null()) {
        if (filesRead) *filesRead = s.sourceFiles;
        return diags;
    }
    s.sourceMap = std::move(doc.sourceMap);
    Ctx ctx(s.sourceMap, diags);
    Reader reader(ctx, s);
    if (const auto tfs = doc.value.find("transferFunctions");
        tfs != doc.value.end() && tfs->is_object())
        for (auto it = tfs->begin(); it != tfs->end(); ++it)
            reader.mDeclaredTransfers.push_back(it.key());
    reader.root(doc.value);
    readBriefing(doc.value, s, diags);  // config/BriefingReader.cpp
    for (auto& f : reader.mFiles)
        if (std::find(s.sourceFiles.begin(), s.sourceFiles.end(), f) == s.sourceFiles.end())
            s.sourceFiles.push_back(f);
    if (filesRead) *filesRead = s.sourceFiles;
    if (diags.hasErrors()) return diags;
    return {std::move(s), std::move(diags)};
}

}  // namespace

const std::map<std::string, std::vector<std::string>>& acceptedProperties() {
    return propertyTable();
}

const char* layerKindName(LayerKind k) noexcept {
    for (const auto& [name, kind] : kLayerKinds)
        if (kind == k) return name.c_str();
    return "thematic";
}

const char* operationName(OperationType t) noexcept {
    for (const auto& [name, type] : kOperations)
        if (type == t) return name.c_str();
    return "opacity";
}

Result<Scenario> parseScenario(std::string_view text, const std::filesystem::path& name,
                               std::vector<std::filesystem::path>* filesRead) {
    try {
        Diagnostics diags;
        LoadedDocument doc = loadDocument(text, name, diags);
        return build(std::move(doc), std::move(diags), filesRead);
    } catch (const std::exception& e) {
        // Allocation failure or a library bug: still a message, never a crash.
        Diagnostics d;
        d.error("SCENARIO_INTERNAL", name.string(), "", std::string("internal error: ") + e.what());
        return d;
    }
}

Result<Scenario> readScenario(const std::filesystem::path& file,
                              std::vector<std::filesystem::path>* filesRead) {
    if (filesRead) *filesRead = {file};
    std::string why;
    auto text = readTextFile(file, kMaxScenarioFileBytes, why);
    if (!text) {
        Diagnostics d;
        d.error("SCENARIO_FILE", file.string(), "", "scenario file " + why);
        return d;
    }
    return parseScenario(*text, file, filesRead);
}

}  // namespace kiosk::config
