// Sun position and direct sunlight through the atmosphere; sources cited in sky/sun.h.
#include "sky/sun.h"

#include <algorithm>
#include <cmath>

namespace meadow::sky {
namespace {

constexpr double kDegrees = M_PI / 180.0;

// Luminous solar constant (lx) outside the atmosphere at the mean Earth–Sun distance: Darula,
// Kittler and Gueymard, "Reference luminous solar constant and solar luminance for illuminance
// calculations", Solar Energy 79, 2005.
constexpr double kLuminousSolarConstant = 133.8e3;

// Effective temperature of the solar photosphere (K), for the colour of the sun outside the
// atmosphere.
constexpr double kSunTemperature = 5778.0;

// Dominant wavelengths (micrometres) of the Rec.709 red, green and blue primaries: where each
// channel's extinction is evaluated.
constexpr double kChannelWavelength[3] = {0.610, 0.550, 0.465};

// Chromaticity of a black body of temperature t (4000-25000 K): the cubic spline fit of the
// Planckian locus by Kim et al., "Design of advanced color temperature control system for HDTV
// applications", J. Korean Physical Society 41(6), 2002.
glm::dvec2 planckianChromaticity(double t) {
    const double x = -3.0258469e9 / (t * t * t) + 2.1070379e6 / (t * t) + 0.2226347e3 / t + 0.240390;
    const double y = 3.0817580 * x * x * x - 5.8733867 * x * x + 3.75112997 * x - 0.37001483;
    return {x, y};
}

} // namespace

glm::dvec3 xyYToRec709(double x, double y, double luminanceY) {
    if (y <= 0.0)
        return glm::dvec3(0.0);
    const double bigX = x / y * luminanceY, bigZ = (1.0 - x - y) / y * luminanceY;
    // XYZ -> linear Rec.709 (sRGB primaries, D65 white), IEC 61966-2-1.
    return {3.2404542 * bigX - 1.5371385 * luminanceY - 0.4985314 * bigZ,
            -0.9692660 * bigX + 1.8760108 * luminanceY + 0.0415560 * bigZ,
            0.0556434 * bigX - 0.2040259 * luminanceY + 1.0572252 * bigZ};
}

double solarDeclination(double dayOfYear) {
    const double g = 2.0 * M_PI * (dayOfYear - 1.0) / 365.0; // Spencer's day angle
    return 0.006918 - 0.399912 * std::cos(g) + 0.070257 * std::sin(g) - 0.006758 * std::cos(2.0 * g) +
           0.000907 * std::sin(2.0 * g) - 0.002697 * std::cos(3.0 * g) + 0.00148 * std::sin(3.0 * g);
}

glm::dvec3 sunDirection(double latitudeDegrees, double dayOfYear, double solarHours) {
    const double phi = latitudeDegrees * kDegrees, delta = solarDeclination(dayOfYear);
    const double hourAngle = (solarHours - 12.0) * 15.0 * kDegrees;
    const double up = std::sin(phi) * std::sin(delta) + std::cos(phi) * std::cos(delta) * std::cos(hourAngle);
    const double east = -std::cos(delta) * std::sin(hourAngle);
    const double north = std::cos(phi) * std::sin(delta) - std::sin(phi) * std::cos(delta) * std::cos(hourAngle);
    // The three components are an orthonormal change of frame of a unit vector; normalising only
    // removes rounding.
    return glm::normalize(glm::dvec3(east, up, north));
}

double relativeAirMass(double elevationRadians) {
    const double elevationDegrees = std::max(elevationRadians, 0.0) / kDegrees;
    const double zenithDegrees = 90.0 - elevationDegrees;
    return 1.0 / (std::cos(zenithDegrees * kDegrees) + 0.50572 * std::pow(96.07995 - zenithDegrees, -1.6364));
}

glm::dvec3 sunTransmittance(double elevationRadians, double turbidity) {
    const double airMass = relativeAirMass(elevationRadians);
    const double beta = 0.04608 * turbidity - 0.04586; // Angstrom's turbidity coefficient
    glm::dvec3 transmittance;
    for (int c = 0; c < 3; ++c) {
        const double lambda = kChannelWavelength[c];
        const double rayleigh = 0.008735 * std::pow(lambda, -4.08);
        const double aerosol = beta * std::pow(lambda, -1.3);
        transmittance[c] = std::exp(-airMass * (rayleigh + aerosol));
    }
    return transmittance;
}

double sunVisibleFraction(double elevationRadians) {
    // The disk is a circle of radius r centred h r above the horizon line; the part above the
    // line has area r^2 (pi / 2 + asin h + h sqrt(1 - h^2)).
    const double h = glm::clamp(elevationRadians / kSunAngularRadius, -1.0, 1.0);
    return (0.5 * M_PI + std::asin(h) + h * std::sqrt(1.0 - h * h)) / M_PI;
}

glm::dvec3 sunRadiance(const glm::dvec3& sunDirection, double dayOfYear, double turbidity) {
    const double e = elevation(sunDirection);
    const double visible = sunVisibleFraction(e);
    if (visible <= 0.0)
        return glm::dvec3(0.0);
    const double eccentricity = 1.0 + 0.033 * std::cos(2.0 * M_PI * dayOfYear / 365.0);
    const double luminanceOutside = kLuminousSolarConstant * eccentricity / sunSolidAngle(); // cd/m^2
    const glm::dvec2 xy = planckianChromaticity(kSunTemperature);
    const glm::dvec3 colour = xyYToRec709(xy.x, xy.y, 1.0); // unit luminance, all components > 0
    return colour * (luminanceOutside * kUnitsPerCandela * visible) * sunTransmittance(e, turbidity);
}

} // namespace meadow::sky
