#include "config/BriefingReader.h"

#include "config/ScenarioReader.h"
#include "runtime/core/Strings.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace kiosk::config {
namespace {

using nlohmann::json;

std::string quote(const std::string& s) {
    return "\"" + s + "\"";
}

/** One briefing's reading: the scenario (for references and positions) and the messages. */
class BriefingReader {
public:
    BriefingReader(Scenario& s, Diagnostics& d) : mS(s), mD(d) {}

    void read(const json& j) {
        if (!object(j, "/briefing", "Briefing")) return;
        Briefing b;
        const auto it = j.find("chapters");
        if (it == j.end()) {
            error("SCENARIO_MISSING", "/briefing", "missing required property \"chapters\"");
            return;
        }
        const std::string ptr = "/briefing/chapters";
        if (!it->is_array() || it->empty()) {
            error("SCENARIO_TYPE", ptr, "expected a non-empty array of chapters");
            return;
        }
        if (it->size() > kMaxChapters) {
            error("SCENARIO_RANGE", ptr,
                  "at most " + std::to_string(kMaxChapters) + " chapters, got " +
                      std::to_string(it->size()));
            return;
        }
        for (std::size_t i = 0; i < it->size(); ++i)
            if (auto c = chapter((*it)[i], childPointer(ptr, i))) b.chapters.push_back(*c);
        mS.briefing = std::move(b);
    }

private:
    Diagnostic& error(const char* code, const std::string& ptr, std::string message,
                      bool atKey = false) {
        const Location l = atKey ? mS.sourceMap.key(ptr) : mS.sourceMap.value(ptr);
        auto& d = mD.error(code, l.file, ptr, std::move(message));
        d.line = l.line;
        d.column = l.column;
        return d;
    }

    /** An object of a known kind; unknown members are reported (with a did-you-mean). */
    bool object(const json& j, const std::string& ptr, const char* kind) {
        if (!j.is_object()) {
            error("SCENARIO_TYPE", ptr, "expected object, got " + std::string(j.type_name()));
            return false;
        }
        const auto& keys = acceptedProperties().at(kind);
        for (auto it = j.begin(); it != j.end(); ++it) {
            if (std::find(keys.begin(), keys.end(), it.key()) != keys.end()) continue;
            auto& e = error("SCENARIO_UNKNOWN_PROPERTY", childPointer(ptr, it.key()),
                            "unknown property " + quote(it.key()), true);
            if (auto m = closestMatch(it.key(), keys)) e.hint = "did you mean " + quote(*m) + "?";
        }
        return true;
    }

    template <class T>
    const json* member(const json& j, const std::string& ptr, const char* key,
                       bool (json::*is)() const, const char* expected) {
        const auto it = j.find(key);
        if (it == j.end()) return nullptr;
        if (!((*it).*is)()) {
            error("SCENARIO_TYPE", childPointer(ptr, key),
                  std::string("expected ") + expected + ", got " + it->type_name());
            return nullptr;
        }
        return &*it;
    }
    std::optional<std::string> str(const json& j, const std::string& ptr, const char* key) {
        const json* v = member<std::string>(j, ptr, key, &json::is_string, "string");
        return v ? std::optional(v->get<std::string>()) : std::nullopt;
    }
    std::optional<bool> boolean(const json& j, const std::string& ptr, const char* key) {
        const json* v = member<bool>(j, ptr, key, &json::is_boolean, "boolean");
        return v ? std::optional(v->get<bool>()) : std::nullopt;
    }
    std::optional<double> number(const json& j, const std::string& ptr, const char* key, double lo,
                                 double hi, bool loOpen) {
        const json* v = member<double>(j, ptr, key, &json::is_number, "number");
        if (!v) return std::nullopt;
        const double x = v->get<double>();
        if (!std::isfinite(x) || (loOpen ? x <= lo : x < lo) || x > hi) {
            char buf[96];
            std::snprintf(buf, sizeof buf, "%s must be in %s%g, %g], got %g", key,
                          loOpen ? "(" : "[", lo, hi, x);
            error("SCENARIO_RANGE", childPointer(ptr, key), buf);
            return std::nullopt;
        }
        return x;
    }
    std::optional<TimeSpec> time(const json& j, const std::string& ptr, const char* key) {
        auto s = str(j, ptr, key);
        if (!s) return std::nullopt;
        auto t = parseTimeSpec(*s);
        // Absolute times must say they are UTC (or give an offset), as everywhere in a scenario.
        const auto tpos = s->find('T');
        const bool zoned =
            !s->empty() &&
            (s->back() == 'Z' || s->back() == 'z' ||
             (tpos != std::string::npos && s->find_first_of("+-", tpos) != std::string::npos));
        if (!t || (!t->isOffset && !zoned)) {
            error("SCENARIO_BAD_TIME", childPointer(ptr, key),
                  "bad time " + quote(*s) +
                      " (expected ISO 8601 UTC like \"2026-03-14T06:40:00Z\" or an offset from "
                      "the clock start like \"+1h30m\")");
            return std::nullopt;
        }
        if (t->isOffset && !mS.clock)
            error("SCENARIO_MISSING", childPointer(ptr, key),
                  "time offsets need a \"clock\" with a start");
        return t;
    }

