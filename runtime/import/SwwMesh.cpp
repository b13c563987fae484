#include "runtime/import/SwwMesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <netcdf.h>
#include <string>
#include <vector>

namespace kiosk::import {

namespace {

struct NcFile {
    int id = -1;
    ~NcFile() {
        if (id >= 0) nc_close(id);
    }
};

double attDouble(int nc, const char* name, double fallback) {
    double v = 0;
    return nc_get_att_double(nc, NC_GLOBAL, name, &v) == NC_NOERR ? v : fallback;
}

/**
 * libnetcdf allocates whatever a classic-format header claims (a 60-byte file asking for 926
 * million dimensions makes nc_open calloc 7.4 GB: found by tests/fuzz/SwwFuzzer.cpp). Walk the
 * header of a classic file (CDF1/CDF2/CDF5) and refuse it when a count or name length cannot fit
 * in the bytes that follow, and when a variable's shape would make nc_open divide by zero (a
 * length-0 dimension before the last of a shape, an unknown type: libnetcdf 4.9's NC_check_vlen
 * multiplies the sizes up and divides by the product; SIGFPE, found by SwwFuzzSmoke); anything
 * else (HDF5-based netCDF-4, a header cut short) is left to nc_open. False with `why` set when
 * the header lies.
 */
bool classicHeaderFits(const std::string& path, std::string& why) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return true;
    std::vector<unsigned char> h(1 << 20);  // counts are checked against the whole file below
    const std::size_t got = std::fread(h.data(), 1, h.size(), f);
    std::fseek(f, 0, SEEK_END);
    const long fileSize = std::ftell(f);
    std::fclose(f);
    h.resize(got);
    if (got < 8 || h[0] != 'C' || h[1] != 'D' || h[2] != 'F') return true;
    const int version = h[3];
    if (version != 1 && version != 2 && version != 5) return true;
    const std::size_t countBytes = version == 5 ? 8 : 4;
    std::size_t p = 4 + countBytes;  // magic, numrecs
    const std::uint64_t total = fileSize > 0 ? std::uint64_t(fileSize) : got;
    bool ok = true;
    // The whole file is in `h` and the header runs past its end: libnetcdf reads the missing
    // bytes as zeros, so 15 bytes claiming 14.9 million dimensions took 1 GB and 2 s to open.
    auto inside = [&](std::size_t end) {
        if (end <= h.size()) return true;
        if (h.size() == total) {
            why = "header ends before the lists it declares (truncated file)";
            ok = false;
        }
        return false;
    };
    auto u = [&](std::size_t n, std::uint64_t& v) {
        if (!inside(p + n)) return false;
        v = 0;
        for (std::size_t i = 0; i < n; ++i) v = (v << 8) | h[p + i];
        p += n;
        return true;
    };
    // Each element of a list takes at least `minBytes`; a count beyond the file is a lie.
    auto count = [&](std::uint64_t& n, std::uint64_t minBytes, const char* what) {
        std::uint64_t tag = 0;
        if (!u(4, tag) || !u(countBytes, n)) return false;
        if (n > (total - std::min<std::uint64_t>(total, p)) / minBytes) {
            why = std::string("header claims ") + std::to_string(n) + " " + what +
                  " (larger than the file)";
            ok = false;
            return false;
        }
        return true;
    };
    auto name = [&]() {
        std::uint64_t len = 0;
        if (!u(countBytes, len)) return false;
        if (len > total - std::min<std::uint64_t>(total, p)) {
            why = "header claims a name of " + std::to_string(len) + " bytes (larger than the file)";
            ok = false;
            return false;
        }
        p += (len + 3) / 4 * 4;
        return inside(p);
    };
    auto attributes = [&]() {
        std::uint64_t n = 0;
        if (!count(n, 12, "attributes")) return false;
        for (std::uint64_t i = 0; i < n; ++i) {
            std::uint64_t type = 0, len = 0;
            if (!name() || !u(4, type) || !u(countBytes, len)) return false;
            static const std::uint64_t kSize[] = {0, 1, 1, 2, 4, 4, 8, 1, 2, 4, 8, 8};
            const std::uint64_t size = type < 12 ? kSize[type] : 0;
            if (size == 0) return false;  // nc_open refuses it
            if (len > (total - std::min<std::uint64_t>(total, p)) / size) {
                why = "header claims an attribute of " + std::to_string(len) +
                      " values (larger than the file)";
                ok = false;
                return false;
            }
            p += (len * size + 3) / 4 * 4;
        }
        return inside(p);
    };
    std::uint64_t dims = 0;
    if (!count(dims, 8, "dimensions")) return ok;
    std::vector<std::uint64_t> dimLength;  // 0: the record (unlimited) dimension
    for (std::uint64_t i = 0; i < dims; ++i) {
        std::uint64_t len = 0;
        if (!name() || !u(countBytes, len)) return ok;
        dimLength.push_back(len);
    }
    if (!attributes()) return ok;
    std::uint64_t vars = 0;
    if (!count(vars, 16, "variables")) return ok;
    for (std::uint64_t i = 0; i < vars; ++i) {
        std::uint64_t ndims = 0, type = 0, vsize = 0, begin = 0;
        if (!name() || !u(countBytes, ndims)) return ok;
        if (ndims > (total - std::min<std::uint64_t>(total, p)) / 4) {
            why = "header claims a variable of " + std::to_string(ndims) +
                  " dimensions (larger than the file)";
            return false;
        }
        std::vector<std::uint64_t> shape;
        for (std::uint64_t k = 0; k < ndims; ++k) {
            std::uint64_t id = 0;
            if (!u(countBytes, id)) return ok;
            if (id >= dimLength.size()) return ok;  // nc_open refuses it
            shape.push_back(dimLength[std::size_t(id)]);
        }
        if (!attributes() || !u(4, type) || !u(countBytes, vsize) ||
            !u(version == 1 ? 4 : 8, begin))
            return ok;
        if (type == 0 || type > (version == 5 ? 11u : 6u)) {
            why = "header gives a variable the unknown type " + std::to_string(type);
            return false;
        }
        // What NC_check_vlen divides by: the product of the sizes before the last (past the
        // record dimension, which is first when a variable has it).
        const std::size_t first = !shape.empty() && shape[0] == 0 ? 1 : 0;
        for (std::size_t k = first; k + 1 < shape.size(); ++k)
            if (shape[k] == 0) {
                why = "header gives a variable a dimension of length 0 inside its shape";
                return false;
            }
    }
    return ok;
}

}  // namespace

