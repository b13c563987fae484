#include "runtime/anim/CameraPath.h"

#include "runtime/core/TimeParse.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace kiosk::anim {
namespace {

std::string keyPointer(std::string_view where, std::size_t i, const char* member) {
    return std::string(where) + "/keys/" + std::to_string(i) + "/" + member;
}

std::string num(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

// PCHIP tangents (Fritsch-Carlson with Fritsch-Butland weights for uneven spacing): zero at
// extrema so no overshoot, shared between adjacent segments so the curve is C1. End tangents are
// zero on purpose: the camera eases into the first key and out of the last one.
void pchipTangents(const std::vector<double>& x, const std::vector<double>& y,
                   std::vector<double>& m) {
    const std::size_t n = x.size();
    m.assign(n, 0.0);
    for (std::size_t k = 1; k + 1 < n; ++k) {
        const double h0 = x[k] - x[k - 1], h1 = x[k + 1] - x[k];
        const double d0 = (y[k] - y[k - 1]) / h0, d1 = (y[k + 1] - y[k]) / h1;
        if (d0 * d1 <= 0.0) continue;
        const double w1 = 2.0 * h1 + h0, w2 = h1 + 2.0 * h0;
        m[k] = (w1 + w2) / (w1 / d0 + w2 / d1);
    }
}

double hermite(double y0, double y1, double m0, double m1, double h, double s) {
    const double s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * h * m0 + (-2 * s3 + 3 * s2) * y1 +
           (s3 - s2) * h * m1;
}

}  // namespace

double shortestHeadingDelta(double a, double b) noexcept {
    double d = std::fmod(b - a, 360.0);
    if (d <= -180.0) d += 360.0;
    if (d > 180.0) d -= 360.0;
    return d;
}

double normalizeHeading(double deg) noexcept {
    double h = std::fmod(deg, 360.0);
    if (h < 0.0) h += 360.0;
    return h >= 360.0 ? 0.0 : h;
}

double smootherstep(double s) noexcept {
    s = std::clamp(s, 0.0, 1.0);
    return s * s * s * (s * (s * 6.0 - 15.0) + 10.0);
}

std::optional<PathInterpolation> parsePathInterpolation(std::string_view text) noexcept {
    if (text == "smooth") return PathInterpolation::Smooth;
    if (text == "linear") return PathInterpolation::Linear;
    if (text == "step") return PathInterpolation::Step;
    return std::nullopt;
}

Result<CameraPath> CameraPath::create(std::vector<CameraKey> keys, std::string_view file,
                                      std::string_view where, PathInterpolation mode) {
    Diagnostics d;
    const std::string f(file);
    if (keys.empty()) {
        d.error("ANIM_PATH_EMPTY", f, std::string(where) + "/keys", "camera path has no keys");
        return d;
    }
    for (std::size_t i = 0; i < keys.size(); ++i) {
        const auto& k = keys[i];
        const auto& v = k.view;
        if (!std::isfinite(k.time)) {
            d.error("ANIM_PATH_NOT_FINITE", f, keyPointer(where, i, "time"),
                    "camera key time is not a finite time");
            continue;
        }
        if (!std::isfinite(v.target.x) || !std::isfinite(v.target.y) ||
            !std::isfinite(v.target.z) || !std::isfinite(v.headingDeg) ||
            !std::isfinite(v.pitchDeg) || !std::isfinite(v.range)) {
            d.error("ANIM_PATH_NOT_FINITE", f, keyPointer(where, i, "view"),
                    "camera key has a non-finite target, heading, pitch or range");
            continue;
        }
        if (!(v.range > 0.0))
            d.error("ANIM_PATH_RANGE_INVALID", f, keyPointer(where, i, "range"),
                    "camera range must be > 0 m, got " + num(v.range));
        if (v.pitchDeg < -90.0 || v.pitchDeg > 90.0)
            d.error("ANIM_PATH_PITCH_INVALID", f, keyPointer(where, i, "pitch"),
                    "camera pitch must be within [-90, 90] degrees, got " + num(v.pitchDeg));
        if (i > 0 && std::isfinite(keys[i - 1].time) && !(k.time > keys[i - 1].time))
            d.error("ANIM_PATH_KEYS_UNSORTED", f, keyPointer(where, i, "time"),
                    "camera key time " + formatIso8601(k.time) +
                        " is not after the previous key's " + formatIso8601(keys[i - 1].time))
                .hint = "keys must be in strictly increasing time";
    }
    if (d.hasErrors()) return d;

    CameraPath p;
    const std::size_t n = keys.size();
    p.mTimes.resize(n);
    for (auto& v : p.mValues) v.resize(n);
    double heading = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const auto& v = keys[i].view;
        p.mTimes[i] = keys[i].time;
        p.mValues[kX][i] = v.target.x;
        p.mValues[kY][i] = v.target.y;
        p.mValues[kZ][i] = v.target.z;
        // Unwrap so each step is the short way round; the spline then never crosses 180 wrongly.
        heading = i == 0 ? normalizeHeading(v.headingDeg)
                         : heading + shortestHeadingDelta(heading, v.headingDeg);
        p.mValues[kHeading][i] = heading;
        p.mValues[kPitch][i] = v.pitchDeg;
        p.mValues[kLogRange][i] = std::log(v.range);
    }
    for (int c = 0; c < kChannels; ++c) pchipTangents(p.mTimes, p.mValues[c], p.mTangents[c]);
    p.mKeys = std::move(keys);
    p.mMode = mode;
    return p;
}

