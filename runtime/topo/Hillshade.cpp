#include "runtime/topo/Hillshade.h"

#include "runtime/topo/Gradient.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace kiosk::topo {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

// gdaldem writes its float result into a Byte band; GDAL's float->byte copy rounds to nearest.
inline std::uint8_t toByte(double v) {
    if (!(v >= 1.0)) return 1;  // also catches NaN from degenerate (overflowing) heights
    if (v >= 255.0) return 255;
    return static_cast<std::uint8_t>(v + 0.5);
}

// Light and scale terms hoisted out of the per-pixel loop. x, y are detail::GradientRows'
// gradient; zs turns them into slopes.
struct Shader {
    double sinAlt;
    double cosAltZ;  // cos(alt) * zs
    double sinAz;
    double cosAz;
    double zs2;  // zs^2
    double halfSqrt2CosAltZ;

    explicit Shader(const HillshadeParams& p) {
        const double zs = detail::gradientScale(p);
        const double alt = p.altitudeDeg * kDegToRad;
        const double az = p.azimuthDeg * kDegToRad;
        sinAlt = std::sin(alt);
        cosAltZ = std::cos(alt) * zs;
        sinAz = std::sin(az);
        cosAz = std::cos(az);
        zs2 = zs * zs;
        halfSqrt2CosAltZ = std::numbers::sqrt2 * 0.5 * cosAltZ;
    }

    // Lambert of the unit normal (zs*x, -zs*y, 1)/|.| with the light (sin az cos alt,
    // cos az cos alt, sin alt), east/north/up; may be negative (facing away).
    double lambert(double x, double y) const {
        const double r2 = x * x + y * y;
        return (sinAlt - (y * cosAz - x * sinAz) * cosAltZ) / std::sqrt(1.0 + zs2 * r2);
    }

    double standard(double x, double y) const {
        const double c = lambert(x, y);
        return c <= 0.0 ? 1.0 : 1.0 + 254.0 * c;
    }

    // Combined: the oblique shade's angle from the light scaled by the slope angle, both
    // normalised by pi/2 (gdaldem -combined).
    double combined(double x, double y) const {
        const double slope2 = zs2 * (x * x + y * y);
        const double c = std::clamp(lambert(x, y), -1.0, 1.0);
        const double v = 1.0 - std::acos(c) * std::atan(std::sqrt(slope2)) /
                                   (0.25 * std::numbers::pi * std::numbers::pi);
        return v <= 0.0 ? 1.0 : 1.0 + 254.0 * v;
    }

    // Mark (1992): four lights at 225/270/315/360 deg, each weighted by cos^2 of the angle
    // between its azimuth and the downslope direction (x, -y); the weights sum to 2 |g|^2.
    // Each light's contribution is clamped at 0 before weighting.
    double multidirectional(double x, double y) const {
        const double r2 = x * x + y * y;
        if (r2 == 0.0) return 1.0 + 254.0 * sinAlt;
        const double v225 = sinAlt - (x - y) * halfSqrt2CosAltZ;
        const double v270 = sinAlt - x * cosAltZ;
        const double v315 = sinAlt - (x + y) * halfSqrt2CosAltZ;
        const double v360 = sinAlt - y * cosAltZ;
        const double w225 = 0.5 * r2 - x * y;
        const double w270 = x * x;
        const double w315 = 0.5 * r2 + x * y;
        const double w360 = y * y;
        const double sum = w225 * std::max(0.0, v225) + w270 * std::max(0.0, v270) +
                           w315 * std::max(0.0, v315) + w360 * std::max(0.0, v360);
        const double c = sum / (2.0 * r2) / std::sqrt(1.0 + zs2 * r2);
        return 1.0 + 254.0 * c;
    }
};

