// The "transferFunctions" section: stops, classes, presets and colour-map files.
#include "config/ScenarioSections.h"
#include "runtime/color/ColorImport.h"
#include "runtime/color/ColorMapFiles.h"

namespace kiosk::config::reader {

void Reader::transferFunctions(const json& j) {
    for (auto it = j.begin(); it != j.end(); ++it) {
        const std::string ptr = childPointer("/transferFunctions", it.key());
        if (auto def = transfer(*it, ptr, it.key())) mS.transferFunctions[it.key()] = *def;
    }
}

void Reader::reemit(const Diagnostics& d, const std::string& ptr, const std::string& prefix) {
    for (const auto& item : d.items()) {
        std::string msg = prefix + item.message;
        if (item.line > 0) msg = "line " + std::to_string(item.line) + ": " + msg;
        Diagnostic& e = item.severity == Severity::Error ? mC.error(item.code.c_str(), ptr, msg)
                                                         : mC.warning(item.code.c_str(), ptr, msg);
        e.hint = item.hint;
    }
}

std::optional<TransferFunctionDef> Reader::transfer(const json& j, const std::string& ptr,
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
        mC.error("SCENARIO_MISSING", ptr,
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
    if (auto d = o.numbers<2>("domain", kDataValue)) {
        if (!((*d)[0] < (*d)[1]))
            mC.error("SCENARIO_RANGE", o.at("domain"), "domain must be [min, max] with min < max");
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
            auto v = s.num("value", kDataValue, true);
            auto c = s.color("color", true);
            if (v && c) tf.stops.push_back({*v, *c});
            if (v && last && *last > *v)
                mC.error("SCENARIO_RANGE", s.at("value"),
                         "stops must be in increasing value order (" + numberText(*v) + " after " +
                             numberText(*last) + ")");
            if (v) last = v;
        }
    } else if (source == "classes") {
        def.origin = TransferFunctionDef::Origin::Classes;
        const json* arr = o.array("classes");
        if (!arr) return std::nullopt;
        if (arr->empty()) mC.error("SCENARIO_RANGE", o.at("classes"), "give at least one class");
        std::optional<double> last;
        for (std::size_t i = 0; i < arr->size(); ++i) {
            Obj s(mC, (*arr)[i], childPointer(o.at("classes"), i), "ClassBreak");
            auto v = s.num("from", kDataValue, true);
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
        if (domain && !color::hasDataUnits(format)) tf = tf.rescaled(domain->first, domain->second);
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
            auto v = p.num("value", kDataValue, true);
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

std::size_t Reader::errorCount() const {
    std::size_t n = 0;
    for (const auto& d : mC.diags().items())
        if (d.severity == Severity::Error) ++n;
    return n;
}

bool Reader::fileExists(const std::filesystem::path& file, const std::string& ptr) {
    if (!contained(file, ptr)) return false;
    std::error_code ec;
    if (std::filesystem::is_regular_file(file, ec)) return true;
    mC.error(
        "SCENARIO_FILE", ptr,
        "file " + quote(file.string()) +
            (std::filesystem::exists(file, ec) ? " is not a regular file" : " does not exist"));
    return false;
}

}  // namespace kiosk::config::reader