math::Viewpoint CameraPath::sample(double t) const noexcept {
    if (mKeys.empty() || std::isnan(t)) return {};
    if (t <= mTimes.front()) return mKeys.front().view;
    if (t >= mTimes.back()) return mKeys.back().view;
    const auto it = std::upper_bound(mTimes.begin(), mTimes.end(), t);
    const auto k1 = static_cast<std::size_t>(it - mTimes.begin());
    const std::size_t k0 = k1 - 1;
    if (mMode == PathInterpolation::Step) return mKeys[k0].view;
    const double h = mTimes[k1] - mTimes[k0];
    const double s = (t - mTimes[k0]) / h;
    std::array<double, kChannels> v{};
    for (int c = 0; c < kChannels; ++c) {
        v[c] =
            mMode == PathInterpolation::Linear
                ? mValues[c][k0] + (mValues[c][k1] - mValues[c][k0]) * s
                : hermite(mValues[c][k0], mValues[c][k1], mTangents[c][k0], mTangents[c][k1], h, s);
    }
    math::Viewpoint out;
    out.target = glm::dvec3(v[kX], v[kY], v[kZ]);
    out.headingDeg = normalizeHeading(v[kHeading]);
    out.pitchDeg = std::clamp(v[kPitch], -90.0, 90.0);
    out.range = std::exp(v[kLogRange]);
    return out;
}

void CameraPath::sampleAlong(double t, double dt, int count,
                             std::vector<math::Viewpoint>& out) const {
    out.clear();
    if (count <= 0) return;
    for (int i = 1; i <= count; ++i)
        out.push_back(sample(t + dt * static_cast<double>(i) / static_cast<double>(count)));
}

FlyTo::FlyTo(const math::Viewpoint& from, const math::Viewpoint& to, double startTime,
             double durationSeconds) noexcept
    : mFrom(from),
      mTo(to),
      mStart(std::isfinite(startTime) ? startTime : 0.0),
      mDuration(std::isfinite(durationSeconds) && durationSeconds > 0.0 ? durationSeconds : 0.0) {
    // Ranges must be positive for the log-space blend; a bad viewpoint degrades to 1 m.
    mFrom.range = mFrom.range > 0.0 && std::isfinite(mFrom.range) ? mFrom.range : 1.0;
    mTo.range = mTo.range > 0.0 && std::isfinite(mTo.range) ? mTo.range : 1.0;
    const double dist =
        glm::length(glm::dvec2(to.target.x - from.target.x, to.target.y - from.target.y));
    const double mid = 0.5 * (std::log(mFrom.range) + std::log(mTo.range));
    constexpr double kArcPeakFactor = 0.75;
    mArcLog = dist > 0.0 && std::isfinite(dist)
                  ? std::max(0.0, std::log(kArcPeakFactor * dist) - mid)
                  : 0.0;
}

math::Viewpoint FlyTo::sample(double now) const noexcept {
    if (mDuration <= 0.0 || !(now < mStart + mDuration) || std::isnan(now)) return mTo;
    const double u = (now - mStart) / mDuration;
    if (u <= 0.0) return mFrom;
    const double s = smootherstep(u);
    math::Viewpoint v;
    v.target = mFrom.target + (mTo.target - mFrom.target) * s;
    v.headingDeg = normalizeHeading(mFrom.headingDeg +
                                    shortestHeadingDelta(mFrom.headingDeg, mTo.headingDeg) * s);
    v.pitchDeg = std::clamp(mFrom.pitchDeg + (mTo.pitchDeg - mFrom.pitchDeg) * s, -90.0, 90.0);
    const double logRange =
        std::log(mFrom.range) * (1.0 - s) + std::log(mTo.range) * s + 4.0 * s * (1.0 - s) * mArcLog;
    v.range = std::exp(logRange);
    return v;
}

}  // namespace kiosk::anim
