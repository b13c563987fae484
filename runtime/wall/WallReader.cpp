#include "runtime/wall/WallReader.h"

#include "config/DocumentLoader.h"
#include "runtime/core/Strings.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace kiosk::wall {
namespace {

using config::childPointer;
using nlohmann::json;

const std::vector<std::string>& props(const char* kind) {
    return acceptedWallProperties().at(kind);
}

constexpr std::uintmax_t kMaxWallFileBytes = 1u << 20;
constexpr int kMaxGrid = 64;
constexpr int kMaxPixels = 16384;

/** Every message carries file:line:col of the value (or key) at the pointer. */
class Reader {
public:
    Reader(const config::SourceMap& map, Diagnostics& diags) : mMap(map), mDiags(diags) {}

    Diagnostic& error(const char* code, const std::string& ptr, std::string message,
                      bool atKey = false) {
        const config::Location l = atKey ? mMap.key(ptr) : mMap.value(ptr);
        auto& d = mDiags.error(code, l.file, ptr, std::move(message));
        d.line = l.line;
        d.column = l.column;
        return d;
    }

    /** Unknown members are errors with a "did you mean" (a typo must not silently do nothing). */
    bool object(const json& j, const std::string& ptr, const std::vector<std::string>& allowed) {
        if (!j.is_object()) {
            error("WALL_TYPE", ptr, "expected an object");
            return false;
        }
        for (auto it = j.begin(); it != j.end(); ++it) {
            if (std::find(allowed.begin(), allowed.end(), it.key()) != allowed.end()) continue;
            auto& d = error("WALL_UNKNOWN_PROPERTY", childPointer(ptr, it.key()),
                            "unknown property \"" + it.key() + "\"", true);
            if (auto m = closestMatch(it.key(), allowed)) d.hint = "did you mean \"" + *m + "\"?";
        }
        return true;
    }
    const json* member(const json& j, const std::string& ptr, const char* name, bool required) {
        auto it = j.find(name);
        if (it != j.end()) return &*it;
        if (required)
            error("WALL_MISSING", ptr, std::string("missing required property \"") + name + "\"");
        return nullptr;
    }
    std::optional<double> number(const json& j, const std::string& ptr, double min, bool minOpen,
                                 double max, const std::string& what) {
        if (!j.is_number()) {
            error("WALL_TYPE", ptr, "expected a number");
            return std::nullopt;
        }
        const double v = j.get<double>();
        if (!std::isfinite(v) || (minOpen ? v <= min : v < min) || v > max) {
            error("WALL_RANGE", ptr,
                  what + " must be " + (minOpen ? "> " : ">= ") + shortNumber(min) +
                      " and <= " + shortNumber(max) + ", got " + shortNumber(v));
            return std::nullopt;
        }
        return v;
    }
    std::optional<int> integer(const json& j, const std::string& ptr, int min, int max,
                               const std::string& what) {
        if (!j.is_number_integer()) {
            error("WALL_TYPE", ptr, "expected an integer");
            return std::nullopt;
        }
        const auto v = j.get<std::int64_t>();
        if (v < min || v > max) {
            error("WALL_RANGE", ptr,
                  what + " must be in [" + std::to_string(min) + ", " + std::to_string(max) +
                      "], got " + std::to_string(v));
            return std::nullopt;
        }
        return int(v);
    }
    std::optional<std::string> string(const json& j, const std::string& ptr) {
        if (!j.is_string() || j.get<std::string>().empty()) {
            error("WALL_TYPE", ptr, "expected a non-empty string");
            return std::nullopt;
        }
        return j.get<std::string>();
    }
    /** [a, b] of numbers with a lower bound (pixels, millimetres). */
    bool pair(const json& j, const std::string& ptr, double min, bool minOpen, double max,
              const std::string& what, double& a, double& b) {
        if (!j.is_array() || j.size() != 2) {
            error("WALL_TYPE", ptr, "expected an array of 2 numbers");
            return false;
        }
        auto x = number(j[0], childPointer(ptr, 0), min, minOpen, max, what);
        auto y = number(j[1], childPointer(ptr, 1), min, minOpen, max, what);
        if (!x || !y) return false;
        a = *x;
        b = *y;
        return true;
    }

