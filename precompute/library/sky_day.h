// A day of sky as the library keeps it (docs/ARCHITECTURE.md, Sky): frames at evenly spaced times,
// each with its SH for lighting and a small lat-long image for the backdrop; at run time the two
// frames around the current time are blended, as Cove and James blend their sky photographs.
// sky/sky_day.h builds it from the analytic sky, sky/environment_map.h from a user's panoramas.
//
// Axes and units: y up, +x east, +z north; radiance in units of 10^4 cd/m^2, linear Rec.709.
// Images use light/latlong.h's layout (row 0 the zenith, the centre column south); SH use
// library/sh.h's basis.
#pragma once

#include "library/sh.h"

#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace meadow::sky {

// The sun's mean apparent angular radius (0.2666 degrees).
inline constexpr double kSunAngularRadius = 0.2666 * M_PI / 180.0;

struct SkyFrame {
    double hours = 0.0;              // local solar time of the frame
    glm::vec3 sunDirection{0, 1, 0}; // unit, towards the sun's centre; below the horizon at night
    glm::vec3 sunRadiance{0.0f};     // the disk's radiance, averaged over its solid angle (sky/sun.h)
    glm::vec3 sunIrradiance{0.0f};   // sunRadiance x sunSolidAngle(): on a surface facing the sun
    // coefficientCount(shOrder) RGB coefficients, sh[3 i + c], of all incident radiance: sky,
    // ground below the horizon, and the sun's disk as a delta of weight sunIrradiance.
    std::vector<float> sh;
    // imageWidth x imageHeight x 3 radiance, each pixel the solid-angle mean over its footprint:
    // sky and ground; the sun's disk (far smaller than a pixel) is left to the renderer, which
    // draws it from sunDirection and sunRadiance.
    std::vector<float> image;
};

struct SkyDay {
    int shOrder = sh::kDefaultOrder;
    uint32_t imageWidth = 0, imageHeight = 0;
    std::vector<SkyFrame> frames; // frames[i].hours = 24 i / frames.size()
};

// The two frames around a time of day and the weight of the second: value = (1 - weight) first +
// weight second, linear in time between the frames' hours, wrapping from the last frame to the
// first across midnight. `hours` may be any real number (taken modulo 24). A time within 1e-9 of
// a frame's hours returns exactly that frame with weight 0. Preconditions: day has >= 1 frame,
// hours is finite.
struct SkyBlend {
    uint32_t first = 0;
    uint32_t second = 0;
    double weight = 0.0;
};
SkyBlend skyBlendAt(const SkyDay& day, double hours);

// The blended SH coefficients (same layout as SkyFrame::sh).
std::vector<float> blendSh(const SkyDay& day, const SkyBlend& blend);

// Convenience: blendSh(day, skyBlendAt(day, hours)).
std::vector<float> shAt(const SkyDay& day, double hours);
} // namespace meadow::sky