// Default variant, the hot one: float arithmetic, no per-pixel branches on validity (NaN-safe
// clamps keep the float->int conversion defined even for pathological input).
void shadeRowStandard(const Shader& s, const float* __restrict gx, const float* __restrict gy,
                      const std::uint8_t* __restrict ok, int n, std::uint8_t* __restrict out) {
    const float sinAlt = static_cast<float>(s.sinAlt);
    const float cosAzZ = static_cast<float>(s.cosAz * s.cosAltZ);
    const float sinAzZ = static_cast<float>(s.sinAz * s.cosAltZ);
    const float zs2 = static_cast<float>(s.zs2);
    for (int c = 0; c < n; ++c) {
        const float x = gx[c];
        const float y = gy[c];
        const float cang =
            (sinAlt - (y * cosAzZ - x * sinAzZ)) / std::sqrt(1.0f + zs2 * (x * x + y * y));
        // NaN-safe clamp (a NaN compares false and becomes 0) before the float->int cast.
        const float clamped = cang > 0.0f ? (cang < 1.0f ? cang : 1.0f) : 0.0f;
        const int b = static_cast<int>(1.5f + 254.0f * clamped);
        out[c] = static_cast<std::uint8_t>(b & -static_cast<int>(ok[c]));
    }
}

template <class Shade>
void shadeRow(const float* gx, const float* gy, const std::uint8_t* ok, int n, std::uint8_t* out,
              Shade shade) {
    for (int c = 0; c < n; ++c) out[c] = ok[c] ? toByte(shade(gx[c], gy[c])) : kHillshadeNodata;
}

}  // namespace

Diagnostics validateParams(const HillshadeParams& p, const char* where) {
    Diagnostics d;
    const char* code = "TOPO_INVALID_PARAMS";
    if (!std::isfinite(p.azimuthDeg))
        d.error(code, "", where, "azimuth must be a finite number of degrees");
    if (!(p.altitudeDeg >= 0.0 && p.altitudeDeg <= 90.0))
        d.error(
            code, "", where,
            "altitude must be within [0, 90] degrees (got " + std::to_string(p.altitudeDeg) + ")");
    if (!std::isfinite(p.zFactor))
        d.error(code, "", where, "zFactor must be finite (got " + std::to_string(p.zFactor) + ")");
    if (!(std::isfinite(p.scale) && p.scale > 0.0))
        d.error(code, "", where,
                "scale must be finite and > 0 (got " + std::to_string(p.scale) + ")");
    return d;
}

Diagnostics hillshade(const RasterView& dem, const HillshadeParams& params, std::uint8_t* out,
                      std::ptrdiff_t outStride) {
    Diagnostics d = dem.validate("hillshade");
    d.append(validateParams(params, "hillshade"));
    if (out == nullptr)
        d.error("TOPO_INVALID_OUTPUT", "", "hillshade", "output buffer is null");
    else if (dem.width > 0 && outStride < dem.width)
        d.error("TOPO_INVALID_OUTPUT", "", "hillshade",
                "output stride " + std::to_string(outStride) + " is smaller than the width " +
                    std::to_string(dem.width));
    if (d.hasErrors()) return d;

    const Shader s(params);
    detail::GradientRows rows(dem, params.algorithm, params.computeEdges);
    for (int r = 0; r < dem.height; ++r) {
        rows.compute(r);
        std::uint8_t* o = out + r * outStride;
        switch (params.variant) {
            case HillshadeVariant::Default:
                shadeRowStandard(s, rows.x(), rows.y(), rows.valid(), dem.width, o);
                break;
            case HillshadeVariant::Combined:
                shadeRow(rows.x(), rows.y(), rows.valid(), dem.width, o,
                         [&](double x, double y) { return s.combined(x, y); });
                break;
            case HillshadeVariant::Multidirectional:
                shadeRow(rows.x(), rows.y(), rows.valid(), dem.width, o,
                         [&](double x, double y) { return s.multidirectional(x, y); });
                break;
        }
    }
    return d;
}

}  // namespace kiosk::topo
