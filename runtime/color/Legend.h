#pragma once

#include "runtime/color/TransferFunction.h"

#include <string>
#include <vector>

// Legend content derived from the same TransferFunction that fills the LUT, so the colour bar and
// the terrain can never disagree. Pure; any thread.
namespace kiosk::color {

/** @brief A labelled tick on a continuous colour bar. */
struct LegendTick {
    double value = 0;     ///< data units
    double position = 0;  ///< 0 at domainMin .. 1 at domainMax along the bar
    std::string label;    ///< number formatted to the tick spacing (no units)
};

/** @brief A class patch: its colour and label ("0.5 - 1 m" when the author gave none). */
struct LegendPatch {
    Rgba color;
    std::string label;
};

/** @brief "Nice" number near x (1, 2, 5 times a power of ten), Heckbert's Graphics Gems rule. */
double niceNumber(double x, bool round) noexcept;

/**
 * @brief Ticks at nice values inside [domainMin, domainMax], at most about `maxTicks` of them
 * (>= 2). Empty for a discrete function (use legendPatches) or an empty domain.
 */
std::vector<LegendTick> legendTicks(const TransferFunction& tf, int maxTicks = 6);

/** @brief One patch per class, in order; empty for a continuous function. */
std::vector<LegendPatch> legendPatches(const TransferFunction& tf);

}  // namespace kiosk::color
