// Preetham's daylight with twilight, a night floor and a Lambertian ground (sky/daylight.h).
#include "sky/daylight.h"

#include "light/sh.h"
#include "sky/sun.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

namespace meadow::sky {
namespace {

enum Channel { kLuminance = 0, kChromaX = 1, kChromaY = 2 };

// Preetham et al. 1999, appendix A.2: Perez coefficients A..E as linear functions of turbidity,
// rows for Y, x, y: {slope, intercept} per coefficient.
constexpr double kPerezTable[3][5][2] = {
    {{0.1787, -1.4630}, {-0.3554, 0.4275}, {-0.0227, 5.3251}, {0.1206, -2.5771}, {-0.0670, 0.3703}},
    {{-0.0193, -0.2592}, {-0.0665, 0.0008}, {-0.0004, 0.2125}, {-0.0641, -0.8989}, {-0.0033, 0.0452}},
    {{-0.0167, -0.2608}, {-0.0950, 0.0092}, {-0.0079, 0.2102}, {-0.0441, -1.6537}, {-0.0109, 0.0529}},
};

// Zenith chromaticity polynomials: x_z = [T^2 T 1] M [theta^3 theta^2 theta 1]^T (appendix A.2).
constexpr double kZenithX[3][4] = {
    {0.00166, -0.00375, 0.00209, 0.0}, {-0.02903, 0.06377, -0.03202, 0.00394}, {0.11693, -0.21196, 0.06052, 0.25886}};
constexpr double kZenithY[3][4] = {
    {0.00275, -0.00610, 0.00317, 0.0}, {-0.04214, 0.08970, -0.04153, 0.00516}, {0.15346, -0.26756, 0.06670, 0.26688}};

// Twilight: decades of luminance lost per degree of solar depression (sky/daylight.h).
constexpr double kTwilightDecadesPerDegree = 0.4;

// Night floor chromaticity: a little bluer than D65 (0.3127, 0.3290), as night scenes are
// conventionally shown.
constexpr double kNightX = 0.28, kNightY = 0.29;

// The Perez et al. 1993 all-weather luminance distribution.
double perez(const double (&c)[5], double cosTheta, double gamma, double cosGamma) {
    return (1.0 + c[0] * std::exp(c[1] / cosTheta)) *
           (1.0 + c[2] * std::exp(c[3] * gamma) + c[4] * cosGamma * cosGamma);
}

double zenithChromaticity(const double (&m)[3][4], double turbidity, double thetaSun) {
    const double t[3] = {turbidity * turbidity, turbidity, 1.0};
    const double s[4] = {thetaSun * thetaSun * thetaSun, thetaSun * thetaSun, thetaSun, 1.0};
    double sum = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j)
            sum += t[i] * m[i][j] * s[j];
    return sum;
}

// Sky radiance above the horizon (dir.y > 0), sun disk excluded.
glm::dvec3 upperSkyRadiance(const DaylightSky& sky, const glm::dvec3& dir) {
    // dir.y > 0 here; the floor only keeps B / cos(theta) finite for a denormal y.
    const double cosTheta = std::max(dir.y, 1e-9);
    const double cosGamma = glm::clamp(glm::dot(dir, sky.modelSunDirection), -1.0, 1.0);
    const double gamma = std::acos(cosGamma);
    double value[3];
    for (int k = 0; k < 3; ++k)
        value[k] = sky.zenith[k] * perez(sky.perez[k], cosTheta, gamma, cosGamma) / sky.perezAtZenith[k];
    // Y is in kcd/m^2: 10^3 cd/m^2 each.
    const glm::dvec3 rgb = xyYToRec709(value[kChromaX], value[kChromaY], value[kLuminance] * 1e3 * kUnitsPerCandela);
    return glm::max(rgb, glm::dvec3(0.0)) * sky.twilight + sky.night;
}

} // namespace

DaylightSky makeDaylightSky(const glm::dvec3& sunDirection, double dayOfYear, const DaylightParams& params) {
    assert(std::abs(glm::length(sunDirection) - 1.0) < 1e-9);
    assert(params.turbidity >= 1.7 && params.turbidity <= 10.0);
    assert(params.groundAlbedo >= 0.0 && params.groundAlbedo <= 1.0 && params.nightLuminance >= 0.0);
    DaylightSky sky;
    sky.sunDirection = sunDirection;

    // Preetham's formulas see the sun at the horizon when it is below it (twilight).
    const double sunElevation = elevation(sunDirection);
    if (sunElevation >= 0.0) {
        sky.modelSunDirection = sunDirection;
        sky.twilight = 1.0;
    } else {
        const glm::dvec3 horizontal(sunDirection.x, 0.0, sunDirection.z);
        const double length = glm::length(horizontal);
        // A sun exactly at the nadir has no azimuth; any horizon direction will do.
        sky.modelSunDirection = length > 1e-12 ? horizontal / length : glm::dvec3(0.0, 0.0, -1.0);
        const double depressionDegrees = -sunElevation * 180.0 / M_PI;
        sky.twilight = std::pow(10.0, -kTwilightDecadesPerDegree * depressionDegrees);
    }
    const double thetaSun = std::acos(glm::clamp(sky.modelSunDirection.y, 0.0, 1.0));
    const double turbidity = params.turbidity;

    // Zenith luminance (kcd/m^2), Preetham et al. appendix A.2.
    const double chi = (4.0 / 9.0 - turbidity / 120.0) * (M_PI - 2.0 * thetaSun);
    sky.zenith[kLuminance] = (4.0453 * turbidity - 4.9710) * std::tan(chi) - 0.2155 * turbidity + 2.4192;
    sky.zenith[kChromaX] = zenithChromaticity(kZenithX, turbidity, thetaSun);
    sky.zenith[kChromaY] = zenithChromaticity(kZenithY, turbidity, thetaSun);
    for (int k = 0; k < 3; ++k) {
        for (int i = 0; i < 5; ++i)
            sky.perez[k][i] = kPerezTable[k][i][0] * turbidity + kPerezTable[k][i][1];
        // F(0, theta_sun): the distribution at the zenith, where gamma = theta_sun.
        sky.perezAtZenith[k] = perez(sky.perez[k], 1.0, thetaSun, std::cos(thetaSun));
    }

    sky.night = xyYToRec709(kNightX, kNightY, params.nightLuminance * kUnitsPerCandela);
    sky.sunRadiance = sunRadiance(sunDirection, dayOfYear, turbidity);

    // Horizontal irradiance: the upper hemisphere by Gauss–Legendre in cos(theta) x uniform
    // azimuth (16 x 32 nodes; the sky is smooth, and the rule's error on the cosine-weighted
    // Perez distribution is far below a percent), plus the sun's beam.
    static const std::vector<sh::SphereSample> hemisphere = sh::quadratureSamples(16, 32, 0.0, 1.0);
    glm::dvec3 irradiance(0.0);
    for (const sh::SphereSample& s : hemisphere)
        irradiance += upperSkyRadiance(sky, s.direction) * (s.direction.y * s.weight);
    irradiance += sky.sunRadiance * (sunSolidAngle() * std::max(sunDirection.y, 0.0));
    sky.horizontalIrradiance = irradiance;
    sky.ground = irradiance * (params.groundAlbedo / M_PI);
    return sky;
}

glm::dvec3 skyRadiance(const DaylightSky& sky, const glm::dvec3& dir) {
    return dir.y > 0.0 ? upperSkyRadiance(sky, dir) : sky.ground;
}

} // namespace meadow::sky
