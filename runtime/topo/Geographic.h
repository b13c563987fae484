#pragma once

#include <optional>

namespace kiosk::topo {

/** @brief A geographic position on WGS 84, degrees (east and north positive). */
struct LatLon {
    double latitudeDeg = 0;
    double longitudeDeg = 0;
};

/**
 * @brief Geographic position of a point of the store's CRS, for the sun's position over the
 * data (no PROJ at run time: the CRSs the importer writes are handled in closed form).
 * Supported: EPSG:4326 (x = longitude, y = latitude) and WGS 84 / UTM zones, EPSG:32601..32660
 * (north) and 32701..32760 (south), by the inverse transverse Mercator series (Snyder 1987,
 * USGS PP 1395, eq. 8-17..8-25; agrees with PROJ within 1e-6 degree inside a zone).
 * Anything else, or non-finite input: nullopt. Pure, any thread.
 */
std::optional<LatLon> geographicOf(int epsg, double x, double y);

}  // namespace kiosk::topo
