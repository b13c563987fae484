#pragma once

// Internal to kiosk_topo: the 3x3 neighbourhood walk shared by hillshade and normal maps.
// Not part of the public API (no other module includes it).

#include "runtime/topo/Hillshade.h"
#include "runtime/topo/RasterView.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace kiosk::topo::detail {

/**
 * Surface gradient in gdaldem's convention, before the zFactor / scale factor:
 * x = (west - east) differences / pixelSizeX, y = (north - south) differences / pixelSizeY,
 * summed with the (1,2,1) weights for Horn (so 8x the slope) and unweighted for
 * Zevenbergen-Thorne (2x the slope). gradientScale() gives the factor turning them into
 * dimensionless slopes: -dz/dEast = x * s, dz/dNorth = y * s.
 */
inline double gradientScale(const HillshadeParams& p) {
    return p.zFactor / ((p.algorithm == GradientAlgorithm::Horn ? 8.0 : 2.0) * p.scale);
}

inline bool finite(float v) {
    return std::isfinite(v);
}

// gdaldem's INTERPOL(): linear extrapolation across the DEM border, nodata if either input is.
inline float extrapolate(float a, float b) {
    return (finite(a) && finite(b)) ? 2.0f * a - b : NAN;
}

// The 3x3 window of (c, r) with gdaldem's rules for the DEM border (an apron of 0 on that
// side) and for nodata. Returns false when the output pixel is nodata. Row-major, w[4] centre.
inline bool gatherSlow(const RasterView& v, int c, int r, bool computeEdges, float w[9]) {
    const bool absentT = r == 0 && v.apronTop == 0;
    const bool absentB = r == v.height - 1 && v.apronBottom == 0;
    const bool absentL = c == 0 && v.apronLeft == 0;
    const bool absentR = c == v.width - 1 && v.apronRight == 0;
    const bool atBorder = absentT || absentB || absentL || absentR;
    if (atBorder && !computeEdges) return false;
    if (absentT || absentB) {
        // gdaldem's first/last-line path: a missing column repeats the centre column (not
        // extrapolated), the missing row is extrapolated from the two rows inside.
        const int cols[3] = {absentL ? c : c - 1, c, absentR ? c : c + 1};
        for (int k = 0; k < 3; ++k) {
            const float mid = v.at(cols[k], r);
            float up = 0.0f;
            float dn = 0.0f;
            if (absentT && absentB) {
                up = dn = mid;
            } else if (absentT) {
                dn = v.at(cols[k], r + 1);
                up = extrapolate(mid, dn);
            } else {
                up = v.at(cols[k], r - 1);
                dn = extrapolate(mid, up);
            }
            w[k] = up;
            w[3 + k] = mid;
            w[6 + k] = dn;
        }
    } else {
        for (int k = 0; k < 3; ++k) {
            const int rr = r + k - 1;
            const float mid = v.at(c, rr);
            float left = 0.0f;
            float right = 0.0f;
            if (absentL && absentR) {
                left = right = mid;
            } else if (absentL) {
                right = v.at(c + 1, rr);
                left = extrapolate(mid, right);
            } else if (absentR) {
                left = v.at(c - 1, rr);
                right = extrapolate(mid, left);
            } else {
                left = v.at(c - 1, rr);
                right = v.at(c + 1, rr);
            }
            w[3 * k] = left;
            w[3 * k + 1] = mid;
            w[3 * k + 2] = right;
        }
    }
    const float centre = w[4];
    if (!finite(centre)) return false;
    for (int k = 0; k < 9; ++k) {
        if (!finite(w[k])) {
            if (!computeEdges) return false;
            w[k] = centre;
        }
    }
    return true;
}

inline void gradientOf(const float w[9], GradientAlgorithm alg, double invX, double invY, double& x,
                       double& y) {
    if (alg == GradientAlgorithm::Horn) {
        x = ((double(w[0]) + 2.0 * w[3] + w[6]) - (double(w[2]) + 2.0 * w[5] + w[8])) * invX;
        y = ((double(w[0]) + 2.0 * w[1] + w[2]) - (double(w[6]) + 2.0 * w[7] + w[8])) * invY;
    } else {
        x = (double(w[3]) - w[5]) * invX;
        y = (double(w[1]) - w[7]) * invY;
    }
}

