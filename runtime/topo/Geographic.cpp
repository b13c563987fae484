#include "runtime/topo/Geographic.h"

#include <cmath>
#include <numbers>

namespace kiosk::topo {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

LatLon inverseUtm(int zone, bool south, double easting, double northing) {
    constexpr double a = 6378137.0, f = 1.0 / 298.257223563, k0 = 0.9996;
    const double e2 = f * (2.0 - f), ep2 = e2 / (1.0 - e2);
    const double x = easting - 500000.0, y = south ? northing - 10000000.0 : northing;
    const double mu =
        y / k0 / (a * (1.0 - e2 / 4.0 - 3.0 * e2 * e2 / 64.0 - 5.0 * e2 * e2 * e2 / 256.0));
    const double s = std::sqrt(1.0 - e2), e1 = (1.0 - s) / (1.0 + s);
    const double phi1 = mu + (3.0 * e1 / 2.0 - 27.0 * std::pow(e1, 3) / 32.0) * std::sin(2 * mu) +
                        (21.0 * e1 * e1 / 16.0 - 55.0 * std::pow(e1, 4) / 32.0) * std::sin(4 * mu) +
                        (151.0 * std::pow(e1, 3) / 96.0) * std::sin(6 * mu) +
                        (1097.0 * std::pow(e1, 4) / 512.0) * std::sin(8 * mu);
    const double sin1 = std::sin(phi1), cos1 = std::cos(phi1), tan1 = std::tan(phi1);
    const double C1 = ep2 * cos1 * cos1, T1 = tan1 * tan1;
    const double w = 1.0 - e2 * sin1 * sin1;
    const double N1 = a / std::sqrt(w), R1 = a * (1.0 - e2) / std::pow(w, 1.5);
    const double D = x / (N1 * k0), D2 = D * D;
    const double lat =
        phi1 -
        (N1 * tan1 / R1) *
            (D2 / 2.0 - (5.0 + 3.0 * T1 + 10.0 * C1 - 4.0 * C1 * C1 - 9.0 * ep2) * D2 * D2 / 24.0 +
             (61.0 + 90.0 * T1 + 298.0 * C1 + 45.0 * T1 * T1 - 252.0 * ep2 - 3.0 * C1 * C1) * D2 *
                 D2 * D2 / 720.0);
    const double dLon = (D - (1.0 + 2.0 * T1 + C1) * D2 * D / 6.0 +
                         (5.0 - 2.0 * C1 + 28.0 * T1 - 3.0 * C1 * C1 + 8.0 * ep2 + 24.0 * T1 * T1) *
                             D2 * D2 * D / 120.0) /
                        cos1;
    const double lon0 = (zone - 1) * 6.0 - 180.0 + 3.0;
    return {lat / kDeg, lon0 + dLon / kDeg};
}

}  // namespace

std::optional<LatLon> geographicOf(int epsg, double x, double y) {
    if (!std::isfinite(x) || !std::isfinite(y)) return std::nullopt;
    if (epsg == 4326) {
        if (std::abs(y) > 90.0) return std::nullopt;
        return LatLon{y, x};
    }
    if (epsg >= 32601 && epsg <= 32660) return inverseUtm(epsg - 32600, false, x, y);
    if (epsg >= 32701 && epsg <= 32760) return inverseUtm(epsg - 32700, true, x, y);
    return std::nullopt;
}

}  // namespace kiosk::topo
