#include "config/DocumentLoader.h"
#include "config/KioskFile.h"
#include "config/ScenarioReader.h"
#include "runtime/core/Strings.h"
#include "runtime/core/TimeParse.h"

#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <fstream>

namespace kiosk::config {
namespace {

using nlohmann::json;

class KioskChecker {
public:
    KioskChecker(const LoadedDocument& doc, Diagnostics& diags) : mDoc(doc), mDiags(diags) {}

    void error(const char* code, const std::string& ptr, std::string message,
               std::string hint = {}) {
        Diagnostic& d = mDiags.error(code, "", ptr, std::move(message));
        const Location l = mDoc.sourceMap.value(ptr);
        d.file = l.file;
        d.line = l.line;
        d.column = l.column;
        d.hint = std::move(hint);
    }

    /** @brief Object with only known members; false (and an error) if not an object. */
    bool object(const json& j, const std::string& ptr, const char* kind) {
        if (!j.is_object()) {
            error("KIOSK_TYPE", ptr, std::string("expected an object (") + kind + ")");
            return false;
        }
        const auto& known = kioskProperties().at(kind);
        for (const auto& [key, value] : j.items()) {
            if (std::find(known.begin(), known.end(), key) != known.end()) continue;
            std::string hint;
            if (auto m = closestMatch(key, known)) hint = "did you mean \"" + *m + "\"?";
            const std::string child = childPointer(ptr, key);
            Diagnostic& d = mDiags.error("KIOSK_UNKNOWN_PROPERTY", "", child,
                                         "unknown property \"" + key + "\"");
            const Location l = mDoc.sourceMap.key(child);
            d.file = l.file;
            d.line = l.line;
            d.column = l.column;
            d.hint = hint;
        }
        return true;
    }

    std::optional<std::string> string(const json& j, const std::string& ptr) {
        if (j.is_string() && !j.get_ref<const std::string&>().empty()) return j.get<std::string>();
        error("KIOSK_TYPE", ptr, "expected a non-empty string");
        return std::nullopt;
    }

    std::optional<double> seconds(const json& j, const std::string& ptr) {
        double v = 0;
        if (j.is_number()) {
            v = j.get<double>();
        } else if (j.is_string()) {
            std::string text = j.get<std::string>();
            if (!text.empty() && text[0] != '+' && text[0] != '-') text = "+" + text;
            auto o = parseOffset(text);
            if (!o) {
                error("KIOSK_BAD_VALUE", ptr,
                      "expected seconds or a duration like \"10m\" or \"1h30m\"");
                return std::nullopt;
            }
            v = *o;
        } else {
            error("KIOSK_TYPE", ptr, "expected seconds or a duration like \"10m\"");
            return std::nullopt;
        }
        if (!std::isfinite(v) || v <= 0 || v > 366.0 * 86400) {
            error("KIOSK_BAD_VALUE", ptr, "must be more than 0 s and at most a year");
            return std::nullopt;
        }
        return v;
    }

    std::optional<std::int64_t> bytes(const json& j, const std::string& ptr) {
        if (!j.is_number_integer() || j.get<std::int64_t>() < (1 << 20)) {
            error("KIOSK_BAD_VALUE", ptr, "expected a whole number of bytes, at least 1048576");
            return std::nullopt;
        }
        return j.get<std::int64_t>();
    }

    /** @brief A memory budget with where it was set (refusals name the kiosk file's line). */
    void memoryBudget(const json& b, const char* key, std::int64_t minimum, MemoryBudget& out) {
        if (!b.contains(key)) return;
        const std::string ptr = std::string("/budgets/") + key;
        const json& j = b[key];
        if (!j.is_number_integer() || j.get<std::int64_t>() < minimum ||
            j.get<std::int64_t>() > (std::int64_t(1) << 40)) {
            error("KIOSK_BAD_VALUE", ptr,
                  "expected a whole number of bytes from " + std::to_string(minimum) + " to 1 TiB");
            return;
        }
        const Location l = mDoc.sourceMap.value(ptr);
        out = {j.get<std::int64_t>(), l.file.empty() ? mDoc.files.front().string() : l.file, l.line,
               l.column, ptr};
    }

