#pragma once

#include "runtime/io/StoreTypes.h"

#include <string>

// Layers from several stores (docs/scenario-format.md "stores"): a layer's store must share the
// terrain store's CRS and tile grid, because the scene requests every layer's tiles by the
// terrain's tile ids. Checked by `validate` (MeaningCheck.cpp) and again by the scene.
namespace kiosk::config {

/** @brief Same CRS: the same srs id, and the same WKT when either has no id. */
bool sameCrs(const io::TileGrid& a, const io::TileGrid& b);
/** @brief "WGS 84 / UTM zone 55S (srs_id 32755)" for messages, as `geokiosk info` names it. */
std::string crsText(const io::TileGrid& g);
/**
 * @brief Same tile grid: origin, tile size and the pixel size of every level both have (one
 * store may have finer levels than the other). Empty when they match, else what differs.
 */
std::string tileGridDifference(const io::TileGrid& a, const io::TileGrid& b);

}  // namespace kiosk::config
