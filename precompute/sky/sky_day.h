// A whole day of sky (docs/ARCHITECTURE.md, Sky): the analytic sky of sky/daylight.h sampled at
// evenly spaced times, each frame projected to SH for lighting and kept as a small lat-long image
// for the backdrop; at run time the two frames around the current time are blended, as Cove and
// James blend their sky photographs. sky/environment_map.h builds the same SkyDay from a user's HDR
// panoramas instead.
//
// Axes and units as in sky/sun.h: y up, +x east, +z north; radiance in units of 10^4 cd/m^2,
// linear Rec.709. Images use light/latlong.h's layout (row 0 the zenith, the centre column
// south); SH use light/sh.h's basis.
#pragma once

#include "library/sky_day.h"
#include "light/sh.h"
#include "sky/daylight.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace meadow::sky {

struct SkyParams {
    double latitudeDegrees = 40.4; // north positive; default Pittsburgh, where Cove and James worked
    double dayOfYear = 152.0;      // 1 = 1 January; default 1 June, when irises flower
    DaylightParams daylight;       // turbidity, ground albedo, night floor
    uint32_t frames = 288;         // evenly spaced over 24 h, frame i at 24 i / frames hours
    uint32_t imageWidth = 64;      // the backdrop image, a 2:1 lat-long panorama
    uint32_t imageHeight = 32;
    int shOrder = sh::kDefaultOrder;
};

// "full": 288 frames (every 5 minutes); "ci": 48 frames (every 30 minutes). Both 64 x 32, order 3.
// Throws meadow::Error for any other preset name.
SkyParams skyParamsForPreset(const std::string& preset);

// Throws meadow::Error ("sky: <what> is <value>; <what it must be>") for parameters outside
// their meaning: latitude beyond +-90, day outside 1-366, turbidity outside Preetham's fitted
// 1.7-10, albedo outside 0-1, a negative or non-finite night luminance, no frames, an image that
// is not 2:1 or is empty, an SH order outside 1..kMaxOrder.
void validateSkyParams(const SkyParams& params);

// One frame of the analytic sky at `hours` (local solar time). Deterministic. Preconditions:
// validateSkyParams(params) passes.
SkyFrame buildSkyFrame(const SkyParams& params, double hours);

// params.frames frames, built in parallel (TBB); each frame's arithmetic is independent of the
// thread count, so the result is the same bytes on every run. Throws meadow::Error from
// validateSkyParams.
SkyDay buildSkyDay(const SkyParams& params);

} // namespace meadow::sky
