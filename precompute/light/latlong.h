// Latitude-longitude (equirectangular) images: the one mapping between pixels and world
// directions that the sky backdrop, HDR environment maps and their SH projection all use.
//
// World axes (docs/ARCHITECTURE.md; sh.h): y up, +x east, +z north. The image coordinates are
//   u = phi / (2 pi), phi the azimuth measured from +z (north) towards +x (east), in [0, 2 pi);
//   v = theta / pi,   theta the angle from +y (the zenith), in [0, pi].
// So row 0 is the zenith, the middle row boundary is the horizon, the last row the nadir;
// column 0 starts at north, a quarter across is east, the centre column looks south, three
// quarters across is west. Pixel (i, j) of a width x height image covers u in [i, i + 1) / width
// and v in [j, j + 1) / height; its centre is ((i + 0.5) / width, (j + 0.5) / height). Texels are
// stored row-major, RGB interleaved: rgb[3 (j width + i) + c].
#pragma once

#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

namespace meadow {

// Unit world direction of image coordinates (u, v).
inline glm::dvec3 latLongDirection(double u, double v) {
    const double phi = 2.0 * M_PI * u, theta = M_PI * v;
    const double sinTheta = std::sin(theta);
    return {sinTheta * std::sin(phi), std::cos(theta), sinTheta * std::cos(phi)};
}

// Image coordinates of a unit world direction: u in [0, 1), v in [0, 1].
inline glm::dvec2 latLongCoordinates(const glm::dvec3& dir) {
    double phi = std::atan2(dir.x, dir.z);
    if (phi < 0.0)
        phi += 2.0 * M_PI;
    double u = phi / (2.0 * M_PI);
    if (u >= 1.0) // phi just below 2 pi can round up to exactly 1
        u = 0.0;
    return {u, std::acos(glm::clamp(dir.y, -1.0, 1.0)) / M_PI};
}

// cos(theta) at the top edge of row j of an image `height` rows tall (j = height: the bottom).
inline double latLongRowTopCosine(uint32_t j, uint32_t height) {
    return std::cos(M_PI * double(j) / double(height));
}

// Exact solid angle (sr) of one pixel of row j: (2 pi / width) (cos theta_top - cos theta_bottom).
// The pixels of a whole image sum to 4 pi.
inline double latLongPixelSolidAngle(uint32_t j, uint32_t width, uint32_t height) {
    return 2.0 * M_PI / double(width) * (latLongRowTopCosine(j, height) - latLongRowTopCosine(j + 1, height));
}

} // namespace meadow
