#include "runtime/topo/Shadow.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace kiosk::topo {

namespace {

// Block-maximum grid cell: 16 x 16 pixels (log2; shifts, not divisions, per step). A finer
// second level (4 x 4) was measured not to pay for its lookups.
constexpr int kCoarseShift = 4;
// Lipschitz bound also per 128 x 128 super-cell (8 x 8 cells), for long skips on gentle terrain.
constexpr int kSuperShift = 7;
constexpr int kApronCap = 1 << 20;  // "unbounded" apron answer

Diagnostics checkOutput(const std::uint8_t* out, std::ptrdiff_t stride, int width,
                        const char* where, const char* what) {
    Diagnostics d;
    if (out == nullptr)
        d.error("TOPO_INVALID_OUTPUT", "", where, std::string(what) + " buffer is null");
    else if (width > 0 && stride < width)
        d.error("TOPO_INVALID_OUTPUT", "", where,
                std::string(what) + " stride " + std::to_string(stride) +
                    " is smaller than the width " + std::to_string(width));
    return d;
}

// Maximum scaled height per cell x cell block of the whole buffer (window + aprons),
// each cell dilated by one pixel on every side: a ray sample interpolates between a pixel and
// its neighbour, which may lie in the next cell.
struct BlockMax {
    int shift = 0;
    int cell = 1;
    int cols = 0;
    int rows = 0;
    std::vector<double> max;
    double overall = -std::numeric_limits<double>::infinity();

    BlockMax(const RasterView& v, double k, int cellShift)
        : shift(cellShift), cell(1 << cellShift) {
        const int bufW = v.apronLeft + v.width + v.apronRight;
        const int bufH = v.apronTop + v.height + v.apronBottom;
        cols = (bufW + cell - 1) / cell;
        rows = (bufH + cell - 1) / cell;
        max.assign(static_cast<std::size_t>(cols) * rows, -std::numeric_limits<double>::infinity());
        std::vector<double> rowMax(static_cast<std::size_t>(cols));
        for (int y = 0; y < bufH; ++y) {
            std::fill(rowMax.begin(), rowMax.end(), -std::numeric_limits<double>::infinity());
            const float* src =
                v.data + static_cast<std::ptrdiff_t>(y - v.apronTop) * v.stride - v.apronLeft;
            for (int x = 0; x < bufW; ++x) {
                const float h = src[x];
                if (!std::isfinite(h)) continue;
                const double s = h * k;
                const int lo = x >= 1 ? (x - 1) / cell : 0;
                const int hi = std::min((x + 1) / cell, cols - 1);
                for (int i = lo; i <= hi; ++i) rowMax[i] = std::max(rowMax[i], s);
            }
            const int lo = y >= 1 ? (y - 1) / cell : 0;
            const int hi = std::min((y + 1) / cell, rows - 1);
            for (int j = lo; j <= hi; ++j)
                for (int i = 0; i < cols; ++i) {
                    double& m = max[static_cast<std::size_t>(j) * cols + i];
                    m = std::max(m, rowMax[i]);
                }
        }
        for (double m : max) overall = std::max(overall, m);
    }

    double at(int bx, int by) const { return max[static_cast<std::size_t>(by) * cols + bx]; }
};

// Per coarse cell, an upper bound of how much the sampled terrain profile can rise from one
// ray step to the next (scaled height units). Between steps the sample moves one column along
// the dominant axis and |sMin| along the minor axis, and within a column it interpolates
// linearly, so the rise is at most D + |sMin| * G: D the largest forward difference between
// neighbours along the dominant axis, G the largest absolute difference along the minor axis.
// Cells are dilated by two pixels (pairs straddling a border). Nodata makes the interpolation
// jump between pixels, so a cell touching nodata gets no bound (infinity: never skipped).
struct StepRise {
    int cols = 0;
    std::vector<double> max;

