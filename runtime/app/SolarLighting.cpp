#include "runtime/app/SolarLighting.h"

#include "runtime/core/Log.h"
#include "runtime/topo/SolarPosition.h"

#include <atomic>

namespace kiosk::app {

std::optional<topo::LatLon> solarSite(const config::Lighting& lighting, const io::StoreInfo& store,
                                      const std::string& elevationLayer) {
    if (lighting.latitude && lighting.longitude)
        return topo::LatLon{*lighting.latitude, *lighting.longitude};
    double x = 0.5 * (store.grid.minX + store.grid.maxX),
           y = 0.5 * (store.grid.minY + store.grid.maxY);
    if (const io::LayerInfo* l = store.findLayer(elevationLayer);
        l && l->dataMaxX > l->dataMinX && l->dataMaxY > l->dataMinY) {
        x = 0.5 * (l->dataMinX + l->dataMaxX);
        y = 0.5 * (l->dataMinY + l->dataMaxY);
    }
    return topo::geographicOf(store.grid.srsId, x, y);
}

std::optional<SunAngles> solarSun(const config::Lighting& lighting, const io::StoreInfo& store,
                                  const std::string& elevationLayer, double time) {
    if (!lighting.solar) return std::nullopt;
    const auto site = solarSite(lighting, store, elevationLayer);
    if (!site) {
        // Once per process: this is evaluated every frame.
        static std::atomic<bool> warned{false};
        if (!warned.exchange(true))
            KIOSK_LOG_WARN("app::SolarLighting",
                           "%s: lighting.solar needs latitude/longitude: the store's CRS (%s, "
                           "srs_id %d) is not geographic or UTM; the fixed sun is used",
                           store.path.c_str(), store.grid.crsName.c_str(), store.grid.srsId);
        return std::nullopt;
    }
    const topo::SolarPosition p = topo::solarPosition(time, site->latitudeDeg, site->longitudeDeg);
    return SunAngles{p.azimuthDeg, p.altitudeDeg};
}

}  // namespace kiosk::app
