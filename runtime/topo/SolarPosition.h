#pragma once

namespace kiosk::topo {

/** @brief Where the sun is for an observer (degrees). */
struct SolarPosition {
    double azimuthDeg = 0;         ///< clockwise from north, [0, 360)
    double altitudeDeg = 0;        ///< above the horizon; with refraction if requested
    double declinationDeg = 0;     ///< apparent declination
    double equationOfTimeMin = 0;  ///< apparent minus mean solar time, minutes
};

/**
 * @brief Sun position from the NOAA solar calculator's algorithm (Meeus, "Astronomical
 * Algorithms", low-precision series; about 0.01 degree for years 1800-2100; universal time is
 * used for dynamical time, which moves the sun by about 0.003 degree).
 *
 * `unixSeconds`: UTC seconds since 1970-01-01. `latitudeDeg` north positive, `longitudeDeg`
 * east positive. `refraction`: add NOAA's standard atmospheric refraction to the altitude (what
 * an observer sees; for lighting the difference is below 0.6 degree, only near the horizon).
 * Bad input (non-finite, |latitude| > 90) gives a sun below the horizon at altitude -90, so a
 * caller lights nothing rather than something wrong. Pure, any thread.
 */
SolarPosition solarPosition(double unixSeconds, double latitudeDeg, double longitudeDeg,
                            bool refraction = true);

}  // namespace kiosk::topo