    const config::SourceMap& mMap;
    Diagnostics& mDiags;
};

struct ScreenShape {
    double pixelsX = 0, pixelsY = 0, mmX = 0, mmY = 0;
    bool havePixels = false, haveMm = false;
};

void readShape(Reader& r, const json& j, const std::string& ptr, ScreenShape& s) {
    if (auto p = j.find("pixels"); p != j.end()) {
        double x = 0, y = 0;
        if (r.pair(*p, childPointer(ptr, "pixels"), 1, false, kMaxPixels, "a screen size in pixels",
                   x, y)) {
            if (x != std::floor(x) || y != std::floor(y))
                r.error("WALL_TYPE", childPointer(ptr, "pixels"), "pixel sizes are whole numbers");
            s.pixelsX = x;
            s.pixelsY = y;
            s.havePixels = true;
        }
    }
    if (auto p = j.find("activeMm"); p != j.end()) {
        if (r.pair(*p, childPointer(ptr, "activeMm"), 0, true, 1e5, "an active size in mm", s.mmX,
                   s.mmY))
            s.haveMm = true;
    }
}

double readAngle(Reader& r, const json& j, const std::string& ptr, const char* name) {
    auto it = j.find(name);
    if (it == j.end()) return 0.0;
    return r.number(*it, childPointer(ptr, name), -90, false, 90, std::string(name) + " (degrees)")
        .value_or(0.0);
}

std::optional<int> screenRef(Reader& r, const Wall& w, const json& j, const std::string& ptr) {
    auto id = r.string(j, ptr);
    if (!id) return std::nullopt;
    const int s = w.findScreen(*id);
    if (s >= 0) return s;
    std::vector<std::string> ids;
    for (const auto& sc : w.screens) ids.push_back(sc.id);
    auto& d = r.error("WALL_UNKNOWN_SCREEN", ptr, "unknown screen id \"" + *id + "\"");
    if (auto m = closestMatch(*id, ids)) d.hint = "did you mean \"" + *m + "\"?";
    return std::nullopt;
}

void readScreens(Reader& r, const json& root, Wall& w) {
    ScreenShape defaults;
    if (const json* d = r.member(root, "", "screenDefaults", false)) {
        if (r.object(*d, "/screenDefaults", props("ScreenDefaults")))
            readShape(r, *d, "/screenDefaults", defaults);
    }
    const json* list = r.member(root, "", "screens", true);
    if (!list) return;
    if (!list->is_array() || list->empty()) {
        r.error("WALL_TYPE", "/screens", "expected a non-empty array of screens");
        return;
    }
    for (std::size_t i = 0; i < list->size(); ++i) {
        const std::string ptr = childPointer("/screens", i);
        const json& j = (*list)[i];
        if (!r.object(j, ptr, props("Screen"))) continue;
        Screen s;
        if (const json* id = r.member(j, ptr, "id", true))
            if (auto v = r.string(*id, childPointer(ptr, "id"))) s.id = *v;
        if (!s.id.empty() && w.findScreen(s.id) >= 0)
            r.error("WALL_DUPLICATE_ID", childPointer(ptr, "id"),
                    "screen id \"" + s.id + "\" is used twice");
        if (const json* v = r.member(j, ptr, "row", true))
            s.row = r.integer(*v, childPointer(ptr, "row"), 0, std::max(0, w.rows - 1), "row")
                        .value_or(-1);
        if (const json* v = r.member(j, ptr, "column", true))
            s.column =
                r.integer(*v, childPointer(ptr, "column"), 0, std::max(0, w.columns - 1), "column")
                    .value_or(-1);
        ScreenShape shape = defaults;
        ScreenShape own;
        readShape(r, j, ptr, own);
        if (own.havePixels)
            shape.pixelsX = own.pixelsX, shape.pixelsY = own.pixelsY, shape.havePixels = true;
        if (own.haveMm) shape.mmX = own.mmX, shape.mmY = own.mmY, shape.haveMm = true;
        if (!shape.havePixels)
            r.error("WALL_MISSING", ptr,
                    "screen \"" + s.id + "\" has no \"pixels\" (here or in /screenDefaults)");
        if (!shape.haveMm)
            r.error("WALL_MISSING", ptr,
                    "screen \"" + s.id + "\" has no \"activeMm\" (here or in /screenDefaults)");
        s.pixelsX = int(shape.pixelsX);
        s.pixelsY = int(shape.pixelsY);
        s.activeMmX = shape.mmX;
        s.activeMmY = shape.mmY;
        s.yawDeg = readAngle(r, j, ptr, "yaw");
        s.pitchDeg = readAngle(r, j, ptr, "pitch");
        s.rollDeg = readAngle(r, j, ptr, "roll");
        if (auto p = j.find("positionMm"); p != j.end()) {
            r.pair(*p, childPointer(ptr, "positionMm"), -1e6, false, 1e6, "a position in mm", s.xMm,
                   s.yMm);
        } else {
            s.xMm = s.yMm = std::nan("");  // placed from the grid (placeScreens)
        }
        w.screens.push_back(std::move(s));
    }
}

/** Grid placement: columns as wide as their widest screen, rows as tall as their tallest,
 * mullions between them; a screen sits centred in its cell unless it gives positionMm. */
void placeScreens(Reader& r, Wall& w) {
    std::vector<double> colW(std::size_t(std::max(0, w.columns)), 0.0),
        rowH(std::size_t(std::max(0, w.rows)), 0.0);
    for (const auto& s : w.screens) {
        if (s.row < 0 || s.column < 0) return;
        colW[std::size_t(s.column)] = std::max(colW[std::size_t(s.column)], s.activeMmX);
        rowH[std::size_t(s.row)] = std::max(rowH[std::size_t(s.row)], s.activeMmY);
    }
    for (auto& s : w.screens) {
        if (!std::isnan(s.xMm)) continue;
        double x = 0, y = 0;
        for (int c = 0; c < s.column; ++c) x += colW[std::size_t(c)] + w.mullionMmX;
        for (int rr = 0; rr < s.row; ++rr) y += rowH[std::size_t(rr)] + w.mullionMmY;
        s.xMm = x + (colW[std::size_t(s.column)] - s.activeMmX) * 0.5;
        s.yMm = y + (rowH[std::size_t(s.row)] - s.activeMmY) * 0.5;
    }
    // Overlap of the active areas on the wall plane (explicit positions can collide).
    for (std::size_t a = 0; a < w.screens.size(); ++a)
        for (std::size_t b = a + 1; b < w.screens.size(); ++b) {
            const Screen &p = w.screens[a], &q = w.screens[b];
            const double ox =
                std::min(p.xMm + p.activeMmX, q.xMm + q.activeMmX) - std::max(p.xMm, q.xMm);
            const double oy =
                std::min(p.yMm + p.activeMmY, q.yMm + q.activeMmY) - std::max(p.yMm, q.yMm);
            if (ox > 1e-9 && oy > 1e-9)
                r.error("WALL_OVERLAP", childPointer("/screens", b),
                        "screens \"" + p.id + "\" and \"" + q.id + "\" overlap by " +
                            shortNumber(ox) + " x " + shortNumber(oy) + " mm on the wall" +
                            (p.row == q.row && p.column == q.column
                                 ? " (both at row " + std::to_string(p.row) + ", column " +
                                       std::to_string(p.column) + ")"
                                 : std::string()));
        }
    double minX = HUGE_VAL, minY = HUGE_VAL, maxX = -HUGE_VAL, maxY = -HUGE_VAL;
    for (const auto& s : w.screens) {
        minX = std::min(minX, s.xMm);
        minY = std::min(minY, s.yMm);
        maxX = std::max(maxX, s.xMm + s.activeMmX);
        maxY = std::max(maxY, s.yMm + s.activeMmY);
    }
    for (auto& s : w.screens) {
        s.xMm -= minX;
        s.yMm -= minY;
    }
    w.canvasMmX = maxX - minX;
    w.canvasMmY = maxY - minY;
}

void readNodes(Reader& r, const json& root, Wall& w) {
    const json* list = r.member(root, "", "nodes", true);
    if (!list) return;
    if (!list->is_array() || list->empty()) {
        r.error("WALL_TYPE", "/nodes", "expected a non-empty array of nodes");
        return;
    }
    for (std::size_t i = 0; i < list->size(); ++i) {
        const std::string ptr = childPointer("/nodes", i);
        const json& j = (*list)[i];
        if (!r.object(j, ptr, props("Node"))) continue;
        Node n;
        if (const json* id = r.member(j, ptr, "id", true))
            if (auto v = r.string(*id, childPointer(ptr, "id"))) n.id = *v;
        for (const auto& other : w.nodes)
            if (!n.id.empty() && other.id == n.id)
                r.error("WALL_DUPLICATE_ID", childPointer(ptr, "id"),
                        "node id \"" + n.id + "\" is used twice");
        const json* screens = r.member(j, ptr, "screens", true);
        if (screens && (!screens->is_array() || screens->empty()))
            r.error("WALL_TYPE", childPointer(ptr, "screens"),
                    "expected a non-empty array of screen ids");
        else if (screens)
            for (std::size_t k = 0; k < screens->size(); ++k) {
                const std::string sp = childPointer(childPointer(ptr, "screens"), k);
                auto s = screenRef(r, w, (*screens)[k], sp);
                if (!s) continue;
                Screen& sc = w.screens[std::size_t(*s)];
                if (sc.node >= 0)
                    r.error("WALL_DUPLICATE_ID", sp,
                            "screen \"" + sc.id + "\" is already driven by node \"" +
                                w.nodes[std::size_t(sc.node)].id + "\"");
                else
                    sc.node = int(w.nodes.size());
                n.screens.push_back(*s);
            }
        w.nodes.push_back(std::move(n));
    }
    for (std::size_t i = 0; i < w.screens.size(); ++i)
        if (w.screens[i].node < 0 && !w.screens[i].id.empty())
            r.error("WALL_UNDRIVEN", childPointer("/screens", i),
                    "screen \"" + w.screens[i].id +
                        "\" is not driven by any node (list it in a node's \"screens\")");
    if (const json* l = r.member(root, "", "leader", true)) {
        if (auto id = r.string(*l, "/leader")) {
            std::vector<std::string> ids;
            for (std::size_t i = 0; i < w.nodes.size(); ++i) {
                ids.push_back(w.nodes[i].id);
                if (w.nodes[i].id == *id) w.leader = int(i);
            }
            if (w.leader < 0 || w.nodes[std::size_t(w.leader)].screens.empty()) {
                w.leader = -1;
                auto& d =
                    r.error("WALL_UNKNOWN_NODE", "/leader", "unknown node id \"" + *id + "\"");
                if (auto m = closestMatch(*id, ids)) d.hint = "did you mean \"" + *m + "\"?";
            }
        }
    }
}

void readEndpoint(Reader& r, const json& j, const std::string& ptr, std::string& out) {
    auto v = r.string(j, ptr);
    if (!v) return;
    if (v->rfind("tcp://", 0) != 0 && v->rfind("ipc://", 0) != 0) {
        r.error("WALL_ENDPOINT", ptr, "endpoint \"" + *v + "\" must start with tcp:// or ipc://");
        return;
    }
    out = *v;
}

void readSync(Reader& r, const json& root, Wall& w) {
    const json* s = r.member(root, "", "sync", true);
    if (!s || !r.object(*s, "/sync", props("Sync"))) return;
    if (const json* v = r.member(*s, "/sync", "state", true))
        readEndpoint(r, *v, "/sync/state", w.sync.stateEndpoint);
    if (const json* v = r.member(*s, "/sync", "ready", true))
        readEndpoint(r, *v, "/sync/ready", w.sync.readyEndpoint);
    if (!w.sync.stateEndpoint.empty() && w.sync.stateEndpoint == w.sync.readyEndpoint)
        r.error("WALL_ENDPOINT", "/sync/ready",
                "the ready endpoint must differ from the state endpoint");
    if (const json* v = r.member(*s, "/sync", "deadlineMs", false))
        w.sync.deadlineMs =
            r.number(*v, "/sync/deadlineMs", 0, true, 10000, "deadlineMs").value_or(100.0);
}

void readPlacement(Reader& r, const Wall& w, const json& j, const std::string& ptr,
                   OverlayPlacement& p) {
    if (!r.object(j, ptr, props("Placement"))) return;
    const bool hasScreen = j.contains("screen"), hasCanvas = j.contains("canvas");
    if (hasScreen == hasCanvas) {
        r.error("WALL_MISSING", ptr,
                "give exactly one of \"screen\" (a screen id) or \"canvas\" ([x, y] in 0..1)");
        return;
    }
    if (hasScreen) {
        p.screen = screenRef(r, w, j["screen"], childPointer(ptr, "screen")).value_or(-1);
    } else {
        double x = 0, y = 0;
        if (r.pair(j["canvas"], childPointer(ptr, "canvas"), 0, false, 1, "a canvas position", x,
                   y))
            p.canvas = std::array<double, 2>{x, y};
    }
}

Wall build(const json& root, Reader& r, const std::string& file) {
    Wall w;
    w.file = file;
    if (!r.object(root, "", props("Wall"))) return w;
    if (const json* v = r.member(root, "", "version", false))
        r.integer(*v, "/version", 1, 1, "version");
    if (const json* g = r.member(root, "", "grid", true);
        g && r.object(*g, "/grid", props("Grid"))) {
        if (const json* v = r.member(*g, "/grid", "rows", true))
            w.rows = r.integer(*v, "/grid/rows", 1, kMaxGrid, "rows").value_or(0);
        if (const json* v = r.member(*g, "/grid", "columns", true))
            w.columns = r.integer(*v, "/grid/columns", 1, kMaxGrid, "columns").value_or(0);
    }
    if (const json* m = r.member(root, "", "mullionMm", true)) {
        if (!m->is_array() || m->size() != 2) {
            r.error("WALL_TYPE", "/mullionMm",
                    "expected an array of 2 numbers [between columns, between rows]");
        } else {
            for (std::size_t i = 0; i < 2; ++i) {
                const std::string ptr = childPointer("/mullionMm", i);
                if (!(*m)[i].is_number()) {
                    r.error("WALL_TYPE", ptr, "expected a number");
                    continue;
                }
                const double v = (*m)[i].get<double>();
                // Bezelled screens always leave a gap; 0 is a typo (or a projector blend, which
                // this layout does not model) and would silently misplace the picture.
                if (!(v > 0) || !std::isfinite(v) || v > 1000)
                    r.error("WALL_BEZEL", ptr,
                            std::string("mullion (bezel gap) ") +
                                (i == 0 ? "between columns" : "between rows") +
                                " must be > 0 and <= 1000 mm, got " + shortNumber(v));
                else
                    (i == 0 ? w.mullionMmX : w.mullionMmY) = v;
            }
        }
    }
    if (w.rows > 0 && w.columns > 0) readScreens(r, root, w);
    if (r.mDiags.hasErrors()) return w;
    placeScreens(r, w);
    readNodes(r, root, w);
    readSync(r, root, w);
    if (const json* o = r.member(root, "", "overlays", false);
        o && r.object(*o, "/overlays", props("Overlays"))) {
        if (auto it = o->find("legend"); it != o->end())
            readPlacement(r, w, *it, "/overlays/legend", w.overlays.legend);
        if (auto it = o->find("timeLabel"); it != o->end())
            readPlacement(r, w, *it, "/overlays/timeLabel", w.overlays.timeLabel);
        if (auto it = o->find("title"); it != o->end())
            readPlacement(r, w, *it, "/overlays/title", w.overlays.title);
    }
    return w;
}

}  // namespace