Result<SwwMesh> SwwMesh::open(const std::string& path) {
    Diagnostics d;
    NcFile nc;
    if (std::string why; !classicHeaderFits(path, why)) {
        d.error("IMPORT_UNREADABLE", path, "",
                "cannot read SWW: " + why);
        return d;
    }
    int rc = nc_open(path.c_str(), NC_NOWRITE, &nc.id);
    if (rc != NC_NOERR) {
        nc.id = -1;
        d.error("IMPORT_UNREADABLE", path, "", std::string("cannot read SWW: ") + nc_strerror(rc));
        return d;
    }
    auto var = [&](const char* name, int& id, int& ndims) -> bool {
        if (nc_inq_varid(nc.id, name, &id) != NC_NOERR) return false;
        return nc_inq_varndims(nc.id, id, &ndims) == NC_NOERR;
    };
    auto dimLen = [&](int varId, int which) -> std::size_t {
        int dims[NC_MAX_VAR_DIMS];
        nc_inq_vardimid(nc.id, varId, dims);
        std::size_t n = 0;
        nc_inq_dimlen(nc.id, dims[which], &n);
        return n;
    };
    SwwMesh m;
    m.mPath = path;
    int xId, yId, volId, timeId, stageId, nd;
    if (!var("x", xId, nd) || !var("y", yId, nd) || !var("volumes", volId, nd) ||
        !var("time", timeId, nd) || !var("stage", stageId, nd) || nd != 2) {
        d.error("IMPORT_SWW", path, "",
                "not an ANUGA SWW file (needs x, y, volumes, time and stage[time][points])");
        return d;
    }
    const std::size_t np = dimLen(xId, 0), nt = dimLen(timeId, 0), nv = dimLen(volId, 0);
    // Every read below fills a buffer sized from these: shapes must agree exactly, or a file
    // whose `y` is longer than `x` (or whose triangles have 4 corners) overruns it. The sizes
    // are bounded so that a small file claiming huge dimensions is refused, not allocated.
    int ndY = 0, ndVol = 0, ndTime = 0;
    nc_inq_varndims(nc.id, yId, &ndY);
    nc_inq_varndims(nc.id, volId, &ndVol);
    nc_inq_varndims(nc.id, timeId, &ndTime);
    int ndX = 0;
    nc_inq_varndims(nc.id, xId, &ndX);
    if (ndX != 1 || ndY != 1 || ndVol != 2 || ndTime != 1 || dimLen(yId, 0) != np ||
        dimLen(volId, 1) != 3 || dimLen(stageId, 0) != nt || dimLen(stageId, 1) != np) {
        d.error("IMPORT_SWW", path, "",
                "variables have inconsistent shapes (x[points], y[points], volumes[triangles][3], "
                "time[steps], stage[steps][points])");
        return d;
    }
    // A header can claim any size; the data must be in the file (netCDF-4 may compress it:
    // allow 64:1), so a 600-byte file cannot make this allocate gigabytes.
    constexpr std::size_t kMaxPoints = std::size_t(1) << 24, kMaxSteps = std::size_t(1) << 20;
    std::error_code sizeError;
    const std::uintmax_t fileBytes = std::filesystem::file_size(path, sizeError);
    const std::uintmax_t budget = sizeError ? 0 : fileBytes * 64;
    if (np == 0 || nv == 0 || nt == 0 || np > kMaxPoints || nv > kMaxPoints || nt > kMaxSteps ||
        (np * 2 + nv * 3 + nt) * 4 > budget) {
        d.error("IMPORT_SWW", path, "",
                "mesh sizes out of range (" + std::to_string(np) + " points, " +
                    std::to_string(nv) + " triangles, " + std::to_string(nt) + " steps)");
        return d;
    }
    m.mX.resize(np);
    m.mY.resize(np);
    m.mTri.resize(nv * 3);
    m.mTimes.resize(nt);
    if (nc_get_var_double(nc.id, xId, m.mX.data()) != NC_NOERR ||
        nc_get_var_double(nc.id, yId, m.mY.data()) != NC_NOERR ||
        nc_get_var_int(nc.id, volId, m.mTri.data()) != NC_NOERR ||
        nc_get_var_double(nc.id, timeId, m.mTimes.data()) != NC_NOERR) {
        d.error("IMPORT_SWW", path, "", "cannot read the mesh variables");
        return d;
    }
    for (int i : m.mTri)
        if (i < 0 || std::size_t(i) >= np) {
            d.error("IMPORT_SWW", path, "volumes", "triangle refers to a point out of range");
            return d;
        }
    const double xll = attDouble(nc.id, "xllcorner", 0), yll = attDouble(nc.id, "yllcorner", 0);
    for (auto& v : m.mX) v += xll;
    for (auto& v : m.mY) v += yll;
    m.mStartTime = attDouble(nc.id, "starttime", 0);
    for (auto& t : m.mTimes) t += m.mStartTime;
    const int zone = int(attDouble(nc.id, "zone", -1));
    if (zone >= 1 && zone <= 60)
        m.mEpsg = (attDouble(nc.id, "false_northing", 0) > 0 ? 32700 : 32600) + zone;
    int eId;
    if (var("elevation", eId, nd))
        m.mElevationVar = "elevation";
    else if (var("z", eId, nd))
        m.mElevationVar = "z";
    else {
        d.error("IMPORT_SWW", path, "", "no elevation (or z) variable");
        return d;
    }
    // Static elevation is read whole into a points-sized buffer: its length must be exactly that.
    if ((nd == 1 && dimLen(eId, 0) != np) || (nd == 2 && dimLen(eId, 1) != np) || nd < 1 ||
        nd > 2) {
        d.error("IMPORT_SWW", path, m.mElevationVar, "shape is not [points] or [steps][points]");
        return d;
    }
    m.mElevationPerStep = nd == 2;
    return m;
}