    StepRise(const RasterView& v, double k, bool alongX, bool forward, double absMinorStep,
             int shift, int cellCols, int cellRows)
        : cols(cellCols) {
        const int bufW = v.apronLeft + v.width + v.apronRight;
        const int bufH = v.apronTop + v.height + v.apronBottom;
        const std::size_t cells = static_cast<std::size_t>(cellCols) * cellRows;
        std::vector<double> dMax(cells, 0.0), gMax(cells, 0.0);
        std::vector<std::uint8_t> hasNodata(cells, 0);
        auto h = [&](int x, int y) {
            return v.data[static_cast<std::ptrdiff_t>(y - v.apronTop) * v.stride + x - v.apronLeft];
        };
        const int fx = alongX ? (forward ? 1 : -1) : 0;
        const int fy = alongX ? 0 : (forward ? 1 : -1);
        const int gx = alongX ? 0 : 1;
        const int gy = alongX ? 1 : 0;
        for (int y = 0; y < bufH; ++y) {
            for (int x = 0; x < bufW; ++x) {
                const float h0 = h(x, y);
                double d = 0.0;
                double g = 0.0;
                bool nodata = !std::isfinite(h0);
                if (!nodata) {
                    const int x1 = x + fx, y1 = y + fy;
                    if (x1 >= 0 && y1 >= 0 && x1 < bufW && y1 < bufH) {
                        const float h1 = h(x1, y1);
                        if (std::isfinite(h1))
                            d = std::max(0.0, (double(h1) - h0) * k);
                        else
                            nodata = true;
                    }
                    const int x2 = x + gx, y2 = y + gy;
                    if (x2 < bufW && y2 < bufH) {
                        const float h2 = h(x2, y2);
                        if (std::isfinite(h2))
                            g = std::abs((double(h2) - h0) * k);
                        else
                            nodata = true;
                    }
                }
                if (d <= 0.0 && g <= 0.0 && !nodata) continue;
                const int cx0 = std::max(0, (x - 2) >> shift);
                const int cx1 = std::min(cellCols - 1, (x + 2) >> shift);
                const int cy0 = std::max(0, (y - 2) >> shift);
                const int cy1 = std::min(cellRows - 1, (y + 2) >> shift);
                for (int cy = cy0; cy <= cy1; ++cy)
                    for (int cx = cx0; cx <= cx1; ++cx) {
                        const std::size_t c = static_cast<std::size_t>(cy) * cellCols + cx;
                        dMax[c] = std::max(dMax[c], d);
                        gMax[c] = std::max(gMax[c], g);
                        hasNodata[c] |= static_cast<std::uint8_t>(nodata);
                    }
            }
        }
        max.resize(cells);
        for (std::size_t c = 0; c < cells; ++c)
            max[c] = hasNodata[c] ? std::numeric_limits<double>::infinity()
                                  : dMax[c] + absMinorStep * gMax[c];
    }

    double at(int cx, int cy) const { return max[static_cast<std::size_t>(cy) * cols + cx]; }
};

// Max of a StepRise grid over groups of 2^levels x 2^levels cells, and over everything.
struct SuperRise {
    int cols = 0;
    std::vector<double> max;
    double overall = 0.0;

    SuperRise(const StepRise& fine, int fineRows, int levels) {
        cols = ((fine.cols - 1) >> levels) + 1;
        const int rows = ((fineRows - 1) >> levels) + 1;
        max.assign(static_cast<std::size_t>(cols) * rows, 0.0);
        for (int y = 0; y < fineRows; ++y)
            for (int x = 0; x < fine.cols; ++x) {
                double& m = max[static_cast<std::size_t>(y >> levels) * cols + (x >> levels)];
                m = std::max(m, fine.at(x, y));
                overall = std::max(overall, m);
            }
    }

    double at(int cx, int cy) const { return max[static_cast<std::size_t>(cy) * cols + cx]; }
};

}  // namespace

int requiredShadowApron(double maxRelief, const HillshadeParams& light, double pixelSizeX,
                        double pixelSizeY) {
    if (!(light.altitudeDeg > 0.0) || !std::isfinite(maxRelief) || !(light.scale > 0.0) ||
        !(pixelSizeX > 0.0) || !(pixelSizeY > 0.0) || !std::isfinite(light.zFactor))
        return kApronCap;
    if (light.altitudeDeg >= 90.0) return 0;
    const double reach = std::abs(maxRelief * light.zFactor / light.scale) /
                         std::tan(light.altitudeDeg * std::numbers::pi / 180.0);
    const double pixels = std::ceil(reach / std::min(pixelSizeX, pixelSizeY)) + 1.0;
    return pixels >= kApronCap ? kApronCap : static_cast<int>(pixels);
}