const std::map<std::string, std::vector<std::string>>& acceptedWallProperties() {
    static const std::map<std::string, std::vector<std::string>> table = {
        {"Wall",
         {"$schema", "version", "include", "grid", "screenDefaults", "mullionMm", "screens",
          "nodes", "leader", "sync", "overlays"}},
        {"Grid", {"rows", "columns"}},
        {"ScreenDefaults", {"pixels", "activeMm"}},
        {"Screen",
         {"id", "row", "column", "pixels", "activeMm", "positionMm", "yaw", "pitch", "roll"}},
        {"Node", {"id", "screens"}},
        {"Sync", {"state", "ready", "deadlineMs"}},
        {"Overlays", {"legend", "timeLabel", "title"}},
        {"Placement", {"screen", "canvas"}},
    };
    return table;
}

int Wall::findScreen(const std::string& id) const {
    for (std::size_t i = 0; i < screens.size(); ++i)
        if (screens[i].id == id) return int(i);
    return -1;
}

Result<Wall> parseWall(std::string_view text, const std::filesystem::path& name) {
    try {
        Diagnostics diags;
        config::LoadedDocument doc = config::loadDocument(text, name, diags);
        if (diags.hasErrors() || doc.value.is_null()) return diags;
        Reader r(doc.sourceMap, diags);
        Wall w = build(doc.value, r, name.string());
        if (diags.hasErrors()) return diags;
        return {std::move(w), std::move(diags)};
    } catch (const std::exception& e) {
        Diagnostics d;
        d.error("WALL_INTERNAL", name.string(), "", std::string("internal error: ") + e.what());
        return d;
    }
}

Result<Wall> readWall(const std::filesystem::path& file) {
    std::string why;
    auto text = config::readTextFile(file, kMaxWallFileBytes, why);
    if (!text) {
        Diagnostics d;
        d.error("WALL_FILE", file.string(), "", "wall file " + why);
        return d;
    }
    return parseWall(*text, file);
}

}  // namespace kiosk::wall
