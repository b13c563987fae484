// What the viewer sees besides the data: viewpoints, camera paths, overlays, lighting, governor.
#include "config/ScenarioSections.h"

namespace kiosk::config::reader {

std::optional<Viewpoint> Reader::viewpoint(const Obj& o, bool targetRequired) {
    Viewpoint v;
    v.pointer = o.ptr();
    assign(v.target, o.numbers<3>("target", kMapCoordinate, targetRequired));
    assign(v.heading, o.num("heading", Range{-360, 360}));
    assign(v.pitch, o.num("pitch", Range{-90, 90}));
    assign(v.range, o.num("range", kMapLength));
    return v;
}

void Reader::viewpoints(const json& j) {
    for (auto it = j.begin(); it != j.end(); ++it) {
        Obj o(mC, *it, childPointer("/viewpoints", it.key()), "Viewpoint");
        if (!o.valid()) continue;
        if (auto v = viewpoint(o, true)) mS.viewpoints[it.key()] = *v;
    }
}

void Reader::cameraPaths(const json& j) {
    for (auto it = j.begin(); it != j.end(); ++it) {
        const std::string ptr = childPointer("/cameraPaths", it.key());
        Obj o(mC, *it, ptr, "CameraPath");
        if (!o.valid()) continue;
        CameraPath path;
        path.pointer = ptr;
        assign(path.interpolation, o.oneOf("interpolation", kCameraInterpolations));
        if (const json* keys = o.array("keys", true)) {
            if (keys->empty()) mC.error("SCENARIO_RANGE", o.at("keys"), "give at least one key");
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

void Reader::camera(const json& j) {
    Obj o(mC, j, "/camera", "Camera");
    if (!o.valid()) return;
    assign(mS.camera.viewpoint, o.name("viewpoint"));
    assign(mS.camera.path, o.name("path"));
    assign(mS.camera.interactive, o.boolean("interactive"));
    assign(mS.camera.fovY, o.num("fovY", Range{1, 170}));
}

void Reader::simpleOverlay(const json& j, const std::string& ptr, SimpleOverlay& out) {
    Obj o(mC, j, ptr, "SimpleOverlay");
    if (!o.valid()) return;
    out.enabled = o.boolean("enabled").value_or(true);
    assign(out.position, o.oneOf("position", kCorners));
}

void Reader::overlays(const json& j) {
    Obj o(mC, j, "/overlays", "Overlays");
    if (!o.valid()) return;
    Overlays& ov = mS.overlays;
    if (const json* l = o.get("legend")) {
        ov.legends.clear();
        auto one = [&](const json& item, const std::string& ptr) {
            Obj lo(mC, item, ptr, "Legend");
            if (!lo.valid()) return;
            LegendOverlay& legend = ov.legends.emplace_back();
            legend.pointer = ptr;
            legend.enabled = lo.boolean("enabled").value_or(true);
            assign(legend.transfer, lo.name("transfer"));
            assign(legend.position, lo.oneOf("position", kCorners));
            assign(legend.title, lo.str("title"));
            assign(legend.layer, lo.name("layer"));
        };
        if (l->is_array()) {
            for (std::size_t i = 0; i < l->size(); ++i)
                one((*l)[i], o.at("legend") + "/" + std::to_string(i));
        } else {
            one(*l, o.at("legend"));
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

std::optional<int> Reader::parseZone(const std::string& tz) {
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

void Reader::governor(const json& j) {
    Obj o(mC, j, "/governor", "Governor");
    if (!o.valid()) return;
    Governor& g = mS.governor;
    assign(g.targetFps, o.num("targetFps", Range{0, 240}));
    assign(g.maxTauFactor, o.num("maxTauFactor", Range{1, 16}));
    assign(g.minRenderScale, o.num("minRenderScale", Range{0.25, 1}));
}

void Reader::lighting(const json& j) {
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

}  // namespace kiosk::config::reader
