#include "runtime/color/TransferFunction.h"

#include <algorithm>
#include <cmath>

namespace kiosk::color {

namespace {

Rgba lerpStops(const Stop& a, const Stop& b, double t, Space space) {
    const Vec3 c =
        interpolate({a.color.r, a.color.g, a.color.b}, {b.color.r, b.color.g, b.color.b}, t, space);
    return Rgba{float(c[0]), float(c[1]), float(c[2]),
                float(a.color.a + t * (double(b.color.a) - double(a.color.a)))};
}

double opacityAt(const std::vector<OpacityPoint>& ramp, double v) {
    if (ramp.empty()) return 1.0;
    if (v <= ramp.front().value) return ramp.front().opacity;
    if (v >= ramp.back().value) return ramp.back().opacity;
    for (std::size_t i = 0; i + 1 < ramp.size(); ++i) {
        const auto &a = ramp[i], &b = ramp[i + 1];
        if (v >= a.value && v < b.value) {
            const double span = b.value - a.value;
            return span > 0 ? a.opacity + (v - a.value) / span * (b.opacity - a.opacity)
                            : b.opacity;
        }
    }
    return ramp.back().opacity;
}

}  // namespace

Diagnostics TransferFunction::finalize(bool explicitDomain, bool explicitBelow, bool explicitAbove,
                                       const std::string& file, const std::string& where) {
    Diagnostics d;
    const std::string what = "transfer function \"" + name + "\"";
    if (stops.empty() && classes.empty()) {
        d.error("TF_EMPTY", file, where, what + " has no stops and no classes");
        return d;
    }
    auto finite = [](double v) { return std::isfinite(v); };
    for (const auto& s : stops)
        if (!finite(s.value))
            d.error("TF_NOT_FINITE", file, where, what + ": stop value not finite");
    for (const auto& c : classes)
        if (!finite(c.from))
            d.error("TF_NOT_FINITE", file, where, what + ": class bound not finite");
    if (d.hasErrors()) return d;

    std::stable_sort(stops.begin(), stops.end(),
                     [](const Stop& a, const Stop& b) { return a.value < b.value; });
    std::stable_sort(classes.begin(), classes.end(),
                     [](const ClassBreak& a, const ClassBreak& b) { return a.from < b.from; });
    std::stable_sort(
        opacity.begin(), opacity.end(),
        [](const OpacityPoint& a, const OpacityPoint& b) { return a.value < b.value; });

    if (!explicitDomain) {
        if (!stops.empty()) {
            domainMin = stops.front().value;
            domainMax = stops.back().value;
        } else {
            domainMin = classes.front().from;
            const double last = classes.back().from;
            const double step = classes.size() > 1 ? last - classes[classes.size() - 2].from : 1.0;
            domainMax = last + (step > 0 ? step : 1.0);
        }
    }
    if (!(domainMin < domainMax) || !finite(domainMin) || !finite(domainMax)) {
        d.error("TF_DOMAIN", file, where,
                what + ": domain [" + std::to_string(domainMin) + ", " + std::to_string(domainMax) +
                    "] is empty (needs two distinct stop values)");
        return d;
    }
    if (!explicitBelow && !belowGiven) below = evaluate(domainMin);
    if (!explicitAbove && !aboveGiven) above = evaluate(domainMax);
    return d;
}

Rgba TransferFunction::evaluate(double value) const {
    if (std::isnan(value)) return nodata;
    const double v = std::clamp(value, domainMin, domainMax);
    Rgba c{0, 0, 0, 0};
    if (!classes.empty()) {
        c = classes.front().color;
        for (const auto& k : classes)
            if (k.from <= v) c = k.color;
    } else if (!stops.empty()) {
        if (v <= stops.front().value) {
            c = stops.front().color;
        } else if (v >= stops.back().value) {
            c = stops.back().color;
        } else {
            // Last segment whose start is <= v: equal stop values form a step, the later wins.
            std::size_t i = 0;
            while (i + 2 < stops.size() && stops[i + 1].value <= v) ++i;
            const Stop &a = stops[i], &b = stops[i + 1];
            const double span = b.value - a.value;
            c = span > 0 ? lerpStops(a, b, (v - a.value) / span, space) : b.color;
        }
    }
    c.a = float(std::clamp(double(c.a) * opacityAt(opacity, v), 0.0, 1.0));
    return c;
}

Rgba TransferFunction::shade(double value) const {
    if (std::isnan(value)) return nodata;
    if (value < domainMin) return below;
    if (value > domainMax) return above;
    return evaluate(value);
}

TransferFunction TransferFunction::rescaled(double newMin, double newMax) const {
    TransferFunction out = *this;
    const double span = domainMax - domainMin;
    auto map = [&](double x) {
        return span != 0 ? newMin + (x - domainMin) / span * (newMax - newMin) : newMin;
    };
    for (auto& s : out.stops) s.value = map(s.value);
    for (auto& c : out.classes) c.from = map(c.from);
    for (auto& o : out.opacity) o.value = map(o.value);
    out.domainMin = newMin;
    out.domainMax = newMax;
    return out;
}

std::uint8_t toByte(double v) noexcept {
    if (std::isnan(v)) return 0;
    return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}

std::vector<std::uint8_t> buildLut(const TransferFunction& tf, int size) {
    size = std::max(size, kMinLutSize);
    std::vector<std::uint8_t> lut(std::size_t(size) * 4);
    for (int i = 0; i < size; ++i) {
        const double v =
            tf.domainMin + (tf.domainMax - tf.domainMin) * double(i) / double(size - 1);
        const Rgba c = tf.evaluate(v);
        std::uint8_t* p = &lut[std::size_t(i) * 4];
        p[0] = toByte(c.r);
        p[1] = toByte(c.g);
        p[2] = toByte(c.b);
        p[3] = toByte(c.a);
    }
    return lut;
}

double lutCoordinate(double value, double domainMin, double domainMax, int size) noexcept {
    const double t =
        std::clamp((value - domainMin) / std::max(domainMax - domainMin, 1e-20), 0.0, 1.0);
    return (t * (size - 1.0) + 0.5) / size;
}

}  // namespace kiosk::color
