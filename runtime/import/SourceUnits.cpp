#include "runtime/import/SourceUnits.h"

#include "runtime/core/Units.h"

namespace kiosk::import {

Result<std::string> bandUnits(GDALDatasetH ds, int band, const std::string& file,
                              const std::string& where) {
    const char* raw = GDALGetRasterUnitType(GDALGetRasterBand(ds, band));
    std::string why;
    auto clean = cleanUnits(raw ? raw : "", &why);
    if (clean) return *clean;
    Diagnostics d;
    d.error("IMPORT_BAD_UNITS", file, where, "the units the source states " + why).hint =
        "state them with --units TEXT";
    return d;
}

SequenceUnits::SequenceUnits(std::optional<std::string> given, std::optional<std::string> stored,
                             bool categorical, std::string sequence, std::string store)
    : mGiven(std::move(given)),
      mStored(std::move(stored)),
      mCategorical(categorical),
      mSequence(std::move(sequence)),
      mStore(std::move(store)) {
    if (mGiven)
        mUnits = cleanUnits(*mGiven).value_or(*mGiven);
    else if (mStored)
        mUnits = *mStored;
    else if (mCategorical)
        mUnits = "class";
}

Diagnostics SequenceUnits::start() const {
    Diagnostics d;
    if (mGiven) {
        std::string why;
        if (!cleanUnits(*mGiven, &why)) {
            d.error("IMPORT_USAGE", "", "--units", "--units " + why);
            return d;
        }
        // An existing sequence keeps its units: appending frames in other units would mix them.
        if (mStored && !mStored->empty() && *mStored != mUnits && !sameUnits(*mStored, mUnits))
            d.error("IMPORT_UNITS_MISMATCH", mStore, mSequence,
                    "sequence \"" + mSequence + "\" is stored in '" + *mStored + "' but --units " +
                        mUnits + " was given")
                .hint = "import the frames into a new sequence (--name)";
    }
    return d;
}

Diagnostics SequenceUnits::frame(const std::string& declared, const std::string& file,
                                 const std::string& where) {
    Diagnostics d;
    if (declared.empty() || mCategorical) return d;
    if (mGiven) {
        if (!mWarned && !sameUnits(declared, mUnits)) {
            d.warning("IMPORT_UNITS_OVERRIDDEN", file, where,
                      "the source states '" + declared + "'; the store records '" + mUnits +
                          "' as --units says");
            mWarned = true;  // once per import, not once per frame
        }
        return d;
    }
    if (mStored) {
        if (!mStored->empty() && !sameUnits(*mStored, declared))
            d.error("IMPORT_UNITS_MISMATCH", file, where,
                    "values are in '" + declared + "' but sequence \"" + mSequence + "\" in " +
                        mStore + " is in '" + *mStored + "'")
                .hint = "import the frames into a new sequence (--name), or state --units";
        return d;
    }
    if (!mFromFrame) {
        mUnits = declared;
        mFirstFile = file;
        mFromFrame = true;
    } else if (!sameUnits(mUnits, declared)) {
        d.error("IMPORT_UNITS_MISMATCH", file, where,
                "values are in '" + declared + "' but " + mFirstFile + " is in '" + mUnits + "'")
            .hint = "frames of one sequence must share units (or state --units)";
    }
    return d;
}

}  // namespace kiosk::import
