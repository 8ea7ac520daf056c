// The sun: where it is for a latitude, date and local solar time, and how much of its light gets
// through the atmosphere (docs/ARCHITECTURE.md, Sky).
//
// Conventions shared by the whole sky module (and light/latlong.h, light/sh.h):
//   - World axes: +y up (zenith), +x east, +z north; so -z is south and -x west. A direction
//     "towards the sun" points from the ground to the sun's centre.
//   - Radiance unit: 1 = 10^4 cd/m^2 of luminance. Colours are linear Rec.709 (sRGB primaries,
//     D65 white), so an RGB radiance (R, G, B) has luminance 0.2126 R + 0.7152 G + 0.0722 B in
//     units of 10^4 cd/m^2. Irradiance then comes in units of 10^4 lx: on a clear June noon at
//     mid latitudes the sky gives a horizontal surface about 2-3 units and the sun about 9.
//     Physical units, scaled into the range of a float render target; the renderer applies
//     exposure.
//   - Time: local apparent solar time in hours, 12 = the sun on the meridian. Time zones and the
//     equation of time are the caller's business.
#pragma once

#include "library/sky_day.h" // kSunAngularRadius

#include <cmath>
#include <glm/glm.hpp>

namespace meadow::sky {

// Radiance units per cd/m^2 of luminance (see above).
inline constexpr double kUnitsPerCandela = 1e-4;

// Rec.709 luminance weights of linear RGB (ITU-R BT.709).
inline double luminance(const glm::dvec3& rgb) {
    return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b;
}

// CIE xyY chromaticity and luminance to linear Rec.709 RGB (D65), same units as Y. Out-of-gamut
// colours come back with negative components; callers clamp.
glm::dvec3 xyYToRec709(double x, double y, double luminanceY);

// Solar declination (radians) on a day of the year (1 = 1 January; fractions allowed), by
// Spencer's Fourier series ("Fourier series representation of the position of the sun", Search
// 2(5), 1971), accurate to about 0.0006 rad.
double solarDeclination(double dayOfYear);

// Unit vector towards the sun's centre (geometric, no refraction) for a latitude (degrees, north
// positive), a day of the year and a local solar time (hours; any real number, taken modulo 24).
// Standard spherical astronomy (e.g. Iqbal, "An Introduction to Solar Radiation", 1983, §1.5):
// with latitude phi, declination delta and hour angle h = 15 degrees (t - 12),
//   up    = sin(phi) sin(delta) + cos(phi) cos(delta) cos(h)   (the sine of the elevation)
//   east  = -cos(delta) sin(h)
//   north = cos(phi) sin(delta) - sin(phi) cos(delta) cos(h)
// so at solar noon the elevation is exactly 90 degrees - |phi - delta|.
glm::dvec3 sunDirection(double latitudeDegrees, double dayOfYear, double solarHours);

// Elevation of a unit direction above the horizon (radians).
inline double elevation(const glm::dvec3& direction) {
    return std::asin(glm::clamp(direction.y, -1.0, 1.0));
}

// The solid angle of the sun's disk (sr), of radius kSunAngularRadius (library/sky_day.h).
inline double sunSolidAngle() {
    return 2.0 * M_PI * (1.0 - std::cos(kSunAngularRadius));
}

// Relative optical air mass at an elevation (radians, clamped to >= 0): Kasten and Young,
// "Revised optical air mass tables and approximation formula", Applied Optics 28(22), 1989.
// 1 at the zenith, about 38 at the horizon.
double relativeAirMass(double elevationRadians);

// Transmittance of the direct beam per Rec.709 channel at an elevation (radians): Rayleigh
// scattering (optical depth 0.008735 lambda^-4.08, lambda in micrometres; Leckner 1978) and
// aerosol extinction by Angstrom's law beta lambda^-1.3 with beta = 0.04608 T - 0.04586 from the
// turbidity T (Preetham, Shirley and Smits 1999, appendix), at each channel's dominant
// wavelength (0.610, 0.550, 0.465 um). Ozone and water vapour absorption are left out; they tint
// but barely dim the beam. Elevations below 0 use the horizon's air mass.
glm::dvec3 sunTransmittance(double elevationRadians, double turbidity);

// The fraction of the sun's disk above the horizon when its centre is at `elevationRadians`:
// 1 above +radius, 0 below -radius, the circular segment's share in between.
double sunVisibleFraction(double elevationRadians);

// Radiance of the sun's disk (units above), averaged over the whole disk: the extraterrestrial
// sun (luminous solar constant 133.8 klx, Darula, Kittler and Gueymard 2005, with the orbit's
// eccentricity factor 1 + 0.033 cos(2 pi N / 365); colour of a 5778 K black body, Planckian
// locus of Kim et al. 2002) times sunTransmittance, times sunVisibleFraction, so a half-set
// sun reads half and a set sun zero. Multiply by sunSolidAngle() for the irradiance it gives a
// surface facing it.
glm::dvec3 sunRadiance(const glm::dvec3& sunDirection, double dayOfYear, double turbidity);

} // namespace meadow::sky
