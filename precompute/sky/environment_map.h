// A user's HDR environment map, or a sequence of them, in place of the analytic sky
// (docs/ARCHITECTURE.md, Sky). Files are read with OpenImageIO (OpenEXR .exr, Radiance .hdr, or
// anything else it reads as floating point), must be latitude-longitude panoramas in
// light/latlong.h's layout (row 0 the zenith, column 0 north, the centre column south), and hold
// linear Rec.709 radiance in the sky's units (sky/sun.h: 1 = 10^4 cd/m^2); a map in other units is
// scaled by the renderer's exposure like any other. The whole sphere comes from the file, the lower
// hemisphere included: a panorama shot above real ground already holds its ground.
#pragma once

#include "sky/sky_day.h"

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace meadow::sky {

inline constexpr uint32_t kMaxEnvironmentMapWidth = 16384; // pixels; the height is half

struct EnvironmentMap {
    std::filesystem::path path;
    uint32_t width = 0, height = 0; // width = 2 height
    std::vector<float> rgb;         // width x height x 3, the file's first three channels
};

// Reads and checks a panorama. Throws meadow::Error "sky map PATH: PROBLEM" when the file is
// missing, unreadable or not an image; when it is not 2:1 ("W x H is not a 2:1 latitude-longitude
// panorama"); is not a regular file; is wider than kMaxEnvironmentMapWidth; has fewer than 3
// channels; or holds a non-finite or negative texel (the first one is named, with its position
// and channel).
EnvironmentMap loadEnvironmentMap(const std::filesystem::path& path);

// Resamples a lat-long RGB image to another size: each output pixel is the solid-angle-weighted
// mean of the source pixels its footprint overlaps (the source taken as piecewise constant,
// partial overlaps weighted exactly). Downsampling is a box filter that conserves the image's
// integral over the sphere; upsampling replicates. Preconditions: sizes >= 1, src.size() =
// 3 srcWidth srcHeight.
std::vector<float> resampleLatLong(uint32_t srcWidth, uint32_t srcHeight, std::span<const float> src, uint32_t dstWidth,
                                   uint32_t dstHeight);

// One sky frame from a panorama: its SH projected at full resolution (sh::projectLatLong), the
// backdrop image resampled to imageWidth x imageHeight. There is no analytic sun: sunRadiance and
// sunIrradiance are zero (the sun, if the map shows it, is in the SH and the image), and
// sunDirection is the map's dominant light direction, the luminance-weighted band-1 vector (Sloan,
// "Stupid Spherical Harmonics Tricks", 2008), or +y for a map without one (order 1, or no
// directional energy). Preconditions as for validateSkyParams.
SkyFrame environmentFrame(const EnvironmentMap& map, double hours, int shOrder, uint32_t imageWidth,
                          uint32_t imageHeight);

// A day from a sequence of panoramas spread evenly over 24 hours: file i becomes frame i at
// 24 i / files.size() hours (one file: the same sky all day), and skyBlendAt blends them like
// analytic frames. Uses params.imageWidth, imageHeight and shOrder; params.frames is ignored.
// Files are read in order, so the first bad file is the one reported. Throws meadow::Error for an
// empty list, bad params (validateSkyParams) or a bad file (loadEnvironmentMap).
SkyDay buildEnvironmentDay(std::span<const std::filesystem::path> files, const SkyParams& params);

} // namespace meadow::sky
