#pragma once

#include "config/MeaningCheck.h"
#include "config/Scenario.h"

// Units a transfer function shows in its legend when the scenario does not state them: those
// the store recorded for the data it colours (CF `units`, a GeoTIFF's unit type, --units).
namespace kiosk::config {

/**
 * @brief Units the store records for the data `src` names: a sequence's, or a layer's; "" when
 * the store records none, says "class" (categorical), or cannot be looked up.
 */
std::string storedUnits(const SourceRef& src, const StoreLookup& lookup);

/**
 * @brief Every transfer function without `units` takes the units of the data it colours (layers
 * and projective mappings) when all of it that records units agrees (by sameUnits); data in
 * different units leaves it without (checkMeaning warns SCENARIO_UNITS). Stated units are kept
 * (a mismatch is checkMeaning's SCENARIO_UNITS error). Call after checkMeaning succeeded.
 */
void adoptDataUnits(Scenario& scenario, const StoreLookup& lookup);

}  // namespace kiosk::config