/**
 * The gradient of one window row at a time into reusable arrays, so the per-pixel shading
 * loops that follow have no nodata branches. Interior pixels (3x3 inside the view) take a
 * straight-line pass; DEM-border pixels and any window holding nodata are redone through
 * gatherSlow(). Invalid pixels get valid 0 and gradient (0, 0).
 */
class GradientRows {
public:
    GradientRows(const RasterView& v, GradientAlgorithm alg, bool computeEdges)
        : mView(v),
          mAlg(alg),
          mComputeEdges(computeEdges),
          mInvX(1.0 / v.pixelSizeX),
          mInvY(1.0 / v.pixelSizeY),
          mX(static_cast<std::size_t>(v.width)),
          mY(static_cast<std::size_t>(v.width)),
          mValid(static_cast<std::size_t>(v.width)) {}

    void compute(int r) {
        const RasterView& v = mView;
        const bool rowAtBorder =
            (r == 0 && v.apronTop == 0) || (r == v.height - 1 && v.apronBottom == 0);
        const int firstFast = rowAtBorder ? v.width : (v.apronLeft == 0 ? 1 : 0);
        const int endFast = rowAtBorder ? v.width : (v.apronRight == 0 ? v.width - 1 : v.width);
        float* __restrict gx = mX.data();
        float* __restrict gy = mY.data();
        std::uint8_t* __restrict ok = mValid.data();
        if (firstFast < endFast) {
            const std::ptrdiff_t s = v.stride;
            const float* __restrict mid = v.data + static_cast<std::ptrdiff_t>(r) * s;
            const float* __restrict up = mid - s;
            const float* __restrict dn = mid + s;
            // Float like gdaldem's own float path: 4 lanes per SSE register. The height sums
            // lose nothing that shows in 8-bit shading (verified against gdaldem).
            const float invX = static_cast<float>(mInvX);
            const float invY = static_cast<float>(mInvY);
            if (mAlg == GradientAlgorithm::Horn) {
                for (int c = firstFast; c < endFast; ++c) {
                    const float a0 = up[c - 1], a1 = up[c], a2 = up[c + 1];
                    const float a3 = mid[c - 1], a4 = mid[c], a5 = mid[c + 1];
                    const float a6 = dn[c - 1], a7 = dn[c], a8 = dn[c + 1];
                    gx[c] = ((a0 + 2.0f * a3 + a6) - (a2 + 2.0f * a5 + a8)) * invX;
                    gy[c] = ((a0 + 2.0f * a1 + a2) - (a6 + 2.0f * a7 + a8)) * invY;
                    const float sum = a0 + a1 + a2 + a3 + a4 + a5 + a6 + a7 + a8;
                    ok[c] = (sum - sum) == 0.0f;  // false for NaN and infinities
                }
            } else {
                for (int c = firstFast; c < endFast; ++c) {
                    const float a0 = up[c - 1], a1 = up[c], a2 = up[c + 1];
                    const float a3 = mid[c - 1], a4 = mid[c], a5 = mid[c + 1];
                    const float a6 = dn[c - 1], a7 = dn[c], a8 = dn[c + 1];
                    gx[c] = (a3 - a5) * invX;
                    gy[c] = (a1 - a7) * invY;
                    const float sum = a0 + a1 + a2 + a3 + a4 + a5 + a6 + a7 + a8;
                    ok[c] = (sum - sum) == 0.0f;
                }
            }
        }
        float w[9];
        for (int c = 0; c < v.width; ++c) {
            if (c >= firstFast && c < endFast && ok[c]) continue;
            double x = 0.0;
            double y = 0.0;
            const bool valid = gatherSlow(v, c, r, mComputeEdges, w);
            if (valid) gradientOf(w, mAlg, mInvX, mInvY, x, y);
            // Finite heights whose differences overflow are nodata too.
            const bool finiteGradient = std::isfinite(x) && std::isfinite(y);
            ok[c] = valid && finiteGradient;
            gx[c] = ok[c] ? static_cast<float>(x) : 0.0f;
            gy[c] = ok[c] ? static_cast<float>(y) : 0.0f;
        }
    }

    const float* x() const { return mX.data(); }
    const float* y() const { return mY.data(); }
    const std::uint8_t* valid() const { return mValid.data(); }

private:
    RasterView mView;
    GradientAlgorithm mAlg;
    bool mComputeEdges;
    double mInvX;
    double mInvY;
    std::vector<float> mX;
    std::vector<float> mY;
    std::vector<std::uint8_t> mValid;
};

}  // namespace kiosk::topo::detail
