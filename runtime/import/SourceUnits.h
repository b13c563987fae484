#pragma once

#include "runtime/core/Result.h"

#include <gdal.h>

#include <optional>
#include <string>

// Units a source states for its values (a GeoTIFF band's unit type, CF `units` through GDAL's
// netCDF driver) and the one text a sequence records in the store, so legends and `info` show
// what the data is in.
namespace kiosk::import {

/**
 * @brief The band's declared units, trimmed ("" when it states none); IMPORT_BAD_UNITS naming
 * `file` and `where` (variable or band) when they cannot be shown (control characters, > 64 bytes).
 */
Result<std::string> bandUnits(GDALDatasetH ds, int band, const std::string& file,
                              const std::string& where);

/**
 * @brief Decides a sequence's stored units frame by frame. --units wins (one warning when the
 * source says otherwise); else the first frame that states units sets them and a later frame
 * stating different ones is IMPORT_UNITS_MISMATCH naming that file. Frames appended to a sequence
 * already in the store must agree with its units. Categorical data is "class" unless --units.
 */
class SequenceUnits {
public:
    /**
     * @param given  --units
     * @param stored units of the sequence already in the store (nullopt: a new sequence)
     */
    SequenceUnits(std::optional<std::string> given, std::optional<std::string> stored,
                  bool categorical, std::string sequence, std::string store);

    /** @brief Checks --units against itself and the stored sequence. */
    Diagnostics start() const;
    /** @brief One frame's declared units ("" = none stated). */
    Diagnostics frame(const std::string& declared, const std::string& file,
                      const std::string& where);
    /** @brief What the store records for the sequence (as far as the frames seen so far tell). */
    const std::string& units() const noexcept { return mUnits; }

private:
    std::optional<std::string> mGiven, mStored;
    bool mCategorical = false;
    std::string mSequence, mStore, mUnits, mFirstFile;
    bool mFromFrame = false, mWarned = false;
};

}  // namespace kiosk::import
