#pragma once

// Internal to config/: what every scenario section reader shares (the reading context that puts
// file:line:col on each message, typed getters with ranges, the property table). Split out of
// ScenarioReader.cpp so each section (layers, transfer functions, clock, lenses, mappings, view,
// cross-references) is a file of its own.
#include "config/Scenario.h"
#include "config/SourceMap.h"
#include "runtime/core/Assert.h"
#include "runtime/core/Diagnostics.h"
#include "runtime/core/Strings.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kiosk::config::reader {

using nlohmann::json;

// ---------------------------------------------------------------------------------------------
// The property table: the single list the reader checks unknown keys against and the schema
// test compares with config/schema/scenario.schema.json.

const std::map<std::string, std::vector<std::string>>& propertyTable();

std::string typeName(const json& j);

std::string quote(const std::string& s);

std::string joined(const std::vector<std::string>& items);

std::string numberText(double v);

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
inline const Range kAny{};
inline const Range kPositive{0, HUGE_VAL, true, false};
inline const Range kNonNegative{0, HUGE_VAL, false, false};
inline const Range kUnit{0, 1, false, false};
// Bounds of the values that reach the GPU as 32-bit floats (docs/scenario-format.md, "Ranges"),
// so that `validate` refuses what would turn into inf or lose all precision in a shader.
/** @brief Map coordinates (store CRS metres), components of mapping vectors: 1e8 m is more than
 *  twice the Earth's circumference, so no map reaches it, and a float still resolves 8 m there. */
inline const Range kMapCoordinate{-1e8, 1e8, false, false};
/** @brief Lens radii, camera ranges: lengths on a map, as kMapCoordinate. */
inline const Range kMapLength{0, 1e8, true, false};
/** @brief Widths that may be 0 (a lens's soft edge). */
inline const Range kMapWidth{0, 1e8, false, false};
/** @brief Data values (stops, domains, thresholds): a float reaches 3.4e38, and the shaders
 *  subtract and divide them, so differences must stay finite too. */
inline const Range kDataValue{-1e30, 1e30, false, false};
inline const Range kDataStep{0, 1e30, true, false};
/** @brief Entries of texture, colour and context matrices. */
inline const Range kMatrixEntry{-1e6, 1e6, false, false};

template <class E>
using EnumTable = std::vector<std::pair<std::string, E>>;

std::optional<double> readNumber(Ctx& c, const json& j, const std::string& ptr, const Range& r,
                                 const std::string& name);

template <std::size_t N>
std::optional<std::array<double, N>> readNumbers(Ctx& c, const json& j, const std::string& ptr,
                                                 const Range& r = kAny,
                                                 const std::string& name = {}) {
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
        if (!r.contains(out[i])) {
            c.error("SCENARIO_RANGE", childPointer(ptr, i),
                    (name.empty() ? "value" : name) + " must be " + r.text() + ", got " +
                        numberText(out[i]));
            return std::nullopt;
        }
    }
    return out;
}

std::optional<color::Rgba> readColor(Ctx& c, const json& j, const std::string& ptr);

bool hasZone(std::string_view s);

std::optional<double> readInstant(Ctx& c, const json& j, const std::string& ptr);

std::optional<TimeSpec> readTimeSpec(Ctx& c, const json& j, const std::string& ptr);

std::optional<std::int64_t> readBytes(Ctx& c, const json& j, const std::string& ptr);

// One JSON object of a known kind: unknown members are reported on construction (with a
// did-you-mean hint), then typed getters report missing members, wrong types and ranges.
class Obj {
public:
    Obj(Ctx& c, const json& j, std::string ptr, const char* kind)
        : Obj(c, j, std::move(ptr), propertyTable().at(kind)) {}
    /** @brief An object whose properties are `keys` (which must outlive it). */
    Obj(Ctx& c, const json& j, std::string ptr, const std::vector<std::string>& keys)
        : mC(c), mJ(j), mPtr(std::move(ptr)), mKeys(keys) {
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
    std::optional<std::array<double, N>> numbers(const std::string& key, const Range& r = kAny,
                                                 bool required = false) const {
        const json* j = get(key, required);
        return j ? readNumbers<N>(mC, *j, at(key), r, key) : std::nullopt;
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

}  // namespace kiosk::config::reader