    void entry(const json& j, const std::string& ptr, KioskFile& out) {
        if (!object(j, ptr, "Entry")) return;
        KioskEntry e;
        e.pointer = ptr;
        if (!j.contains("scenario")) {
            error("KIOSK_MISSING", ptr, "entry needs \"scenario\" (a scenario file)");
            return;
        }
        if (auto s = string(j["scenario"], ptr + "/scenario")) {
            std::filesystem::path p = *s;
            e.scenario = p.is_absolute() ? p : out.file.parent_path() / p;
        }
        if (j.contains("duration")) e.durationSeconds = seconds(j["duration"], ptr + "/duration");
        if (j.contains("loops")) {
            const json& l = j["loops"];
            if (l.is_number_integer() && l.get<std::int64_t>() >= 1 &&
                l.get<std::int64_t>() <= 1000000)
                e.loops = int(l.get<std::int64_t>());
            else
                error("KIOSK_BAD_VALUE", ptr + "/loops", "expected a whole number from 1");
        }
        if (j.contains("duration") && j.contains("loops"))
            error("KIOSK_CONFLICT", ptr + "/loops", "give \"duration\" or \"loops\", not both");
        if (j.contains("window")) {
            const json& w = j["window"];
            const std::string wp = ptr + "/window";
            if (object(w, wp, "Window")) {
                TimeOfDayWindow win;
                bool ok = true;
                for (const char* key : {"from", "to"}) {
                    const std::string kp = wp + "/" + key;
                    if (!w.contains(key)) {
                        error("KIOSK_MISSING", wp, std::string("window needs \"") + key + "\"");
                        ok = false;
                        continue;
                    }
                    std::optional<int> t;
                    if (w[key].is_string()) t = parseTimeOfDay(w[key].get<std::string>());
                    if (!t) {
                        error("KIOSK_BAD_VALUE", kp, "expected a local time \"HH:MM\"");
                        ok = false;
                        continue;
                    }
                    (std::string_view(key) == "from" ? win.fromSeconds : win.toSeconds) = *t;
                }
                if (ok && win.fromSeconds == win.toSeconds) {
                    error("KIOSK_BAD_VALUE", wp + "/to", "window is empty (from equals to)");
                    ok = false;
                }
                if (ok) e.window = win;
            }
        }
        if (!e.loops && !e.durationSeconds) e.loops = 1;
        out.playlist.push_back(std::move(e));
    }