void SwwMesh::bounds(double& minX, double& minY, double& maxX, double& maxY) const {
    minX = *std::min_element(mX.begin(), mX.end());
    maxX = *std::max_element(mX.begin(), mX.end());
    minY = *std::min_element(mY.begin(), mY.end());
    maxY = *std::max_element(mY.begin(), mY.end());
}

Result<std::vector<float>> SwwMesh::readPoints(const std::string& var, bool perStep,
                                               int step) const {
    // Reopened per call: the mesh keeps no handle, so it can be shared by encoder threads.
    Diagnostics d;
    NcFile nc;
    if (nc_open(mPath.c_str(), NC_NOWRITE, &nc.id) != NC_NOERR) {
        nc.id = -1;
        d.error("IMPORT_UNREADABLE", mPath, "", "cannot reopen SWW");
        return d;
    }
    const std::size_t np = mX.size();
    std::vector<float> values(np);
    int id = -1;
    int rc = nc_inq_varid(nc.id, var.c_str(), &id);
    const std::size_t start[2] = {std::size_t(std::max(step, 0)), 0}, count[2] = {1, np};
    if (rc == NC_NOERR)
        rc = perStep ? nc_get_vara_float(nc.id, id, start, count, values.data())
                     : nc_get_var_float(nc.id, id, values.data());
    if (rc != NC_NOERR) {
        d.error("IMPORT_SWW", mPath, var + " step " + std::to_string(step),
                "cannot read " + var + ": " + nc_strerror(rc));
        return d;
    }
    for (std::size_t i = 0; i < np; ++i)
        if (!std::isfinite(values[i])) {
            d.error("IMPORT_NAN", mPath, var + " step " + std::to_string(step),
                    var + " is NaN at point " + std::to_string(i));
            return d;
        }
    return values;
}