Diagnostics castShadows(const RasterView& dem, const HillshadeParams& light, std::uint8_t* mask,
                        std::ptrdiff_t maskStride) {
    Diagnostics d = dem.validate("castShadows");
    d.append(validateParams(light, "castShadows"));
    d.append(checkOutput(mask, maskStride, dem.width, "castShadows", "mask"));
    if (d.hasErrors()) return d;

    const double k = light.zFactor / light.scale;  // vertical -> horizontal units
    for (int r = 0; r < dem.height; ++r) std::fill_n(mask + r * maskStride, dem.width, kLit);
    if (k == 0.0 || light.altitudeDeg >= 90.0) return d;

    const double az = light.azimuthDeg * std::numbers::pi / 180.0;
    // Direction towards the light in pixels per horizontal unit (columns east, rows south).
    const double ux = std::sin(az) / dem.pixelSizeX;
    const double uy = -std::cos(az) / dem.pixelSizeY;
    const double m = std::max(std::abs(ux), std::abs(uy));
    const bool alongX = std::abs(ux) >= std::abs(uy);
    // One step = one pixel along the dominant axis.
    const double sDom = (alongX ? ux : uy) / m > 0 ? 1.0 : -1.0;
    // sin/cos of axis-aligned azimuths are not exactly 0 (cos 270 deg = -1.8e-16): snap, so a
    // ray along a row does not drift out of the view's last row.
    double sMin = (alongX ? uy : ux) / m;
    if (std::abs(sMin) < 1e-9) sMin = 0.0;
    const double rise = std::tan(light.altitudeDeg * std::numbers::pi / 180.0) / m;

    const BlockMax coarse(dem, k, kCoarseShift);
    const StepRise climb(dem, k, alongX, sDom > 0, std::abs(sMin), kCoarseShift, coarse.cols,
                         coarse.rows);
    const SuperRise superClimb(climb, coarse.rows, kSuperShift - kCoarseShift);
    const double top = coarse.overall;
    const int bufW = dem.apronLeft + dem.width + dem.apronRight;
    const int bufH = dem.apronTop + dem.height + dem.apronBottom;
    const int domLimit = alongX ? bufW - 1 : bufH - 1;
    const int minLimit = alongX ? bufH - 1 : bufW - 1;
    // Buffer coordinates (0,0) = top-left of the apron.
    auto sample = [&](int dom, int minor) {
        const int x = alongX ? dom : minor;
        const int y = alongX ? minor : dom;
        return dem.at(x - dem.apronLeft, y - dem.apronTop);
    };
    auto cellMax = [&](const BlockMax& g, int dom, int minor) {
        return alongX ? g.at(dom >> g.shift, minor >> g.shift)
                      : g.at(minor >> g.shift, dom >> g.shift);
    };
    // Step counts come from divisions by sMin, which may be tiny: clamp before converting.
    auto toSteps = [](double v) {
        return v >= 1e15 ? static_cast<long long>(1e15) : static_cast<long long>(std::floor(v));
    };
    // Steps until the ray at (dom, pm) leaves its cell (at least 1). The ray only climbs, so
    // when it is above the cell's maximum every sample left in the cell is below it.
    auto stepsToLeave = [&](int shift, int dom, double pm) {
        const int cell = 1 << shift;
        const int bDom = dom >> shift;
        const int bMin = static_cast<int>(pm) >> shift;
        long long n = sDom > 0 ? (bDom + 1) * cell - dom : dom - bDom * cell + 1;
        if (sMin > 0)
            n = std::min(n, -toSteps(-((bMin + 1) * cell - pm) / sMin));  // ceil
        else if (sMin < 0)
            n = std::min(n, toSteps((pm - bMin * cell) / -sMin) + 1);
        return std::max<long long>(n, 1);
    };

    for (int r = 0; r < dem.height; ++r) {
        std::uint8_t* outRow = mask + r * maskStride;
        for (int c = 0; c < dem.width; ++c) {
            const float h0 = dem.at(c, r);
            if (!std::isfinite(h0)) continue;
            const double base = h0 * k;
            if (base + rise > top) continue;
            const int dom0 = alongX ? c + dem.apronLeft : r + dem.apronTop;
            const double min0 = alongX ? r + dem.apronTop : c + dem.apronLeft;
            // Last step that stays inside the buffer and below the highest point.
            long long last = sDom > 0 ? domLimit - dom0 : dom0;
            if (sMin > 0)
                last = std::min(last, toSteps((minLimit - min0) / sMin));
            else if (sMin < 0)
                last = std::min(last, toSteps(min0 / -sMin));
            if (rise > 0.0) last = std::min(last, toSteps((top - base) / rise));
            for (long long i = 1; i <= last;) {
                const double ray = base + static_cast<double>(i) * rise;
                const int dom = dom0 + static_cast<int>(sDom) * static_cast<int>(i);
                const double pm = std::max(0.0, min0 + sMin * static_cast<double>(i));
                const int fm = std::min(static_cast<int>(pm), minLimit);
                if (ray > cellMax(coarse, dom, fm)) {
                    i += stepsToLeave(kCoarseShift, dom, pm);
                    continue;
                }
                const double t = pm - fm;
                const float a = sample(dom, fm);
                double h = a;
                if (t > 0.0 && fm < minLimit) {
                    const float b = sample(dom, fm + 1);
                    if (std::isfinite(a) && std::isfinite(b))
                        h = a + (b - a) * t;
                    else if (std::isfinite(b))
                        h = b;
                }
                if (!std::isfinite(h)) {
                    ++i;
                    continue;
                }
                const double margin = ray - h * k;
                if (margin < 0.0) {
                    outRow[c] = kShadowed;
                    break;
                }
                // Lipschitz skips: within a cell the terrain profile climbs at most `maxRise`
                // per step and the ray climbs `rise`, so the margin cannot close before
                // margin / (maxRise - rise) steps, and never if the ray climbs faster.
                if (superClimb.overall <= rise) break;  // faster than the steepest step anywhere
                const int sx = alongX ? dom >> kSuperShift : fm >> kSuperShift;
                const int sy = alongX ? fm >> kSuperShift : dom >> kSuperShift;
                if (superClimb.at(sx, sy) <= rise) {
                    i += stepsToLeave(kSuperShift, dom, pm);
                    continue;
                }
                const double maxRise = climb.at(alongX ? dom >> kCoarseShift : fm >> kCoarseShift,
                                                alongX ? fm >> kCoarseShift : dom >> kCoarseShift);
                long long n = stepsToLeave(kCoarseShift, dom, pm);
                if (maxRise > rise) n = std::min(n, toSteps(margin / (maxRise - rise)));
                i += std::max<long long>(n, 1);
            }
        }
    }
    return d;
}

