// The analytic sky of one sun position (precompute/sky/daylight.h): finite and non-negative
// everywhere at every hour, continuous through sunrise and sunset, and physically ordered.
#include "sky/daylight.h"
#include "sky/sun.h"

#include "light/latlong.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace meadow::sky {
namespace {

constexpr double kDay = 152.0, kLatitude = 40.4;

// A grid of directions over the whole sphere, with the exact horizon, zenith and nadir included.
std::vector<glm::dvec3> directionGrid() {
    std::vector<glm::dvec3> dirs;
    for (int j = 0; j <= 24; ++j)
        for (int i = 0; i < 24; ++i)
            dirs.push_back(latLongDirection(i / 24.0, j / 24.0));
    dirs.push_back({1.0, 0.0, 0.0});
    dirs.push_back(glm::normalize(glm::dvec3(1.0, 1e-300, 0.0))); // denormal-close to the horizon
    return dirs;
}

// Time of sunrise by bisection on the sun's elevation between midnight and noon.
double sunriseHours(double latitude, double day) {
    double lo = 0.0, hi = 12.0;
    for (int k = 0; k < 80; ++k) {
        const double mid = 0.5 * (lo + hi);
        (sunDirection(latitude, day, mid).y < 0.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

TEST(Daylight, FiniteAndNonNegativeEverywhereAllDay) {
    const std::vector<glm::dvec3> dirs = directionGrid();
    for (double latitude : {-89.0, -40.0, 0.0, kLatitude, 66.5, 89.0})
        for (double turbidity : {1.7, 3.0, 10.0})
            for (double hours = 0.0; hours < 24.0; hours += 0.25) {
                const glm::dvec3 sun = sunDirection(latitude, kDay, hours);
                const DaylightSky sky = makeDaylightSky(sun, kDay, {turbidity, 0.2, 0.1});
                for (const glm::dvec3& d : dirs) {
                    const glm::dvec3 l = skyRadiance(sky, d);
                    for (int c = 0; c < 3; ++c)
                        ASSERT_TRUE(std::isfinite(l[c]) && l[c] >= 0.0)
                            << "latitude " << latitude << " T " << turbidity << " hours " << hours << " dir " << d.x
                            << "," << d.y << "," << d.z << " channel " << c << " = " << l[c];
                }
                for (int c = 0; c < 3; ++c)
                    ASSERT_TRUE(std::isfinite(sky.sunRadiance[c]) && sky.sunRadiance[c] >= 0.0);
            }
}

TEST(Daylight, ZenithBrighterAtNoonThanAtSevenAndAtSevenThanAtNight) {
    const DaylightParams params;
    const auto zenith = [&](double hours) {
        return luminance(skyRadiance(makeDaylightSky(sunDirection(kLatitude, kDay, hours), kDay, params), {0, 1, 0}));
    };
    EXPECT_GT(zenith(12.0), 1.5 * zenith(7.0));
    EXPECT_GT(zenith(7.0), 100.0 * zenith(0.0));
}

TEST(Daylight, ContinuousThroughSunriseAndSunset) {
    const DaylightParams params;
    const std::vector<glm::dvec3> dirs = {{0, 1, 0},
                                          glm::normalize(glm::dvec3(1, 0.05, 0)),
                                          glm::normalize(glm::dvec3(-1, 0.05, 0)),
                                          glm::normalize(glm::dvec3(0.3, 0.7, -0.6)),
                                          {0, -1, 0}};
    const double rise = sunriseHours(kLatitude, kDay);
    for (double centre : {rise, 24.0 - rise}) { // sunset mirrors sunrise about noon
        // Over 20 minutes around the event in 1 s steps, no radiance moves by more than 1 % of
        // the largest value it takes in that window from one second to the next. The fastest
        // honest change is the twilight dimming, 0.4 decades per degree at 15 degrees per hour
        // (times sin of the sun path's slope): under 0.4 % per second.
        const int steps = 1200;
        std::vector<std::vector<double>> values(dirs.size());
        std::vector<double> sunValues;
        for (int k = 0; k <= steps; ++k) {
            const double hours = centre + (k - steps / 2) / 3600.0;
            const DaylightSky sky = makeDaylightSky(sunDirection(kLatitude, kDay, hours), kDay, params);
            for (size_t i = 0; i < dirs.size(); ++i)
                values[i].push_back(luminance(skyRadiance(sky, dirs[i])));
            sunValues.push_back(luminance(sky.sunRadiance));
        }
        for (size_t i = 0; i < dirs.size(); ++i) {
            const double largest = *std::max_element(values[i].begin(), values[i].end());
            for (int k = 1; k <= steps; ++k)
                EXPECT_LE(std::abs(values[i][size_t(k)] - values[i][size_t(k) - 1]), 0.01 * largest)
                    << "direction " << i << " step " << k;
        }
        // The disk takes ~3 minutes to clear the horizon: under 1 % of its radiance per second
        // at the steepest, and the transmittance grows far slower than that.
        const double largestSun = *std::max_element(sunValues.begin(), sunValues.end());
        EXPECT_GT(largestSun, 0.0);
        for (int k = 1; k <= steps; ++k)
            EXPECT_LE(std::abs(sunValues[size_t(k)] - sunValues[size_t(k) - 1]), 0.02 * largestSun) << k;
    }
    // Exactly at the horizon, the twilight branch and the daytime branch agree.
    const glm::dvec3 above = glm::normalize(glm::dvec3(0.8, 1e-12, -0.6));
    const glm::dvec3 below = glm::normalize(glm::dvec3(0.8, -1e-12, -0.6));
    const DaylightSky a = makeDaylightSky(above, kDay, params), b = makeDaylightSky(below, kDay, params);
    for (const glm::dvec3& d : dirs) {
        const glm::dvec3 la = skyRadiance(a, d), lb = skyRadiance(b, d);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(la[c], lb[c], 1e-9 * std::max(la[c], 1e-12)); // relative; the sun moved 2e-12 rad
    }
}

TEST(Daylight, BrightestNearTheSunDarkestAwayFromIt) {
    // Perez et al.: the circumsolar region is the brightest of a clear sky and the darkest part
    // lies about 90 degrees from the sun.
    const glm::dvec3 sun = glm::normalize(glm::dvec3(0.0, 0.5, -1.0)); // ~27 degrees up, south
    const DaylightSky sky = makeDaylightSky(sun, kDay, {});
    const glm::dvec3 nearSun = glm::normalize(glm::dvec3(0.15, 0.5, -1.0));
    const glm::dvec3 across = glm::normalize(glm::dvec3(1.0, 0.5, 0.0)); // same elevation, 90 deg round
    EXPECT_GT(luminance(skyRadiance(sky, nearSun)), 2.0 * luminance(skyRadiance(sky, across)));
    // Clear sky: blue overhead at noon.
    const glm::dvec3 zenith = skyRadiance(makeDaylightSky(sunDirection(kLatitude, kDay, 12.0), kDay, {}), {0, 1, 0});
    EXPECT_GT(zenith.b, zenith.r);
}

TEST(Daylight, GroundIsAlbedoTimesHorizontalIrradianceOverPi) {
    const DaylightParams params{3.0, 0.3, 0.1};
    const DaylightSky sky = makeDaylightSky(sunDirection(kLatitude, kDay, 10.0), kDay, params);
    const glm::dvec3 ground = skyRadiance(sky, glm::normalize(glm::dvec3(0.2, -0.5, 0.1)));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(ground[c], 0.3 * sky.horizontalIrradiance[c] / M_PI, 1e-12); // the definition
    EXPECT_EQ(skyRadiance(sky, {1, 0, 0}), sky.ground); // the horizon itself belongs to the ground
    // Units (sky/sun.h): a clear late-morning sky gives a horizontal surface 1-6 units of
    // diffuse light (10-60 klx) on top of the sun's beam.
    const glm::dvec3 beam = sky.sunRadiance * sunSolidAngle() * sky.sunDirection.y;
    const double diffuse = luminance(sky.horizontalIrradiance - beam);
    EXPECT_GT(diffuse, 1.0);
    EXPECT_LT(diffuse, 6.0);
}

TEST(Daylight, NightFloorAtMidnight) {
    const DaylightParams params{3.0, 0.2, 0.05};
    const glm::dvec3 midnightSun = sunDirection(kLatitude, kDay, 0.0); // ~27 degrees below
    const DaylightSky sky = makeDaylightSky(midnightSun, kDay, params);
    // 0.4 decades per degree over 27 degrees leave ~1e-11 of the twilight sky: the floor is all.
    const double zenith = luminance(skyRadiance(sky, {0, 1, 0}));
    EXPECT_NEAR(zenith, 0.05 * kUnitsPerCandela, 1e-3 * 0.05 * kUnitsPerCandela);
    const glm::dvec3 night = skyRadiance(sky, {0, 1, 0});
    EXPECT_GT(night.b, night.r); // tinted blue
    EXPECT_EQ(sky.sunRadiance, glm::dvec3(0.0));
    // Without a floor, night is (nearly) black but never negative.
    const DaylightSky dark = makeDaylightSky(midnightSun, kDay, {3.0, 0.2, 0.0});
    EXPECT_LT(luminance(skyRadiance(dark, {0, 1, 0})), 1e-10); // 1e-11 of a ~0.2-unit horizon sky
}

} // namespace
} // namespace meadow::sky
