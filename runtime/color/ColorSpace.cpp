#include "runtime/color/ColorSpace.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

namespace kiosk::color {

namespace {

constexpr double kPi = 3.14159265358979323846;
// D65 white of the sRGB matrices below (Y normalised to 1).
constexpr double kWhiteX = 0.95047, kWhiteY = 1.0, kWhiteZ = 1.08883;
constexpr double kDelta = 6.0 / 29.0;
// Below this saturation angle Moreland treats a colour as unsaturated (hue meaningless).
constexpr double kUnsaturated = 0.05;

double labF(double t) {
    return t > kDelta * kDelta * kDelta ? std::cbrt(t) : t / (3 * kDelta * kDelta) + 4.0 / 29.0;
}
double labFInv(double t) {
    return t > kDelta ? t * t * t : 3 * kDelta * kDelta * (t - 4.0 / 29.0);
}
double clamp01(double v) {
    return std::isnan(v) ? 0.0 : std::clamp(v, 0.0, 1.0);
}

double angleDiff(double a, double b) {
    double d = std::fmod(std::fabs(a - b), 2 * kPi);
    return d > kPi ? 2 * kPi - d : d;
}

// Moreland's AdjustHue: spin the hue of an unsaturated end so the interpolation does not pass
// through an unrelated hue on its way to grey.
double adjustHue(double mSat, double sSat, double hSat, double mUnsat) {
    if (mSat >= mUnsat) return hSat;
    const double sinS = std::sin(sSat);
    if (mSat <= 0 || sinS <= 0) return hSat;
    const double spin = sSat * std::sqrt(mUnsat * mUnsat - mSat * mSat) / (mSat * sinS);
    return hSat > -kPi / 3 ? hSat + spin : hSat - spin;
}

struct NamedColor {
    std::string_view name;
    Rgba color;
};
constexpr float k8 = 1.0f / 255.0f;
const NamedColor kNamed[] = {
    {"transparent", {0, 0, 0, 0}},
    {"white", {1, 1, 1, 1}},
    {"black", {0, 0, 0, 1}},
    {"red", {1, 0, 0, 1}},
    {"green", {0, 128 * k8, 0, 1}},
    {"blue", {0, 0, 1, 1}},
    {"yellow", {1, 1, 0, 1}},
    {"cyan", {0, 1, 1, 1}},
    {"aqua", {0, 1, 1, 1}},
    {"magenta", {1, 0, 1, 1}},
    {"gray", {128 * k8, 128 * k8, 128 * k8, 1}},
    {"grey", {128 * k8, 128 * k8, 128 * k8, 1}},
    {"orange", {1, 165 * k8, 0, 1}},
    {"brown", {165 * k8, 42 * k8, 42 * k8, 1}},
    {"purple", {128 * k8, 0, 128 * k8, 1}},
    {"violet", {238 * k8, 130 * k8, 238 * k8, 1}},
    {"indigo", {75 * k8, 0, 130 * k8, 1}},
    {"navy", {0, 0, 128 * k8, 1}},
};

int hexDigit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

}  // namespace

std::optional<Space> parseSpace(std::string_view name) {
    if (name == "srgb") return Space::Srgb;
    if (name == "linear") return Space::Linear;
    if (name == "lab") return Space::Lab;
    if (name == "msh") return Space::Msh;
    return std::nullopt;
}

const char* spaceName(Space s) noexcept {
    switch (s) {
        case Space::Srgb:
            return "srgb";
        case Space::Linear:
            return "linear";
        case Space::Lab:
            return "lab";
        case Space::Msh:
            return "msh";
    }
    return "srgb";
}

double srgbToLinear(double c) noexcept {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double linearToSrgb(double c) noexcept {
    c = clamp01(c);
    return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

Vec3 linearToXyz(const Vec3& c) noexcept {
    return {0.4124564 * c[0] + 0.3575761 * c[1] + 0.1804375 * c[2],
            0.2126729 * c[0] + 0.7151522 * c[1] + 0.0721750 * c[2],
            0.0193339 * c[0] + 0.1191920 * c[1] + 0.9503041 * c[2]};
}

Vec3 xyzToLinear(const Vec3& x) noexcept {
    // The exact inverse of the forward matrix (the rounded published inverse would make
    // round trips drift by ~1e-6).
    static const std::array<double, 9> inv = [] {
        const double a = 0.4124564, b = 0.3575761, c = 0.1804375, d = 0.2126729, e = 0.7151522,
                     f = 0.0721750, g = 0.0193339, h = 0.1191920, i = 0.9503041;
        const double A = e * i - f * h, B = -(d * i - f * g), C = d * h - e * g;
        const double det = a * A + b * B + c * C;
        return std::array<double, 9>{A / det, -(b * i - c * h) / det, (b * f - c * e) / det,
                                     B / det, (a * i - c * g) / det,  -(a * f - c * d) / det,
                                     C / det, -(a * h - b * g) / det, (a * e - b * d) / det};
    }();
    return {inv[0] * x[0] + inv[1] * x[1] + inv[2] * x[2],
            inv[3] * x[0] + inv[4] * x[1] + inv[5] * x[2],
            inv[6] * x[0] + inv[7] * x[1] + inv[8] * x[2]};
}

Vec3 xyzToLab(const Vec3& x) noexcept {
    const double fx = labF(x[0] / kWhiteX), fy = labF(x[1] / kWhiteY), fz = labF(x[2] / kWhiteZ);
    return {116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)};
}

Vec3 labToXyz(const Vec3& lab) noexcept {
    const double fy = (lab[0] + 16) / 116;
    const double fx = fy + lab[1] / 500, fz = fy - lab[2] / 200;
    return {kWhiteX * labFInv(fx), kWhiteY * labFInv(fy), kWhiteZ * labFInv(fz)};
}

Vec3 labToMsh(const Vec3& lab) noexcept {
    const double m = std::sqrt(lab[0] * lab[0] + lab[1] * lab[1] + lab[2] * lab[2]);
    const double s = m > 0 ? std::acos(std::clamp(lab[0] / m, -1.0, 1.0)) : 0.0;
    const double h = s > 0 ? std::atan2(lab[2], lab[1]) : 0.0;
    return {m, s, h};
}

Vec3 mshToLab(const Vec3& msh) noexcept {
    return {msh[0] * std::cos(msh[1]), msh[0] * std::sin(msh[1]) * std::cos(msh[2]),
            msh[0] * std::sin(msh[1]) * std::sin(msh[2])};
}

Vec3 toSpace(const Vec3& c, Space space) noexcept {
    if (space == Space::Srgb) return c;
    const Vec3 lin{srgbToLinear(c[0]), srgbToLinear(c[1]), srgbToLinear(c[2])};
    if (space == Space::Linear) return lin;
    const Vec3 lab = xyzToLab(linearToXyz(lin));
    return space == Space::Lab ? lab : labToMsh(lab);
}

Vec3 fromSpace(const Vec3& v, Space space) noexcept {
    if (space == Space::Srgb) return {clamp01(v[0]), clamp01(v[1]), clamp01(v[2])};
    Vec3 lin = v;
    if (space == Space::Lab || space == Space::Msh) {
        const Vec3 lab = space == Space::Msh ? mshToLab(v) : v;
        lin = xyzToLinear(labToXyz(lab));
    }
    return {linearToSrgb(lin[0]), linearToSrgb(lin[1]), linearToSrgb(lin[2])};
}

Vec3 interpolate(const Vec3& a, const Vec3& b, double t, Space space) noexcept {
    t = clamp01(t);
    if (space != Space::Msh) {
        const Vec3 p = toSpace(a, space), q = toSpace(b, space);
        return fromSpace(
            {p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])}, space);
    }
    Vec3 p = toSpace(a, Space::Msh), q = toSpace(b, Space::Msh);
    if (p[1] > kUnsaturated && q[1] > kUnsaturated && angleDiff(p[2], q[2]) > kPi / 3) {
        const double mMid = std::max({p[0], q[0], 88.0});
        if (t < 0.5) {
            q = {mMid, 0, 0};
            t = 2 * t;
        } else {
            p = {mMid, 0, 0};
            t = 2 * t - 1;
        }
    }
    if (p[1] < kUnsaturated && q[1] > kUnsaturated)
        p[2] = adjustHue(q[0], q[1], q[2], p[0]);
    else if (q[1] < kUnsaturated && p[1] > kUnsaturated)
        q[2] = adjustHue(p[0], p[1], p[2], q[0]);
    return fromSpace({p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])},
                     Space::Msh);
}

