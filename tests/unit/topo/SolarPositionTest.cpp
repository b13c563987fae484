// NOAA solar position against published reference values (issue 7: sun from date and place).
#include "runtime/core/TimeParse.h"
#include "runtime/topo/Geographic.h"
#include "runtime/topo/SolarPosition.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kiosk::topo {
namespace {

double utc(const char* iso) {
    auto t = parseIso8601(iso);
    EXPECT_TRUE(t.has_value()) << iso;
    return t.value_or(0.0);
}

// Reda & Andreas, "Solar Position Algorithm for Solar Radiation Applications" (NREL 2004),
// example: 2003-10-17 12:30:30 MST at Golden, CO. SPA: azimuth 194.34024, topocentric zenith
// 50.11162 (refraction at 820 mbar; parallax 0.002). NOAA's series agrees within 0.02 degree.
TEST(SolarPositionTest, NrelSpaExample) {
    const SolarPosition p = solarPosition(utc("2003-10-17T19:30:30Z"), 39.742476, -105.1786);
    EXPECT_NEAR(p.azimuthDeg, 194.34024, 0.02);
    EXPECT_NEAR(90.0 - p.altitudeDeg, 50.11162, 0.02);
}

TEST(SolarPositionTest, DeclinationAtEquinoxAndSolstice) {
    // March equinox 2024-03-20 03:06 UTC; June solstice 2024-06-20 20:51 UTC (obliquity 23.44).
    EXPECT_NEAR(solarPosition(utc("2024-03-20T03:06:00Z"), 0, 0).declinationDeg, 0.0, 0.01);
    EXPECT_NEAR(solarPosition(utc("2024-06-20T20:51:00Z"), 0, 0).declinationDeg, 23.439, 0.01);
    EXPECT_NEAR(solarPosition(utc("2024-12-21T09:21:00Z"), 0, 0).declinationDeg, -23.439, 0.01);
}

TEST(SolarPositionTest, EquationOfTimeExtremes) {
    // Sundial fast by 16.4 min around 3 November, slow by 14.2 min around 11 February.
    EXPECT_NEAR(solarPosition(utc("2024-11-03T12:00:00Z"), 0, 0).equationOfTimeMin, 16.4, 0.15);
    EXPECT_NEAR(solarPosition(utc("2024-02-11T12:00:00Z"), 0, 0).equationOfTimeMin, -14.2, 0.15);
}

TEST(SolarPositionTest, ApparentNoonIsDueSouthAtTheRightAltitude) {
    // At Mount Rainier (46.85 N, 121.76 W) the sun crosses the meridian at 12:00 - EoT local
    // mean time, i.e. 12:00 + 121.76 * 4 min - EoT in UTC.
    const double lat = 46.85, lon = -121.76;
    const double day = utc("2026-03-14T00:00:00Z");
    const double eot = solarPosition(day + 20 * 3600.0, lat, lon).equationOfTimeMin;
    const double noon = day + (12 * 60 - 4 * lon - eot) * 60.0;
    const SolarPosition p = solarPosition(noon, lat, lon, false);
    EXPECT_NEAR(p.azimuthDeg, 180.0, 0.05);
    EXPECT_NEAR(p.altitudeDeg, 90.0 - lat + p.declinationDeg, 0.01);
    // Morning sun in the east, evening in the west, night below the horizon.
    EXPECT_LT(solarPosition(noon - 3 * 3600.0, lat, lon).azimuthDeg, 180.0);
    EXPECT_GT(solarPosition(noon + 3 * 3600.0, lat, lon).azimuthDeg, 180.0);
    EXPECT_LT(solarPosition(noon + 12 * 3600.0, lat, lon).altitudeDeg, 0.0);
}

TEST(SolarPositionTest, RefractionLiftsTheLowSun) {
    const double t = utc("2026-03-14T14:45:00Z");  // just after sunrise at Rainier
    const SolarPosition geo = solarPosition(t, 46.85, -121.76, false);
    const SolarPosition app = solarPosition(t, 46.85, -121.76, true);
    ASSERT_LT(std::abs(geo.altitudeDeg), 10.0) << geo.altitudeDeg;
    EXPECT_GT(app.altitudeDeg - geo.altitudeDeg, 0.08);
    EXPECT_LT(app.altitudeDeg - geo.altitudeDeg, 0.6);
    EXPECT_DOUBLE_EQ(app.azimuthDeg, geo.azimuthDeg);
}

TEST(SolarPositionTest, BadInputGivesNoSun) {
    EXPECT_EQ(solarPosition(NAN, 10, 10).altitudeDeg, -90.0);
    EXPECT_EQ(solarPosition(0, 91, 10).altitudeDeg, -90.0);
    EXPECT_EQ(solarPosition(0, 10, INFINITY).altitudeDeg, -90.0);
}

}  // namespace
}  // namespace kiosk::topo

namespace kiosk::topo {
namespace {

// Reference values from PROJ (gdaltransform -s_srs EPSG:326xx/327xx -t_srs EPSG:4326).
TEST(GeographicTest, UtmInverseMatchesProj) {
    struct Case {
        int epsg;
        double x, y, lon, lat;
    };
    const Case cases[] = {
        {32610, 594500, 5189560, -121.760389932156, 46.8528681966363},  // Mount Rainier
        {32610, 500000, 0, -123.0, 0.0},
        {32610, 700000, 5100000, -120.415934879615, 46.0243533958229},
        {32610, 300000, 1000000, -124.819522508767, 9.04204706640632},
        {32733, 400000, 6000000, 13.8885219677738, -36.1395604498603},
    };
    for (const Case& c : cases) {
        auto p = geographicOf(c.epsg, c.x, c.y);
        ASSERT_TRUE(p.has_value()) << c.epsg;
        EXPECT_NEAR(p->latitudeDeg, c.lat, 1e-6) << c.epsg << " " << c.x << " " << c.y;
        EXPECT_NEAR(p->longitudeDeg, c.lon, 1e-6) << c.epsg << " " << c.x << " " << c.y;
    }
    auto g = geographicOf(4326, -121.5, 46.5);
    ASSERT_TRUE(g.has_value());
    EXPECT_EQ(g->latitudeDeg, 46.5);
    EXPECT_EQ(g->longitudeDeg, -121.5);
    EXPECT_FALSE(geographicOf(3857, 0, 0).has_value());
    EXPECT_FALSE(geographicOf(32610, NAN, 0).has_value());
    EXPECT_FALSE(geographicOf(4326, 0, 95).has_value());
}

}  // namespace
}  // namespace kiosk::topo