    void root(KioskFile& out) {
        const json& j = mDoc.value;
        if (!object(j, "", "Kiosk")) return;
        if (!j.contains("playlist")) {
            error("KIOSK_MISSING", "", "a kiosk file needs \"playlist\"");
        } else if (!j["playlist"].is_array() || j["playlist"].empty()) {
            error("KIOSK_TYPE", "/playlist", "expected a non-empty array of entries");
        } else {
            for (std::size_t i = 0; i < j["playlist"].size(); ++i)
                entry(j["playlist"][i], childPointer("/playlist", i), out);
        }
        if (j.contains("transition") && object(j["transition"], "/transition", "Transition")) {
            const json& t = j["transition"];
            if (t.contains("kind")) {
                const json& k = t["kind"];
                if (k == "cut")
                    out.transition = TransitionKind::Cut;
                else if (k == "fade")
                    out.transition = TransitionKind::Fade;
                else
                    error("KIOSK_BAD_VALUE", "/transition/kind", "expected \"cut\" or \"fade\"");
            }
            if (t.contains("seconds")) {
                if (t["seconds"].is_number() && t["seconds"].get<double>() >= 0 &&
                    t["seconds"].get<double>() <= 60)
                    out.transitionSeconds = t["seconds"].get<double>();
                else
                    error("KIOSK_BAD_VALUE", "/transition/seconds", "expected 0 to 60 seconds");
            } else if (out.transition == TransitionKind::Fade) {
                out.transitionSeconds = 1.0;
            }
        }
        if (j.contains("listen")) out.listen = string(j["listen"], "/listen");
        if (j.contains("tokenFile")) {
            if (auto s = string(j["tokenFile"], "/tokenFile")) {
                std::filesystem::path p = *s;
                out.tokenFile = p.is_absolute() ? p : out.file.parent_path() / p;
            }
        }
        if (j.contains("budgets") && object(j["budgets"], "/budgets", "Budgets")) {
            const json& b = j["budgets"];
            if (b.contains("cacheBytes"))
                out.cacheBytes = bytes(b["cacheBytes"], "/budgets/cacheBytes");
            if (b.contains("gpuBytes")) out.gpuBytes = bytes(b["gpuBytes"], "/budgets/gpuBytes");
            // Minimums: one LUT (1024 RGBA8 texels), a small font, SQLite's largest page.
            memoryBudget(b, "lutBytes", 4096, out.memory.luts);
            memoryBudget(b, "mappingBytes", 1 << 20, out.memory.mappings);
            memoryBudget(b, "fontAtlasBytes", 4096, out.memory.fontAtlas);
            memoryBudget(b, "sqlitePageCacheBytes", 65536, out.memory.sqlitePageCache);
        }
    }

private:
    const LoadedDocument& mDoc;
    Diagnostics& mDiags;
};

}  // namespace

const std::map<std::string, std::vector<std::string>>& kioskProperties() {
    static const std::map<std::string, std::vector<std::string>> table = {
        {"Kiosk", {"$schema", "title", "playlist", "transition", "listen", "tokenFile", "budgets"}},
        {"Entry", {"scenario", "duration", "loops", "window", "title"}},
        {"Window", {"from", "to"}},
        {"Transition", {"kind", "seconds"}},
        {"Budgets",
         {"cacheBytes", "gpuBytes", "lutBytes", "mappingBytes", "fontAtlasBytes",
          "sqlitePageCacheBytes"}},
    };
    return table;
}

std::optional<int> parseTimeOfDay(std::string_view text) {
    // HH:MM or HH:MM:SS, two digits each.
    if (text.size() != 5 && text.size() != 8) return std::nullopt;
    int parts[3] = {0, 0, 0};
    for (std::size_t n = 0; n * 3 < text.size(); ++n) {
        const std::size_t at = n * 3;
        if (n > 0 && text[at - 1] != ':') return std::nullopt;
        auto [p, ec] = std::from_chars(text.data() + at, text.data() + at + 2, parts[n]);
        if (ec != std::errc() || p != text.data() + at + 2) return std::nullopt;
    }
    if (parts[1] > 59 || parts[2] > 59) return std::nullopt;
    const int s = parts[0] * 3600 + parts[1] * 60 + parts[2];
    return s <= 86400 ? std::optional<int>(s) : std::nullopt;
}

bool isKioskFile(const std::filesystem::path& file) {
    std::string why;
    auto text = readTextFile(file, kMaxScenarioFileBytes, why);
    if (!text) return false;
    const json j = json::parse(*text, nullptr, false, /*ignore_comments=*/true);
    return j.is_object() && j.contains("playlist");
}

Result<KioskFile> readKioskFile(const std::filesystem::path& file) {
    Diagnostics diags;
    std::string why;
    auto text = readTextFile(file, kMaxScenarioFileBytes, why);
    if (!text) {
        diags.error("KIOSK_FILE", file.string(), "", "kiosk file " + why);
        return Result<KioskFile>(std::move(diags));
    }
    const LoadedDocument doc = loadDocument(*text, file, diags);
    if (diags.hasErrors() || doc.value.is_null()) return Result<KioskFile>(std::move(diags));
    KioskFile out;
    out.file = file;
    try {
        KioskChecker(doc, diags).root(out);
    } catch (const std::exception& e) {
        // Allocation failure or a library bug: still a message, never a crash.
        diags.error("KIOSK_INTERNAL", file.string(), "",
                    std::string("internal error: ") + e.what());
    }
    if (diags.hasErrors()) return Result<KioskFile>(std::move(diags));
    return Result<KioskFile>(std::move(out), std::move(diags));
}

}  // namespace kiosk::config
