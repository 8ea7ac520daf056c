// Sun position and direct sunlight (precompute/sky/sun.h).
#include "sky/sun.h"

#include <gtest/gtest.h>

#include <cmath>

namespace meadow::sky {
namespace {

constexpr double kDegrees = M_PI / 180.0;

double elevationDegrees(const glm::dvec3& d) {
    return elevation(d) / kDegrees;
}

TEST(Sun, DeclinationAtSolsticesAndEquinoxes) {
    // Tolerance: Spencer's series is good to ~0.03 degrees, and the solstice or equinox falls
    // within half a day of these dates (declination moves at most 0.4 degrees per day).
    EXPECT_NEAR(solarDeclination(172) / kDegrees, 23.44, 0.1);  // 21 June
    EXPECT_NEAR(solarDeclination(355) / kDegrees, -23.44, 0.1); // 21 December
    EXPECT_NEAR(solarDeclination(80) / kDegrees, 0.0, 0.5);     // 21 March
    EXPECT_NEAR(solarDeclination(266) / kDegrees, 0.0, 0.5);    // 23 September
}

TEST(Sun, NoonElevationIsNinetyMinusLatitudeMinusDeclination) {
    for (double latitude : {-66.0, -35.0, 0.0, 23.0, 40.4, 52.0, 70.0})
        for (double day : {1.0, 80.0, 152.0, 172.0, 266.0, 355.0}) {
            const double declination = solarDeclination(day) / kDegrees;
            const glm::dvec3 d = sunDirection(latitude, day, 12.0);
            // Tolerance: at h = 0 the formula reduces to sin(e) = cos(phi - delta) exactly; what
            // remains is rounding, amplified by asin near 90 degrees (sqrt of 1e-16).
            EXPECT_NEAR(elevationDegrees(d), 90.0 - std::abs(latitude - declination), 1e-6)
                << "latitude " << latitude << " day " << day;
            EXPECT_NEAR(d.x, 0.0, 1e-12); // on the meridian: neither east nor west
        }
}

TEST(Sun, BelowTheHorizonAtMidnightAtMidLatitudes) {
    // Below the polar circles the sun sets every day of the year.
    for (double latitude : {-60.0, -40.0, -20.0, 0.0, 20.0, 40.4, 60.0})
        for (double day = 1.0; day <= 365.0; day += 7.0)
            EXPECT_LT(sunDirection(latitude, day, 0.0).y, 0.0) << "latitude " << latitude << " day " << day;
    // ... while above the arctic circle at midsummer it does not.
    EXPECT_GT(sunDirection(75.0, 172.0, 0.0).y, 0.0);
}

TEST(Sun, MorningAndAfternoonAreMirrorImages) {
    for (double latitude : {-30.0, 40.4, 65.0})
        for (double offset : {0.5, 2.0, 4.75, 7.0}) {
            const glm::dvec3 morning = sunDirection(latitude, 152.0, 12.0 - offset);
            const glm::dvec3 afternoon = sunDirection(latitude, 152.0, 12.0 + offset);
            // Tolerance: cos is even and sin odd in the hour angle; rounding only.
            EXPECT_NEAR(morning.y, afternoon.y, 1e-12);
            EXPECT_NEAR(morning.z, afternoon.z, 1e-12);
            EXPECT_NEAR(morning.x, -afternoon.x, 1e-12);
            EXPECT_GT(morning.x, 0.0); // rises in the east (+x)
        }
}

TEST(Sun, CompassDirections) {
    // Northern mid latitudes: the noon sun is due south (-z); southern ones: due north.
    EXPECT_LT(sunDirection(40.4, 152.0, 12.0).z, 0.0);
    EXPECT_GT(sunDirection(-35.0, 152.0, 12.0).z, 0.0);
    // At an equinox the sun rises due east at 6 h and sets due west at 18 h, at any latitude.
    for (double latitude : {0.0, 40.4, 60.0}) {
        const double day = 80.0 + 0.35; // the March 2024-ish equinox, declination ~0
        const glm::dvec3 rise = sunDirection(latitude, day, 6.0), set = sunDirection(latitude, day, 18.0);
        // Tolerance: Spencer's declination at this day is within ~0.05 degrees of 0.
        EXPECT_NEAR(rise.y, 0.0, 2e-3);
        EXPECT_NEAR(rise.x, 1.0, 1e-5);
        EXPECT_NEAR(set.x, -1.0, 1e-5);
    }
    // Periodic in the time of day.
    const glm::dvec3 a = sunDirection(40.4, 152.0, 9.25), b = sunDirection(40.4, 152.0, 9.25 + 24.0);
    EXPECT_NEAR(glm::length(a - b), 0.0, 1e-12);
}

TEST(Sun, AirMassAndTransmittance) {
    // Kasten and Young's table: 1.000 at the zenith, 1.995 at 30 degrees, 38.09 at the horizon
    // (their formula reproduces the table to ~0.5 %).
    EXPECT_NEAR(relativeAirMass(M_PI / 2), 1.0, 1e-3);
    EXPECT_NEAR(relativeAirMass(30.0 * kDegrees), 1.995, 0.01);
    EXPECT_NEAR(relativeAirMass(0.0), 38.09, 0.2);
    const glm::dvec3 high = sunTransmittance(60.0 * kDegrees, 3.0);
    const glm::dvec3 low = sunTransmittance(5.0 * kDegrees, 3.0);
    for (int c = 0; c < 3; ++c) {
        EXPECT_GT(high[c], low[c]);
        EXPECT_LE(high[c], 1.0);
        EXPECT_GT(low[c], 0.0);
    }
    // Blue is scattered out of the beam more than red: the low sun reddens.
    EXPECT_GT(low.r / low.b, 2.0 * high.r / high.b);
    // Haze dims the beam.
    EXPECT_LT(luminance(sunTransmittance(60.0 * kDegrees, 8.0)), luminance(high));
}

TEST(Sun, DiskSetsContinuously) {
    // Tolerance: closed form of the circular segment; 1e-12 is rounding.
    EXPECT_NEAR(sunVisibleFraction(0.0), 0.5, 1e-12);
    EXPECT_EQ(sunVisibleFraction(kSunAngularRadius * 1.01), 1.0);
    EXPECT_EQ(sunVisibleFraction(-kSunAngularRadius * 1.01), 0.0);
    double previous = 0.0;
    for (int k = -100; k <= 100; ++k) {
        const double fraction = sunVisibleFraction(kSunAngularRadius * 0.01 * k);
        EXPECT_GE(fraction, previous);        // monotone
        EXPECT_LE(fraction - previous, 0.02); // steepest at the middle: 2 / pi per radius, 1 % steps
        previous = fraction;
    }
    const glm::dvec3 below = glm::normalize(glm::dvec3(1.0, -0.01, 0.0));
    EXPECT_EQ(sunRadiance(below, 152.0, 3.0), glm::dvec3(0.0));
}

TEST(Sun, NoonSunIlluminanceIsPhysical) {
    // A clear June noon at 40 degrees north: direct normal illuminance of the order of 90-110 klx
    // (e.g. Darula and Kittler's measurements); in sky units 9-11. The tolerance brackets clear
    // skies, the test pins the documented units.
    const glm::dvec3 sun = sunDirection(40.4, 172.0, 12.0);
    const double irradiance = luminance(sunRadiance(sun, 172.0, 3.0)) * sunSolidAngle();
    EXPECT_GT(irradiance, 8.0);
    EXPECT_LT(irradiance, 12.0);
    // Outside the atmosphere the sun is white-ish (5778 K): no channel below 80 % of another.
    const glm::dvec3 zenithSun = sunRadiance({0, 1, 0}, 172.0, 1.7) / sunTransmittance(M_PI / 2, 1.7);
    EXPECT_GT(std::min({zenithSun.r, zenithSun.g, zenithSun.b}) / std::max({zenithSun.r, zenithSun.g, zenithSun.b}),
              0.8);
}

} // namespace
} // namespace meadow::sky