std::optional<Rgba> parseColor(std::string_view text) {
    if (!text.empty() && text[0] == '#') {
        std::string_view h = text.substr(1);
        int d[8] = {};
        for (std::size_t i = 0; i < h.size() && i < 8; ++i)
            if ((d[i] = hexDigit(h[i])) < 0) return std::nullopt;
        auto byte = [&](int hi, int lo) { return float(d[hi] * 16 + d[lo]) / 255.0f; };
        if (h.size() == 3)
            return Rgba{float(d[0] * 17) / 255.0f, float(d[1] * 17) / 255.0f,
                        float(d[2] * 17) / 255.0f, 1.0f};
        if (h.size() == 6) return Rgba{byte(0, 1), byte(2, 3), byte(4, 5), 1.0f};
        if (h.size() == 8) return Rgba{byte(0, 1), byte(2, 3), byte(4, 5), byte(6, 7)};
        return std::nullopt;
    }
    std::string lower(text);
    for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (const auto& n : kNamed)
        if (n.name == lower) return n.color;
    return std::nullopt;
}

const std::array<std::string_view, 18>& colorNames() noexcept {
    static const std::array<std::string_view, 18> names = [] {
        std::array<std::string_view, 18> out{};
        for (std::size_t i = 0; i < out.size(); ++i) out[i] = kNamed[i].name;
        return out;
    }();
    return names;
}

std::string formatColor(const Rgba& c) {
    auto dn = [](float v) { return int(std::lround(clamp01(v) * 255.0)); };
    char buf[16];
    std::snprintf(buf, sizeof buf, "#%02x%02x%02x%02x", dn(c.r), dn(c.g), dn(c.b), dn(c.a));
    return buf;
}

}  // namespace kiosk::color
