#pragma once

#include "runtime/core/Result.h"
#include "runtime/import/Pyramid.h"
#include "runtime/io/StoreTypes.h"

#include <optional>
#include <string>
#include <vector>

namespace kiosk::import {

/**
 * @brief ANUGA SWW model output (NetCDF): a triangle mesh with stage per time step.
 *
 * Reads x, y (+ xllcorner/yllcorner), volumes, elevation (static [points] or per step
 * [time][points], or `z` in old files), stage [time][points] and time (+ starttime).
 * Stage is read one step at a time, so memory is O(points), not O(points x steps).
 */
class SwwMesh {
public:
    /** @brief Errors: IMPORT_UNREADABLE, IMPORT_SWW (missing variable, bad indices). */
    static Result<SwwMesh> open(const std::string& path);

    const std::string& path() const { return mPath; }
    int steps() const { return int(mTimes.size()); }
    /** @brief Model times in seconds (time + starttime). */
    const std::vector<double>& times() const { return mTimes; }
    double startTime() const { return mStartTime; }
    /** @brief UTM EPSG code from the zone attributes, 0 if unknown. */
    int epsg() const { return mEpsg; }
    void bounds(double& minX, double& minY, double& maxX, double& maxY) const;
    std::size_t points() const { return mX.size(); }
    std::size_t triangles() const { return mTri.size() / 3; }
    double x(std::size_t i) const { return mX[i]; }
    double y(std::size_t i) const { return mY[i]; }
    const std::vector<int>& triangleIndices() const { return mTri; }

    /**
     * @brief Bed elevation at every point: the static variable, or step `step` of a per-step one
     * (dam-break models change the bed). IMPORT_SWW on a read error, IMPORT_NAN on NaN.
     */
    Result<std::vector<float>> elevation(int step = 0) const;
    /** @brief depth = stage - elevation at every point for one step (NaN-free). */
    Result<std::vector<float>> depth(int step) const;
    /**
     * @brief Flow speed |(xmomentum, ymomentum)| / depth (m/s) at every point for one step; 0
     * where the depth is below `wetThreshold` (ANUGA's momentum is depth-integrated: dividing by
     * a vanishing depth gives noise, not speed). IMPORT_SWW when the file has no momentum
     * (old-format files store stage only).
     */
    Result<std::vector<float>> velocity(int step, double wetThreshold) const;

    /**
     * @brief Rows of a rasterised step on a grid window: pixel centres inside a triangle get the
     * linear interpolation of its vertex depths; depths below `wetThreshold` are 0 (dry);
     * pixels outside the mesh are NaN. Pass -infinity as `wetThreshold` to rasterise values that
     * are not depths (bed elevation) unchanged.
     */
    ScalarRowSource rasterize(const io::TileGrid& grid, const GridWindow& window,
                              std::vector<float> depth, double wetThreshold) const;

private:
    /** @brief One point variable (one step of it when `perStep`), NaN-free. */
    Result<std::vector<float>> readPoints(const std::string& var, bool perStep, int step) const;

    std::string mPath;
    std::vector<double> mX, mY;
    std::vector<int> mTri;
    std::vector<double> mTimes;
    double mStartTime = 0;
    int mEpsg = 0;
    bool mElevationPerStep = false;
    std::string mElevationVar;
};

}  // namespace kiosk::import
