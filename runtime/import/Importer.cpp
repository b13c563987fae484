#include "runtime/import/Importer.h"

#include "runtime/core/Progress.h"
#include "runtime/core/TimeParse.h"
#include "runtime/import/GdalRaster.h"
#include "runtime/import/ImportSteps.h"
#include "runtime/import/SequenceSources.h"
#include "runtime/import/SourceUnits.h"
#include "runtime/import/TempStore.h"
#include "runtime/io/StoreWriter.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>

namespace kiosk::import {

namespace fs = std::filesystem;

static Diagnostics importSequenceImpl(const std::vector<std::string>& sources,
                                      const ImportOptions& o) {
    initGdal();
    Diagnostics d;
    if (o.name.empty()) {
        d.error("IMPORT_USAGE", "", "--name", "sequence needs --name");
        return d;
    }
    if (!io::StoreWriter::validTableName(o.name)) {
        d.error("IMPORT_USAGE", "", "--name",
                "sequence name must be letters, digits and '_' (e.g. flood_depth)");
        return d;
    }
    if (sources.size() == 1 && lowerExt(sources[0]) == ".sww") return importSww(sources[0], o);
    auto frames = expandSources(sources, o);
    if (!frames) return frames.diagnostics;
    {
        std::vector<double> times;
        std::vector<std::string> files;
        for (const auto& f : *frames) {
            times.push_back(*f.time);
            files.push_back(f.file);
        }
        d = checkTimes(times, files);
        if (d.hasErrors()) return d;
    }
    const bool anyCsv =
        std::any_of(frames->begin(), frames->end(), [](const Frame& f) { return f.csvGrid; });
    const bool categorical = o.categorical.value_or(anyCsv);
    std::optional<std::string> like = o.gridLike;
    if (anyCsv && !like) like = findLike(frames->front().file);
    if (anyCsv && !like) {
        d.error("IMPORT_NO_GEOREF", frames->front().file, "",
                "CSV grid has no georeferencing (give --like RASTER with the same grid, e.g. the "
                "landscape's elevation.asc)");
        return d;
    }
    Diagnostics warnings;
    Progress progress(o.quiet);
    d = withTempStore(o.store, [&](io::StoreWriter& w) -> Diagnostics {
        Diagnostics e;
        io::SequenceSpec spec;
        spec.name = o.name;
        spec.variable = o.variable.empty() ? (anyCsv ? "burn_state" : "value") : o.variable;
        spec.categorical = categorical;
        spec.description = "imported from " + fs::path(frames->front().file).filename().string();
        SequenceUnits units(o.units, w.sequenceUnits(o.name), categorical, o.name,
                            o.store.string());
        e.append(units.start());
        if (e.hasErrors()) return e;
        const auto existing = w.sequenceTimes(o.name);
        e.append(checkAppendsAfter(existing, *frames->front().time, frames->front().file, o.name));
        if (e.hasErrors()) return e;
        GdalDataset likeDs;
        if (like) {
            auto l = openRaster(*like);
            if (!l) return l.diagnostics;
            likeDs = std::move(*l);
        }
        for (std::size_t i = 0; i < frames->size(); ++i) {
            const Frame& fr = (*frames)[i];
            GdalDataset ds;
            if (fr.csvGrid) {
                int gw = 0, gh = 0;
                auto values = readCsvGrid(fr.file, gw, gh);
                if (!values) return values.diagnostics;
                if (gw != GDALGetRasterXSize(raw(likeDs)) ||
                    gh != GDALGetRasterYSize(raw(likeDs))) {
                    e.error("IMPORT_EXTENT_MISMATCH", fr.file, "",
                            "grid is " + std::to_string(gw) + "x" + std::to_string(gh) + " but " +
                                *like + " is " + std::to_string(GDALGetRasterXSize(raw(likeDs))) +
                                "x" + std::to_string(GDALGetRasterYSize(raw(likeDs))));
                    return e;
                }
                std::array<double, 6> gt{};
                GDALGetGeoTransform(raw(likeDs), gt.data());
                const char* wkt = GDALGetProjectionRef(raw(likeDs));
                ds = memRaster(*values, gw, gh, gt, wkt ? wkt : "", std::nullopt);
            } else {
                auto r = openRaster(fr.open);
                if (!r) return r.diagnostics;
                ds = std::move(*r);
                const std::string where =
                    o.variable.empty() ? "band " + std::to_string(fr.band) : o.variable;
                auto declared = bandUnits(raw(ds), fr.band, fr.file, where);
                if (!declared && !o.units) return declared.diagnostics;
                e.append(units.frame(declared ? *declared : "", fr.file, where));
                if (e.hasErrors()) return e;
            }
            // The sequence records the units its first frame states (or --units).
            if (i == 0) {
                spec.units = units.units();
                e.append(w.createSequence(spec));
                if (e.hasErrors()) return e;
            }
            auto range = bandRange(raw(ds), fr.band);
            if (!range) {
                e.error("IMPORT_ALL_NODATA", fr.file, "band " + std::to_string(fr.band),
                        "frame holds no valid value (all nodata)");
                return e;
            }
            PlaceOptions po = placeOptions(o, fr.file);
            po.nearest = categorical;
            auto ps = placeSource(w, std::move(ds), po, o.tileSize, warnings);
            if (!ps) return ps.diagnostics;
            e.append(importSequenceFrame(w, *ps, scalarRows(*ps, fr.band, o.zScale, fr.file), range,
                                         o.name, int(existing.size() + i), *fr.time, spec.units,
                                         categorical, o, fr.file, progress));
            if (e.hasErrors()) return e;
        }
        return e;
    });
    warnings.append(d);
    return warnings;
}

template <class Fn>
static Diagnostics guarded(const std::string& what, Fn&& fn) {
    try {
        return fn();
    } catch (const std::exception& e) {
        Diagnostics d;
        d.error("IMPORT_INTERNAL", what, "", std::string("import aborted: ") + e.what());
        return d;
    }
}

Diagnostics importElevation(const std::string& source, const ImportOptions& o) {
    return guarded(source, [&] { return importElevationSource(source, o); });
}

Diagnostics importImagery(const std::string& source, const ImportOptions& o) {
    return guarded(source, [&] { return importImagerySource(source, o); });
}

Diagnostics importSequence(const std::vector<std::string>& sources, const ImportOptions& o) {
    return guarded(sources.empty() ? std::string() : sources.front(),
                   [&] { return importSequenceImpl(sources, o); });
}

}  // namespace kiosk::import
