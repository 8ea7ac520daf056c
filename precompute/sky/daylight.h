// The analytic sky for one sun position (docs/ARCHITECTURE.md, Sky): Preetham, Shirley and Smits,
// "A Practical Analytic Model for Daylight" (SIGGRAPH 1999), extended below the horizon and into
// the night. Axes and units as in sky/sun.h (y up, +x east, +z north; 1 = 10^4 cd/m^2).
//
// The whole sphere of directions has a defined, finite, non-negative radiance at every sun
// position:
//   - Upper hemisphere, sun up: Preetham's sky. Luminance Y from the zenith luminance (their eq.
//     A.2, in kcd/m^2) times the Perez distribution F(theta, gamma) / F(0, theta_sun), and the
//     chromaticity x, y likewise from their zenith polynomials and Perez coefficients, for the
//     turbidity T. xyY goes to linear Rec.709; the few out-of-gamut components are clamped to 0.
//     The sun's own disk is not part of it (sky/sun.h gives the disk's radiance separately).
//   - Upper hemisphere, sun below the horizon: Preetham's model is fitted only for a visible sun.
//     Twilight keeps the sky of a sun on the horizon (same azimuth, so the glow stays on the
//     sunset side) and dims it by 10^(-0.4 d), d the sun's depression in degrees: observed
//     twilight skies fall by two to three orders of magnitude over the 6 degrees of civil
//     twilight (Rozenberg, "Twilight: A Study in Atmospheric Optics", 1966). At d = 0 this is
//     exactly the daytime sky, so radiance is continuous through sunrise and sunset.
//   - A night floor is added everywhere above the horizon at every hour: a uniform, slightly
//     blue sky of luminance `nightLuminance` cd/m^2, a stand-in for moonlight and airglow (not a
//     physical model) so that night scenes are dim rather than black. It is negligible by day.
//   - Lower hemisphere: the ground, a uniform Lambertian plane of albedo `groundAlbedo` lit by
//     this sky and sun: radiance albedo E_h / pi, E_h the irradiance on a horizontal surface.
//     It is what a PRT vertex sees below the horizon where the bake itself has no ground (the
//     transfer bake's own ground grid, where present, occludes it as real geometry would).
#pragma once

#include <glm/glm.hpp>

namespace meadow::sky {

struct DaylightParams {
    double turbidity = 3.0;      // Preetham's T: 2 = very clear, 3 = clear, 6 = hazy; fitted for 1.7-10
    double groundAlbedo = 0.2;   // grass and soil
    double nightLuminance = 0.1; // cd/m^2, the night floor (a moonlit sky is ~0.01-0.1)
};

// Everything that depends only on the sun position, precomputed once per sky.
struct DaylightSky {
    glm::dvec3 sunDirection{0.0, 1.0, 0.0};      // the true sun, possibly below the horizon
    glm::dvec3 modelSunDirection{0.0, 1.0, 0.0}; // the sun Preetham's formulas see (raised to the horizon)
    double twilight = 1.0;                       // 1 by day, 10^(-0.4 depression) at night
    double zenith[3] = {};                       // Preetham zenith Y (kcd/m^2), x, y
    double perez[3][5] = {};                     // Perez A..E for Y, x, y
    double perezAtZenith[3] = {};                // F(0, theta_sun) for Y, x, y
    glm::dvec3 night{0.0};                       // night floor radiance
    glm::dvec3 sunRadiance{0.0};                 // the disk (sky/sun.h)
    glm::dvec3 horizontalIrradiance{0.0};        // sky plus sun on a horizontal surface
    glm::dvec3 ground{0.0};                      // radiance of every below-horizon direction
};

// Builds the sky for a unit sun direction on a day of the year. Preconditions (asserted; user
// input is checked by validateSkyParams in sky/sky_day.h): |sunDirection| = 1, turbidity within
// [1.7, 10], albedo within [0, 1], nightLuminance >= 0.
DaylightSky makeDaylightSky(const glm::dvec3& sunDirection, double dayOfYear, const DaylightParams& params);

// Radiance arriving from the unit direction `dir` (i.e. seen looking along dir): sky above the
// horizon (dir.y > 0), ground at and below it. Excludes the sun's disk. Finite and >= 0.
glm::dvec3 skyRadiance(const DaylightSky& sky, const glm::dvec3& dir);

} // namespace meadow::sky
