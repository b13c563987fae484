#include "runtime/topo/SolarPosition.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace kiosk::topo {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

double wrap360(double a) {
    a = std::fmod(a, 360.0);
    return a < 0 ? a + 360.0 : a;
}

/** NOAA's piecewise fit of standard refraction (degrees) at apparent elevation `e` degrees. */
double refractionDeg(double e) {
    if (e > 85.0) return 0.0;
    const double t = std::tan(e * kDeg);
    double arcsec;
    if (e > 5.0)
        arcsec = 58.1 / t - 0.07 / (t * t * t) + 0.000086 / std::pow(t, 5.0);
    else if (e > -0.575)
        arcsec = 1735.0 + e * (-518.2 + e * (103.4 + e * (-12.79 + e * 0.711)));
    else
        arcsec = -20.774 / t;
    return arcsec / 3600.0;
}

}  // namespace

SolarPosition solarPosition(double unixSeconds, double latitudeDeg, double longitudeDeg,
                            bool refraction) {
    SolarPosition p;
    if (!std::isfinite(unixSeconds) || !std::isfinite(latitudeDeg) ||
        !std::isfinite(longitudeDeg) || std::abs(latitudeDeg) > 90.0) {
        p.altitudeDeg = -90.0;
        return p;
    }
    const double jd = unixSeconds / 86400.0 + 2440587.5;
    const double T = (jd - 2451545.0) / 36525.0;  // Julian centuries since J2000.0
    const double L0 = wrap360(280.46646 + T * (36000.76983 + T * 0.0003032));
    const double M = 357.52911 + T * (35999.05029 - 0.0001537 * T);
    const double e = 0.016708634 - T * (0.000042037 + 0.0000001267 * T);
    const double Mr = M * kDeg;
    const double C = std::sin(Mr) * (1.914602 - T * (0.004817 + 0.000014 * T)) +
                     std::sin(2 * Mr) * (0.019993 - 0.000101 * T) + std::sin(3 * Mr) * 0.000289;
    const double trueLong = L0 + C;
    const double omega = (125.04 - 1934.136 * T) * kDeg;
    const double lambda = (trueLong - 0.00569 - 0.00478 * std::sin(omega)) * kDeg;
    const double eps0 =
        23.0 + (26.0 + (21.448 - T * (46.815 + T * (0.00059 - T * 0.001813))) / 60.0) / 60.0;
    const double eps = (eps0 + 0.00256 * std::cos(omega)) * kDeg;
    const double decl = std::asin(std::sin(eps) * std::sin(lambda));
    const double y = std::pow(std::tan(eps / 2), 2);
    const double L0r = L0 * kDeg;
    const double eot = 4.0 / kDeg *
                       (y * std::sin(2 * L0r) - 2 * e * std::sin(Mr) +
                        4 * e * y * std::sin(Mr) * std::cos(2 * L0r) -
                        0.5 * y * y * std::sin(4 * L0r) - 1.25 * e * e * std::sin(2 * Mr));
    // True solar time at the observer, minutes after its local apparent midnight.
    double dayMinutes = std::fmod(unixSeconds / 60.0, 1440.0);
    if (dayMinutes < 0) dayMinutes += 1440.0;
    const double tst = std::fmod(dayMinutes + eot + 4.0 * longitudeDeg + 2880.0, 1440.0);
    const double ha = (tst / 4.0 - 180.0) * kDeg;  // hour angle, 0 at apparent noon
    const double lat = latitudeDeg * kDeg;
    const double cosZen = std::clamp(
        std::sin(lat) * std::sin(decl) + std::cos(lat) * std::cos(decl) * std::cos(ha), -1.0, 1.0);
    const double zen = std::acos(cosZen);
    // Azimuth from north, clockwise: atan2 of the east and north components of the sun.
    const double east = -std::cos(decl) * std::sin(ha);
    const double north =
        std::cos(lat) * std::sin(decl) - std::sin(lat) * std::cos(decl) * std::cos(ha);
    p.azimuthDeg = wrap360(std::atan2(east, north) / kDeg);
    p.altitudeDeg = 90.0 - zen / kDeg;
    if (refraction) p.altitudeDeg += refractionDeg(p.altitudeDeg);
    p.declinationDeg = decl / kDeg;
    p.equationOfTimeMin = eot;
    return p;
}

}  // namespace kiosk::topo
