#pragma once

#include "config/Scenario.h"
#include "runtime/core/Diagnostics.h"
#include "runtime/io/StoreTypes.h"

#include <functional>
#include <string>

// Checks that need the stores' metadata: does what the scenario names exist, do times, units
// and value ranges fit? config/ does not open stores (no SQLite here); the caller does and
// answers through StoreLookup.
namespace kiosk::config {

/**
 * @brief Metadata of an opened store by scenario store id, or nullptr when that store could not
 * be opened (the caller reports why; checkMeaning then skips checks that need it).
 */
using StoreLookup = std::function<const io::StoreInfo*(const std::string& storeId)>;

/**
 * @brief Meaning checks over a scenario that parsed cleanly.
 *
 * Errors: SCENARIO_STORE_UNAVAILABLE (lookup returned nullptr), SCENARIO_UNKNOWN_LAYER,
 * SCENARIO_UNKNOWN_SEQUENCE (with did-you-mean over the store's names), SCENARIO_LAYER_KIND
 * (e.g. a thematic layer on an elevation table), SCENARIO_UNITS (transfer function units differ
 * from the data's), SCENARIO_TIME_RANGE (clock and sequence do not overlap at all),
 * SCENARIO_DOMAIN (data range entirely outside the transfer function's domain),
 * SCENARIO_STORE_CRS / SCENARIO_STORE_GRID (a layer's store differs from the terrain store in
 * CRS or tile grid; the pointer names the layer's "source/store").
 * Warnings: SCENARIO_TIME_RANGE / SCENARIO_DOMAIN when the overlap is only partial.
 * Messages carry file:line:col of the referencing JSON value. Any thread; never throws.
 */
Diagnostics checkMeaning(const Scenario& scenario, const StoreLookup& lookup);

}  // namespace kiosk::config