Diagnostics combineShadows(std::uint8_t* shade, std::ptrdiff_t shadeStride,
                           const std::uint8_t* mask, std::ptrdiff_t maskStride, int width,
                           int height, const ShadowParams& params) {
    Diagnostics d;
    d.append(checkOutput(shade, shadeStride, width, "combineShadows", "shade"));
    d.append(checkOutput(mask, maskStride, width, "combineShadows", "mask"));
    if (width < 0 || height < 0)
        d.error("TOPO_INVALID_OUTPUT", "", "combineShadows", "negative size");
    if (!(params.darkening >= 0.0 && params.darkening <= 1.0))
        d.error("TOPO_INVALID_PARAMS", "", "combineShadows",
                "shadow darkening must be within [0, 1] (got " + std::to_string(params.darkening) +
                    ")");
    if (d.hasErrors()) return d;
    // One multiplier per mask value, so the per-pixel work is a table lookup.
    double keep[256];
    for (int m = 0; m < 256; ++m) keep[m] = 1.0 - params.darkening * m / 255.0;
    for (int r = 0; r < height; ++r) {
        std::uint8_t* s = shade + r * shadeStride;
        const std::uint8_t* mk = mask + r * maskStride;
        for (int c = 0; c < width; ++c) {
            if (s[c] == kHillshadeNodata || mk[c] == kLit) continue;
            s[c] = static_cast<std::uint8_t>(1.0 + (s[c] - 1) * keep[mk[c]] + 0.5);
        }
    }
    return d;
}

Diagnostics shadedRelief(const RasterView& dem, const HillshadeParams& light,
                         const ShadowParams& shadow, std::uint8_t* out, std::ptrdiff_t outStride) {
    if (!(shadow.darkening >= 0.0 && shadow.darkening <= 1.0)) {
        Diagnostics bad;
        bad.error("TOPO_INVALID_PARAMS", "", "shadedRelief",
                  "shadow darkening must be within [0, 1] (got " +
                      std::to_string(shadow.darkening) + ")");
        return bad;
    }
    Diagnostics d = hillshade(dem, light, out, outStride);
    if (d.hasErrors()) return d;
    std::vector<std::uint8_t> mask(static_cast<std::size_t>(dem.width) * dem.height);
    d.append(castShadows(dem, light, mask.data(), dem.width));
    if (d.hasErrors()) return d;
    d.append(combineShadows(out, outStride, mask.data(), dem.width, dem.width, dem.height, shadow));
    return d;
}

}  // namespace kiosk::topo
