#pragma once

#include "config/Scenario.h"
#include "runtime/io/StoreTypes.h"
#include "runtime/topo/Geographic.h"

#include <optional>
#include <string>

namespace kiosk::app {

/** @brief A sun direction as the renderer takes it (render::sunDirection). */
struct SunAngles {
    double azimuthDeg = 315;
    double altitudeDeg = 45;
};

/**
 * @brief Where `lighting.solar` puts the sun: lighting.latitude/longitude, else the centre of
 * the elevation layer's data (else of the grid) converted from the store's CRS
 * (topo::geographicOf). nullopt when the CRS is not one geographicOf() knows.
 */
std::optional<topo::LatLon> solarSite(const config::Lighting& lighting, const io::StoreInfo& store,
                                      const std::string& elevationLayer);

/**
 * @brief The sun at data time `time` (UTC epoch seconds) for a scenario whose lighting is
 * `solar`: NOAA solar position over solarSite(), with refraction. A sun below the horizon
 * lights nothing (only the ambient term remains): night. nullopt when lighting.solar is false
 * or the site is unknown (the caller keeps its fixed or keyed sun; warned once in the log).
 * Thread: any.
 */
std::optional<SunAngles> solarSun(const config::Lighting& lighting, const io::StoreInfo& store,
                                  const std::string& elevationLayer, double time);

}  // namespace kiosk::app
