#include "config/MeaningCheck.h"

#include "config/StoreGrids.h"
#include "runtime/core/Strings.h"
#include "runtime/core/Units.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <vector>

namespace kiosk::config {

namespace {

std::string quote(const std::string& s) {
    return "\"" + s + "\"";
}

std::string num(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

class Checker {
public:
    Checker(const Scenario& s, const StoreLookup& lookup) : mS(s), mLookup(lookup) {}

    Diagnostics run() {
        for (const auto& [id, store] : mS.stores) {
            if (!mLookup(id))
                error("SCENARIO_STORE_UNAVAILABLE", store.pointer,
                      "store " + quote(id) + " (" + store.path.string() + ") could not be opened");
        }
        terrain();
        for (const auto& l : mS.layers) layer(l);
        for (const auto& m : mS.projectiveMappings) mapping(m);
        return std::move(mDiags);
    }

private:
    Diagnostic& at(Diagnostic& d, const std::string& ptr) {
        const Location l = mS.sourceMap.value(ptr);
        d.file = l.file;
        d.line = l.line;
        d.column = l.column;
        return d;
    }
    Diagnostic& error(const char* code, const std::string& ptr, std::string msg) {
        return at(mDiags.error(code, "", ptr, std::move(msg)), ptr);
    }
    Diagnostic& warning(const char* code, const std::string& ptr, std::string msg) {
        return at(mDiags.warning(code, "", ptr, std::move(msg)), ptr);
    }

    const io::StoreInfo* store(const std::string& id) const {
        return mS.stores.count(id) ? mLookup(id) : nullptr;
    }

    template <class T>
    void unknown(const char* code, const std::string& ptr, const std::string& what,
                 const std::string& name, const std::string& storeId, const std::vector<T>& items) {
        std::vector<std::string> names;
        for (const auto& i : items) names.push_back(i.name);
        auto& e = error(code, ptr,
                        "store " + quote(storeId) + " has no " + what + " " + quote(name) +
                            (names.empty() ? std::string() : " (it has: " + [&] {
                                std::string all;
                                for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
                                return all;
                            }() + ")"));
        if (auto m = closestMatch(name, names)) e.hint = "did you mean " + quote(*m) + "?";
    }

    void terrain() {
        const auto* info = store(mS.terrain.store);
        if (!info) return;
        const auto* l = info->findLayer(mS.terrain.elevation);
        if (!l) {
            unknown("SCENARIO_UNKNOWN_LAYER", "/terrain/elevation", "layer", mS.terrain.elevation,
                    mS.terrain.store, info->layers);
        } else if (l->kind != io::LayerKind::Elevation) {
            error("SCENARIO_LAYER_KIND", "/terrain/elevation",
                  "layer " + quote(l->name) + " is not an elevation layer");
        }
    }

    // Value range of the data a transfer function will colour, with its units.
    struct DataRange {
        double min = 0, max = 0;
        std::string units;
        std::string what;
    };

    void transferFits(const std::string& ptr, const std::string& tfName, const DataRange& r) {
        const TransferFunctionDef* def = mS.findTransfer(tfName);
        if (!def) return;
        const auto& tf = def->function;
        // "metres" and "m", "mm h-1" and "mm/h" are the same units (runtime/core/Units.h).
        if (!tf.units.empty() && !r.units.empty() && tf.units != r.units &&
            !sameUnits(tf.units, r.units))
            error("SCENARIO_UNITS", ptr,
                  "transfer function " + quote(tfName) + " is in " + quote(tf.units) + " but " +
                      r.what + " is in " + quote(r.units));
        if (tf.units.empty() && !r.units.empty() && r.units != "class") {
            // Without units the legend takes the data's (DataUnits.h): only if they agree.
            auto [it, fresh] = mDataUnits.emplace(tfName, std::make_pair(r.units, r.what));
            if (!fresh && !sameUnits(it->second.first, r.units))
                warning("SCENARIO_UNITS", ptr,
                        "transfer function " + quote(tfName) + " states no units and colours " +
                            it->second.second + " in " + quote(it->second.first) + " and " +
                            r.what + " in " + quote(r.units) + "; its legend shows no units")
                    .hint = "give the transfer function \"units\", or one per data set";
        }
        if (!(r.max >= r.min) || !std::isfinite(r.min) || !std::isfinite(r.max)) return;
        const std::string range = "[" + num(r.min) + ", " + num(r.max) + "]";
        const std::string domain = "[" + num(tf.domainMin) + ", " + num(tf.domainMax) + "]";
        if (r.max < tf.domainMin || r.min > tf.domainMax) {
            error("SCENARIO_DOMAIN", ptr,
                  r.what + " spans " + range + ", entirely outside the domain " + domain +
                      " of transfer function " + quote(tfName));
        } else if (r.min < tf.domainMin || r.max > tf.domainMax) {
            warning("SCENARIO_DOMAIN", ptr,
                    r.what + " spans " + range + ", beyond the domain " + domain +
                        " of transfer function " + quote(tfName) +
                        "; values outside take the below/above colours");
        }
    }

    void sequenceTimes(const std::string& ptr, const io::SequenceInfo& seq) {
        if (!mS.clock || seq.frameTimes.empty()) return;
        const double first = seq.frameTimes.front(), last = seq.frameTimes.back();
        const Clock& c = *mS.clock;
        const double end = c.range == RangeBehaviour::Unbounded ? HUGE_VAL : c.end;
        const std::string span = formatIso8601(first) + " .. " + formatIso8601(last);
        const std::string clock = formatIso8601(c.start) + " .. " +
                                  (c.range == RangeBehaviour::Unbounded ? std::string("(unbounded)")
                                                                        : formatIso8601(c.end));
        if (end < first || c.start > last) {
            error("SCENARIO_TIME_RANGE", ptr,
                  "sequence " + quote(seq.name) + " covers " + span + ", which the clock " + clock +
                      " never reaches");
        } else if (c.start < first || end > last) {
            warning("SCENARIO_TIME_RANGE", ptr,
                    "clock " + clock + " runs beyond sequence " + quote(seq.name) + " (" + span +
                        "); the nearest frame is held outside it");
        }
    }

    void source(const std::string& ptr, const SourceRef& src, bool wantSequence,
                const std::string& transfer, const std::string& transferPtr,
                std::optional<LayerKind> kind) {
        const auto* info = store(src.store);
        if (!info) return;
        if (wantSequence || !src.sequence.empty()) {
            const auto* seq = info->findSequence(src.sequence);
            if (!seq) {
                unknown("SCENARIO_UNKNOWN_SEQUENCE", ptr + "/sequence", "sequence", src.sequence,
                        src.store, info->sequences);
                return;
            }
            sequenceTimes(ptr + "/sequence", *seq);
            if (!transfer.empty() && !seq->frameMin.empty()) {
                DataRange r{*std::min_element(seq->frameMin.begin(), seq->frameMin.end()),
                            *std::max_element(seq->frameMax.begin(), seq->frameMax.end()),
                            seq->units, "sequence " + quote(seq->name)};
                transferFits(transferPtr, transfer, r);
            }
            return;
        }
        if (src.layer.empty()) return;
        const auto* l = info->findLayer(src.layer);
        if (!l) {
            unknown("SCENARIO_UNKNOWN_LAYER", ptr + "/layer", "layer", src.layer, src.store,
                    info->layers);
            return;
        }
        if (kind == LayerKind::Thematic && l->kind != io::LayerKind::Imagery)
            error("SCENARIO_LAYER_KIND", ptr + "/layer",
                  "a thematic layer needs an imagery layer; " + quote(l->name) + " is " +
                      (l->kind == io::LayerKind::Elevation ? "elevation" : "a sequence"));
        if (kind == LayerKind::Data && l->kind == io::LayerKind::Imagery)
            error("SCENARIO_LAYER_KIND", ptr + "/layer",
                  "a data layer needs scalar values; " + quote(l->name) + " is imagery");
        if (!transfer.empty() && l->kind != io::LayerKind::Imagery)
            transferFits(transferPtr, transfer,
                         DataRange{l->minValue, l->maxValue, l->units, "layer " + quote(l->name)});
    }

    // A second store is served by the terrain's tile ids: same CRS and tile grid, or refused.
    bool sharesTerrainGrid(const std::string& ptr, const std::string& storeId,
                           const io::StoreInfo& info) {
        if (storeId == mS.terrain.store) return true;
        const auto* terrain = store(mS.terrain.store);
        if (!terrain) return true;  // its own error says why
        if (!sameCrs(terrain->grid, info.grid)) {
            error("SCENARIO_STORE_CRS", ptr,
                  "store " + quote(storeId) + " is in " + crsText(info.grid) +
                      ", the terrain's store " + quote(mS.terrain.store) + " in " +
                      crsText(terrain->grid) + "; a layer's store must share the terrain's CRS")
                .hint = "import it again with geokiosk-import --to-crs set to the terrain's CRS";
            return false;
        }
        if (const std::string why = tileGridDifference(terrain->grid, info.grid); !why.empty()) {
            error("SCENARIO_STORE_GRID", ptr,
                  "store " + quote(storeId) + " has the terrain's CRS but not its tile grid (" +
                      why + "); a layer's store must share the terrain store's tile grid");
            return false;
        }
        return true;
    }

    // A product's options against its sequence (docs/products.md); its transfer function
    // colours the product's values, not the sequence's.
    void product(const Layer& l) {
        const auto* info = store(l.source.store);
        const auto* seq = info ? info->findSequence(l.source.sequence) : nullptr;
        if (!seq) {
            source(l.pointer + "/source", l.source, true, "", "", l.kind);
            return;
        }
        sequenceTimes(l.pointer + "/source/sequence", *seq);
        const ProductOptions& p = l.product;
        if (!p.units.empty() && !sameUnits(p.units, seq->units))
            error("SCENARIO_UNITS", p.pointer + "/units",
                  "threshold stated in " + quote(p.units) + " but sequence " + quote(seq->name) +
                      " is in " + quote(seq->units.empty() ? "(no units)" : seq->units) +
                      "; give the threshold in the sequence's units");
        if (l.kind == LayerKind::Hazard && !p.velocity.empty()) {
            const auto* v = info->findSequence(p.velocity);
            if (!v) {
                unknown("SCENARIO_UNKNOWN_SEQUENCE", p.pointer + "/velocity", "sequence",
                        p.velocity, l.source.store, info->sequences);
            } else if (v->frameTimes != seq->frameTimes) {
                error("SCENARIO_TIME_RANGE", p.pointer + "/velocity",
                      "velocity sequence " + quote(v->name) + " does not have the frames of " +
                          quote(seq->name) + " (" + std::to_string(v->frameTimes.size()) + " and " +
                          std::to_string(seq->frameTimes.size()) + " frames)");
            } else if (!v->units.empty() && !sameUnits(v->units, "m/s")) {
                error("SCENARIO_UNITS", p.pointer + "/velocity",
                      "velocity sequence " + quote(v->name) + " is in " + quote(v->units) +
                          "; the hazard curves need m/s");
            }
        }
        if (l.kind == LayerKind::Hazard && !seq->units.empty() && !sameUnits(seq->units, "m"))
            error("SCENARIO_UNITS", l.pointer + "/source/sequence",
                  "hazard classes need depth in metres; sequence " + quote(seq->name) + " is in " +
                      quote(seq->units));
        if (l.transfer.empty() || seq->frameMin.empty()) return;
        const double lo = *std::min_element(seq->frameMin.begin(), seq->frameMin.end());
        const double hi = *std::max_element(seq->frameMax.begin(), seq->frameMax.end());
        const std::string what = "layer " + quote(l.id);
        switch (l.kind) {
            case LayerKind::Maximum:
                transferFits(l.pointer + "/transfer", l.transfer,
                             DataRange{lo, hi, seq->units, "maximum of " + quote(seq->name)});
                break;
            case LayerKind::Hazard:
                transferFits(l.pointer + "/transfer", l.transfer,
                             DataRange{1, 6, "", "hazard classes H1-H6"});
                break;
            default: {
                // Times since the clock start: the range is known only once replayed.
                DataRange r{0, -1, p.timeUnits, what + " (time)"};
                transferFits(l.pointer + "/transfer", l.transfer, r);
                if (p.hasThreshold && (p.threshold > hi || p.threshold < lo))
                    warning("SCENARIO_DOMAIN", p.pointer + "/threshold",
                            "threshold " + num(p.threshold) + " is outside the values of " +
                                quote(seq->name) + " [" + num(lo) + ", " + num(hi) +
                                "]; the product stays empty or full");
            }
        }
    }

    void layer(const Layer& l) {
        if (l.kind == LayerKind::Difference) return;  // no source: its operands are layers
        // (Mappings place their data by their own rectangle: any store will do for them.)
        if (const auto* info = store(l.source.store);
            info && !sharesTerrainGrid(l.pointer + "/source/store", l.source.store, *info))
            return;
        if (isProductKind(l.kind)) return product(l);
        source(l.pointer + "/source", l.source, l.kind == LayerKind::Sequence, l.transfer,
               l.pointer + "/transfer", l.kind);
    }

    void mapping(const ProjectiveMapping& m) {
        // An image file or a route brings its own data layer (checked by the reader).
        if (m.data.store.empty() && m.data.layer.empty() && m.data.sequence.empty()) return;
        source(m.pointer + "/data", m.data, false, m.transfer, m.pointer + "/transfer",
               std::nullopt);
    }

    const Scenario& mS;
    const StoreLookup& mLookup;
    Diagnostics mDiags;
    std::map<std::string, std::pair<std::string, std::string>> mDataUnits;  ///< tf: units, what
};

}  // namespace

Diagnostics checkMeaning(const Scenario& scenario, const StoreLookup& lookup) {
    if (!lookup) return {};
    return Checker(scenario, lookup).run();
}

}  // namespace kiosk::config