Result<std::vector<float>> SwwMesh::depth(int step) const {
    auto stage = readPoints("stage", true, step);
    if (!stage) return stage;
    auto elev = elevation(step);
    if (!elev) return elev;
    for (std::size_t i = 0; i < stage->size(); ++i) (*stage)[i] -= (*elev)[i];
    return stage;
}

Result<std::vector<float>> SwwMesh::velocity(int step, double wetThreshold) const {
    auto depthNow = depth(step);
    if (!depthNow) return depthNow;
    auto xm = readPoints("xmomentum", true, step);
    if (!xm) return xm;
    auto ym = readPoints("ymomentum", true, step);
    if (!ym) return ym;
    std::vector<float>& out = *depthNow;
    const double wet = std::max(wetThreshold, 1e-6);
    for (std::size_t i = 0; i < out.size(); ++i) {
        const double d = out[i];
        out[i] = d < wet ? 0.0f : float(std::hypot(double((*xm)[i]), double((*ym)[i])) / d);
    }
    return depthNow;
}

Result<std::vector<float>> SwwMesh::elevation(int step) const {
    return readPoints(mElevationVar, mElevationPerStep, step);
}

ScalarRowSource SwwMesh::rasterize(const io::TileGrid& grid, const GridWindow& window,
                                   std::vector<float> depth, double wetThreshold) const {
    // Bucket triangles by 256-row band so a strip only visits triangles that can touch it.
    const double p = grid.levels.back().pixelXSize;
    constexpr int kBand = 256;
    const int bands = (window.height() + kBand - 1) / kBand;
    auto buckets = std::make_shared<std::vector<std::vector<int>>>(std::size_t(std::max(bands, 1)));
    const std::size_t nt = mTri.size() / 3;
    auto rowOf = [&](double y) { return (grid.maxY - y) / p - 0.5 - window.y0; };
    for (std::size_t t = 0; t < nt; ++t) {
        double lo = 1e300, hi = -1e300;
        for (int k = 0; k < 3; ++k) {
            const double r = rowOf(mY[std::size_t(mTri[t * 3 + std::size_t(k)])]);
            lo = std::min(lo, r);
            hi = std::max(hi, r);
        }
        const int b0 = std::max(0, int(std::floor(lo)) / kBand);
        const int b1 = std::min(bands - 1, int(std::ceil(hi)) / kBand);
        for (int b = b0; b <= b1; ++b) (*buckets)[std::size_t(b)].push_back(int(t));
    }
    auto dep = std::make_shared<std::vector<float>>(std::move(depth));
    const std::vector<double>* xs = &mX;
    const std::vector<double>* ys = &mY;
    const std::vector<int>* tri = &mTri;
    const double minX = grid.minX, maxY = grid.maxY;
    const GridWindow w = window;
    return [=](int row0, int rows, float* out) -> Diagnostics {
        const int width = w.width();
        std::fill(out, out + std::size_t(width) * std::size_t(rows),
                  std::numeric_limits<float>::quiet_NaN());
        const int b0 = row0 / kBand, b1 = std::min(bands - 1, (row0 + rows - 1) / kBand);
        std::vector<char> seen(tri->size() / 3, 0);
        for (int b = b0; b <= b1; ++b) {
            for (int t : (*buckets)[std::size_t(b)]) {
                if (seen[std::size_t(t)]) continue;
                seen[std::size_t(t)] = 1;
                const int i0 = (*tri)[std::size_t(t) * 3], i1 = (*tri)[std::size_t(t) * 3 + 1],
                          i2 = (*tri)[std::size_t(t) * 3 + 2];
                // Vertex positions in window pixel units (pixel centre at integer + 0.5).
                const double ax = ((*xs)[std::size_t(i0)] - minX) / p - w.x0,
                             ay = (maxY - (*ys)[std::size_t(i0)]) / p - w.y0;
                const double bx = ((*xs)[std::size_t(i1)] - minX) / p - w.x0,
                             by = (maxY - (*ys)[std::size_t(i1)]) / p - w.y0;
                const double cx = ((*xs)[std::size_t(i2)] - minX) / p - w.x0,
                             cy = (maxY - (*ys)[std::size_t(i2)]) / p - w.y0;
                const double area = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay);
                if (std::fabs(area) < 1e-12) continue;
                const int px0 = std::max(0, int(std::floor(std::min({ax, bx, cx}) - 0.5)));
                const int px1 = std::min(width - 1, int(std::ceil(std::max({ax, bx, cx}) - 0.5)));
                const int py0 = std::max(row0, int(std::floor(std::min({ay, by, cy}) - 0.5)));
                const int py1 =
                    std::min(row0 + rows - 1, int(std::ceil(std::max({ay, by, cy}) - 0.5)));
                const float da = (*dep)[std::size_t(i0)], db = (*dep)[std::size_t(i1)],
                            dc = (*dep)[std::size_t(i2)];
                for (int py = py0; py <= py1; ++py) {
                    const double sy = py + 0.5;
                    for (int px = px0; px <= px1; ++px) {
                        const double sx = px + 0.5;
                        const double l1 = ((bx - sx) * (cy - sy) - (cx - sx) * (by - sy)) / area;
                        const double l2 = ((cx - sx) * (ay - sy) - (ax - sx) * (cy - sy)) / area;
                        const double l3 = 1.0 - l1 - l2;
                        constexpr double kEps = -1e-9;
                        if (l1 < kEps || l2 < kEps || l3 < kEps) continue;
                        double v = l1 * da + l2 * db + l3 * dc;
                        if (v < wetThreshold) v = 0;
                        out[std::size_t(py - row0) * std::size_t(width) + std::size_t(px)] =
                            float(v);
                    }
                }
            }
        }
        return Diagnostics{};
    };
}

}  // namespace kiosk::import