    void reference(const std::string& ptr, const char* what, const std::string& name,
                   const std::vector<std::string>& names) {
        if (std::find(names.begin(), names.end(), name) != names.end()) return;
        auto& e = error("SCENARIO_UNKNOWN_REFERENCE", ptr,
                        std::string("unknown ") + what + " " + quote(name));
        if (auto m = closestMatch(name, names)) e.hint = "did you mean " + quote(*m) + "?";
    }

    template <class Map>
    static std::vector<std::string> keysOf(const Map& m) {
        std::vector<std::string> out;
        for (const auto& kv : m) out.push_back(kv.first);
        return out;
    }

    std::optional<Chapter> chapter(const json& j, const std::string& ptr) {
        if (!object(j, ptr, "Chapter")) return std::nullopt;
        Chapter c;
        c.pointer = ptr;
        if (auto t = str(j, ptr, "title"); t && !t->empty())
            c.title = *t;
        else if (!j.contains("title"))
            error("SCENARIO_MISSING", ptr, "missing required property \"title\"");
        else if (t)
            error("SCENARIO_BAD_VALUE", ptr + "/title", "\"title\" must not be empty");
        // The data time: one instant ("time") or a span ("from" + "to").
        const bool single = j.contains("time"), span = j.contains("from") || j.contains("to");
        if (single && span) {
            error("SCENARIO_CONFLICT", ptr, "give \"time\" or \"from\"/\"to\", not both");
        } else if (single) {
            if (auto t = time(j, ptr, "time")) c.from = c.to = *t;
        } else if (j.contains("from") && j.contains("to")) {
            auto from = time(j, ptr, "from");
            auto to = time(j, ptr, "to");
            if (from && to) {
                c.from = *from;
                c.to = *to;
                c.span = true;
                const double start = mS.clock ? mS.clock->start : 0.0;
                if (to->resolve(start) < from->resolve(start))
                    error("SCENARIO_RANGE", ptr + "/to", "\"to\" is before \"from\"");
            }
        } else {
            error("SCENARIO_MISSING", ptr,
                  span ? "\"from\" and \"to\" go together"
                       : "a chapter needs \"time\" or \"from\" and \"to\"");
        }
        if (auto d = number(j, ptr, "duration", 0, kMaxChapterSeconds, true)) c.duration = d;
        if (auto v = str(j, ptr, "viewpoint")) {
            c.viewpoint = *v;
            reference(ptr + "/viewpoint", "viewpoint", *v, keysOf(mS.viewpoints));
        }
        if (auto p = str(j, ptr, "path")) {
            c.path = *p;
            reference(ptr + "/path", "camera path", *p, keysOf(mS.cameraPaths));
        }
        if (!c.viewpoint.empty() && !c.path.empty())
            error("SCENARIO_CONFLICT", ptr, "give \"viewpoint\" or \"path\", not both");
        if (auto cap = str(j, ptr, "caption")) {
            const auto lines = std::count(cap->begin(), cap->end(), '\n') + 1;
            if (cap->size() > kMaxCaptionBytes || std::size_t(lines) > kMaxCaptionLines)
                error("SCENARIO_RANGE", ptr + "/caption",
                      "a caption has at most " + std::to_string(kMaxCaptionLines) + " lines and " +
                          std::to_string(kMaxCaptionBytes) + " bytes");
            else
                c.caption = *cap;
        }
        if (auto p = boolean(j, ptr, "pause")) c.pause = *p;
        if (const json* layers = member<json>(j, ptr, "layers", &json::is_object, "object"))
            chapterLayers(*layers, ptr + "/layers", c);
        return c;
    }

    void chapterLayers(const json& j, const std::string& ptr, Chapter& c) {
        std::vector<std::string> ids;
        for (const auto& l : mS.layers) ids.push_back(l.id);
        for (auto it = j.begin(); it != j.end(); ++it) {
            const std::string lp = childPointer(ptr, it.key());
            if (!object(*it, lp, "ChapterLayer")) continue;
            const Layer* layer = mS.findLayer(it.key());
            if (!layer) {
                reference(lp, "layer", it.key(), ids);
                continue;
            }
            ChapterLayer o;
            o.layer = it.key();
            o.pointer = lp;
            o.enabled = boolean(*it, lp, "enabled");
            o.opacity = number(*it, lp, "opacity", 0, 1, false);
            // Chapters show and hide layers of the stack; a layer switched off in "layers" is
            // never built, so it cannot be switched on for one chapter.
            if (!layer->enabled && o.enabled.value_or(true))
                error("SCENARIO_CONFLICT", lp,
                      "layer " + quote(o.layer) + " is disabled in " + layer->pointer +
                          "; enable it there and hide it (\"enabled\": false) in the chapters "
                          "that should not show it");
            c.layers.push_back(o);
        }
    }

    Scenario& mS;
    Diagnostics& mD;
};

}  // namespace

void readBriefing(const json& document, Scenario& scenario, Diagnostics& diags) {
    if (!document.is_object()) return;
    const auto it = document.find("briefing");
    if (it == document.end()) return;
    BriefingReader(scenario, diags).read(*it);
}

}  // namespace kiosk::config
