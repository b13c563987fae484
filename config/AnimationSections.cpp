// The time-keyed sections: "clock", "lenses" and "projectiveMappings".
#include "config/ScenarioSections.h"

namespace kiosk::config::reader {

void Reader::clock(const json& j) {
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

std::vector<std::string> Reader::layerIds(const Obj& o, const std::string& key) {
    // The meaning check (ComparisonChecks.cpp) resolves them, naming /.../key/k.
    std::vector<std::string> ids;
    const json* j = o.get(key);
    if (!j) return ids;
    if (!j->is_array()) {
        mC.error("SCENARIO_TYPE", o.at(key), "expected an array of layer ids, got " + typeName(*j));
        return ids;
    }
    for (std::size_t i = 0; i < j->size(); ++i) {
        const json& e = (*j)[i];
        if (!e.is_string() || e.get<std::string>().empty())
            mC.error("SCENARIO_TYPE", childPointer(o.at(key), i),
                     "expected a layer id (non-empty string), got " + typeName(e));
        else
            ids.push_back(e.get<std::string>());
    }
    return ids;
}

void Reader::lenses(const json& arr) {
    for (std::size_t i = 0; i < arr.size(); ++i) {
        const std::string ptr = childPointer("/lenses", i);
        Obj o(mC, arr[i], ptr, "Lens");
        if (!o.valid()) continue;
        Lens l;
        l.pointer = ptr;
        assign(l.id, o.name("id", true));
        assign(l.kind, o.oneOf("kind", kLensKinds, true));
        auto shape = o.oneOf("shape", kLensShapes);
        assign(l.center, o.numbers<2>("center", kMapCoordinate, true));
        auto radius = o.num("radius", kMapLength);
        auto radii = o.numbers<2>("radii", kMapLength);
        l.shape = shape.value_or(o.has("radii") ? LensShape::Ellipse : LensShape::Circle);
        if (l.shape == LensShape::Swipe && (o.has("radius") || o.has("radii")))
            mC.error("SCENARIO_CONFLICT", ptr,
                     "a swipe lens is a line through \"center\": no \"radius\" or \"radii\"");
        else if (l.shape == LensShape::Swipe) {
            // The line needs only its point ("center") and direction ("rotation").
        } else if (o.has("radius") && o.has("radii"))
            mC.error("SCENARIO_CONFLICT", ptr,
                     "give \"radius\" (circle) or \"radii\" (ellipse), not both");
        else if (l.shape == LensShape::Circle && !o.has("radius"))
            mC.error("SCENARIO_MISSING", ptr, "a circular lens needs \"radius\"");
        else if (l.shape == LensShape::Ellipse && !o.has("radii"))
            mC.error("SCENARIO_MISSING", ptr, "an elliptical lens needs \"radii\"");
        if (radius) l.radii = {*radius, *radius};
        if (radii) l.radii = *radii;
        assign(l.rotation, o.num("rotation", Range{-360, 360}));
        assign(l.softEdge, o.num("softEdge", kMapWidth));
        assign(l.raise, o.num("raise", kUnit));
        assign(l.lower, o.num("lower", kUnit));
        if (l.kind == LensKind::Comparison) {
            l.insideStack = layerIds(o, "inside");
            l.outsideStack = layerIds(o, "outside");
            if (!o.has("inside"))
                mC.error("SCENARIO_MISSING", ptr,
                         "a comparison lens needs \"inside\" (the layer ids drawn inside it)");
        } else {
            assign(l.inside, o.name("inside"));
            assign(l.outside, o.name("outside"));
        }
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
                key.center = ko.numbers<2>("center", kMapCoordinate);
                if (auto r = ko.num("radius", kMapLength)) key.radii = Vec2{*r, *r};
                if (auto r = ko.numbers<2>("radii", kMapLength)) key.radii = r;
                if (key.radii && l.shape == LensShape::Swipe)
                    mC.error("SCENARIO_CONFLICT", ko.ptr(), "a swipe lens has no radius to key");
                key.rotation = ko.num("rotation", Range{-360, 360});
                l.keys.push_back(key);
            }
            keyOrder(l.keys, o.at("keys"));
        }
        mS.lenses.push_back(std::move(l));
    }
}

void Reader::mappings(const json& arr) {
    for (std::size_t i = 0; i < arr.size(); ++i) {
        const std::string ptr = childPointer("/projectiveMappings", i);
        Obj o(mC, arr[i], ptr, "ProjectiveMapping");
        if (!o.valid()) continue;
        ProjectiveMapping m;
        m.pointer = ptr;
        assign(m.id, o.name("id", true));
        // A route brings its own geometry; an image or a route its own data layer.
        const bool routed = o.has("route");
        assign(m.origin, o.numbers<3>("origin", kMapCoordinate, !routed));
        assign(m.u, o.numbers<3>("u", kMapCoordinate, !routed));
        assign(m.v, o.numbers<3>("v", kMapCoordinate, !routed));
        assign(m.textureMatrix, o.numbers<9>("textureMatrix", kMatrixEntry));
        if (auto img = o.str("image")) {
            m.image = mC.resolve(o.at("image"), *img);
            fileExists(m.image, o.at("image"));
        }
        if (const json* r = o.object("route")) m.route = route(*r, o.at("route"));
        m.contextMatrix = o.numbers<16>("contextMatrix", kMatrixEntry);
        assign(m.layer, o.name("layer"));
        if (const json* d = o.get("data", !routed && !o.has("image") && !o.has("layer")))
            assign(m.data, source(*d, o.at("data")));
        assign(m.transfer, o.name("transfer"));
        assign(m.colorMatrix, o.numbers<16>("colorMatrix", kMatrixEntry));
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
                key.origin = ko.numbers<3>("origin", kMapCoordinate);
                key.u = ko.numbers<3>("u", kMapCoordinate);
                key.v = ko.numbers<3>("v", kMapCoordinate);
                key.textureMatrix = ko.numbers<9>("textureMatrix", kMatrixEntry);
                key.colorMatrix = ko.numbers<16>("colorMatrix", kMatrixEntry);
                key.opacity = ko.num("opacity", kUnit);
                m.keys.push_back(key);
            }
            keyOrder(m.keys, o.at("keys"));
        }
        if (o.has("layer")) liveLayerMapping(o, m);
        mS.projectiveMappings.push_back(std::move(m));
    }
}

MappingRoute Reader::route(const json& j, const std::string& ptr) {
    MappingRoute r;
    r.pointer = ptr;
    Obj o(mC, j, ptr, "MappingRoute");
    if (!o.valid()) return r;
    if (const json* pts = o.array("points", true)) {
        for (std::size_t i = 0; i < pts->size(); ++i)
            if (auto p = readNumbers<2>(mC, (*pts)[i], childPointer(o.at("points"), i),
                                        kMapCoordinate, "point"))
                r.points.push_back(*p);
        if (pts->size() < 2)
            mC.error("SCENARIO_RANGE", o.at("points"), "a route needs at least 2 way points");
    }
    assign(r.width, o.num("width", Range{0, 1e6, true, false}));
    assign(r.pointRadius, o.num("pointRadius", Range{0, 1e6, false, false}));
    return r;
}

}  // namespace kiosk::config::reader
