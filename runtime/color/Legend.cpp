#include "runtime/color/Legend.h"

#include <cmath>
#include <cstdio>

namespace kiosk::color {

namespace {

std::string formatNumber(double v, int decimals) {
    if (std::fabs(v) < 1e-12) v = 0.0;  // never print "-0"
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    return buf;
}

std::string shortNumber(double v) {
    if (std::fabs(v) < 1e-12) v = 0.0;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

}  // namespace

double niceNumber(double x, bool round) noexcept {
    if (!(x > 0) || !std::isfinite(x)) return 1.0;
    const double e = std::floor(std::log10(x));
    const double f = x / std::pow(10.0, e);
    double nf;
    if (round)
        nf = f < 1.5 ? 1 : f < 3 ? 2 : f < 7 ? 5 : 10;
    else
        nf = f <= 1 ? 1 : f <= 2 ? 2 : f <= 5 ? 5 : 10;
    return nf * std::pow(10.0, e);
}

std::vector<LegendTick> legendTicks(const TransferFunction& tf, int maxTicks) {
    std::vector<LegendTick> out;
    const double lo = tf.domainMin, hi = tf.domainMax;
    if (tf.discrete() || !(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return out;
    if (maxTicks < 2) maxTicks = 2;
    const double range = niceNumber(hi - lo, false);
    const double step = niceNumber(range / (maxTicks - 1), true);
    const int decimals = std::max(0, int(-std::floor(std::log10(step))));
    const double eps = step * 1e-9;
    for (double k = std::ceil((lo - eps) / step); k * step <= hi + eps; k += 1.0) {
        const double v = k * step;
        out.push_back({v, (v - lo) / (hi - lo), formatNumber(v, decimals)});
        if (out.size() > 64) break;  // defensive: absurd domains never loop for long
    }
    return out;
}

std::vector<LegendPatch> legendPatches(const TransferFunction& tf) {
    std::vector<LegendPatch> out;
    for (std::size_t i = 0; i < tf.classes.size(); ++i) {
        const auto& c = tf.classes[i];
        std::string label = c.label;
        if (label.empty()) {
            const double to = i + 1 < tf.classes.size() ? tf.classes[i + 1].from : tf.domainMax;
            label = shortNumber(c.from) + " - " + shortNumber(to);
            if (!tf.units.empty()) label += " " + tf.units;
        }
        out.push_back({c.color, label});
    }
    return out;
}

}  // namespace kiosk::color
