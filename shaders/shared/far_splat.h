// The far field's per-sample arithmetic (issue 18; docs/ARCHITECTURE.md, The far field), one
// function body compiled as C++ (the CPU reference, tests) and as GLSL (the splat and resolve
// passes), like lod_select.h.
//
// Far instances are drawn as surface samples (precompute/library/far_samples.h): each sample is
// moved and lit like the mesh vertex it follows, projected to one pixel (or a small square), and
// merged into a visibility buffer of 64-bit words with atomicMin (Schütz, Kerbl and Wimmer 2021).
// A word is (depth key << 32) | colour:
//   - the depth key is the bit pattern of the reversed-Z depth, complemented: non-negative floats
//     order like their bits, so the nearest sample (largest depth) has the smallest key;
//   - the colour is RGB9E5 (the shared-exponent format of VK_FORMAT_E5B9G9R9_UFLOAT_PACK32), so
//     HDR radiance survives to the tone mapper;
//   - equal depths resolve to the smaller colour word: whatever order the threads run in, the
//     same samples give the same buffer (determinism).
// An empty pixel holds kFarEmpty in both halves.
//
// How many samples an instance draws follows its projected size (stochastic pruning, Cook,
// Halstead, Planck and Ryu 2007): a run of its clump's shuffled samples from a start of its own
// (farSampleStart), each then standing for a larger share of the surface.
//
// Every operation here is exact or correctly rounded (bit patterns, ldexp, floor, products of two
// values, no fused multiply-add where it is marked precise), so C++ and GLSL agree bit for bit.
#ifndef MEADOW_FAR_SPLAT_H
#define MEADOW_FAR_SPLAT_H

#include "gpu_types.h"

#ifdef __cplusplus
#include <cmath>
#include <cstdint>
#include <cstring>
namespace meadow::gpu {
using uint = std::uint32_t;
#define MEADOW_FAR_CONST inline constexpr uint
#define MEADOW_FAR_FCONST inline constexpr float
#define MEADOW_FAR_FN inline
#define MEADOW_FAR_PRECISE
struct FarVec3 {
    float x, y, z;
};
inline uint farFloatBits(float f) {
    uint u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}
inline float farUintBitsToFloat(uint u) {
    float f;
    std::memcpy(&f, &u, sizeof f);
    return f;
}
inline float farMax(float a, float b) {
    return a > b ? a : b;
}
inline float farMin(float a, float b) {
    return a < b ? a : b;
}
inline float farFloor(float x) {
    return std::floor(x);
}
inline float farCeil(float x) {
    return std::ceil(x);
}
inline float farSqrt(float x) {
    return std::sqrt(x);
}
inline float farAtan2(float y, float x) {
    return std::atan2(y, x);
}
inline float farAsin(float x) {
    return std::asin(x);
}
inline float farLog2(float x) {
    return std::log2(x);
}
inline float farMix(float a, float b, float t) {
    return a * (1.0f - t) + b * t; // glm::mix's
}
inline int farIndex(uint i) {
    return int(i); // glm::vec4's components are indexed by int
}
#else
#define MEADOW_FAR_CONST const uint
#define MEADOW_FAR_FCONST const float
#define MEADOW_FAR_FN
#define MEADOW_FAR_PRECISE precise
#define FarVec3 vec3
#define farFloatBits(f) floatBitsToUint(f)
#define farUintBitsToFloat(u) uintBitsToFloat(u)
#define farMax(a, b) max(a, b)
#define farMin(a, b) min(a, b)
#define farFloor(x) floor(x)
#define farCeil(x) ceil(x)
#define farSqrt(x) sqrt(x)
#define farAtan2(y, x) atan(y, x)
#define farAsin(x) asin(x)
#define farLog2(x) log2(x)
#define farMix(a, b, t) mix(a, b, t)
#define farIndex(i) (i)
#endif

MEADOW_FAR_CONST kFarEmpty = 0xffffffffu; // both halves of an empty visibility word

// RGB9E5: three 9-bit mantissas and a 5-bit exponent with bias 15 (the Vulkan specification's
// shared-exponent conversion, "Shared Exponent to RGB" and back).
MEADOW_FAR_CONST kRgb9e5MantissaBits = 9u;
MEADOW_FAR_CONST kRgb9e5Bias = 15u;
MEADOW_FAR_FCONST kRgb9e5Max = 65408.0f; // (2^9 - 1) / 2^9 * 2^(31 - 15)

// The key of a reversed-Z depth in [0, 1] (1 at the near plane): nearer is smaller.
MEADOW_FAR_FN uint farDepthKey(float depth) {
    return ~farFloatBits(farMax(depth, 0.0f));
}

// The reversed-Z depth a key was made from (farDepthKey's inverse; 0 for kFarEmpty).
MEADOW_FAR_FN float farKeyDepth(uint depthKey) {
    return farUintBitsToFloat(~depthKey);
}

// Whether a visibility word's sample shows over the meshes: its depth (farKeyDepth) nearer than
// the meshes' surface anywhere in its pixel, `meshLimit` (farMeshDepthLimit). A sample lies
// anywhere in its pixel, but the depth the mesh pass leaves is its surface's at the pixel's centre.
// Tested there, a sample near a clump's base lost every pixel whose centre sees the ground just in
// front of it, while LOD 0, whose fragments lie on the centre's ray, loses none: with the ground
// seen at 23 degrees, its depth changes by 2.4 pixels' widths from one pixel to the next, and the
// far field covered 1.5-2 % fewer plant pixels than its reference in the high views
// (docs/BENCHMARKS.md). The resolve pass tests the word that won, not each sample as it lands: the
// winner is the nearest of the pixel's samples, so if it is behind the meshes every other one is
// too, and the picture is the same. An empty word (depth 0, infinitely far) never shows.
MEADOW_FAR_FN bool farWordShows(uint depthKey, float meshLimit) {
    return farKeyDepth(depthKey) > meshLimit;
}

// The farthest the meshes' surface at a pixel reaches within it, as a reversed-Z depth: `centre`,
// the depth at the pixel's centre, less half its change per pixel in x and in y. A plane's reversed
// depth is affine on the screen, so where the neighbours (left, right; up, down) continue the
// centre's surface, the central difference is that change. Where they do not (a silhouette, an
// edge between two surfaces, a blade a pixel wide before the ground far behind), the second
// difference shows it and that axis adds nothing: the centre's depth is all the test has. A level
// ground seen from 23 degrees reaches about 1.2 pixels' widths behind its centre's depth; a
// surface facing the eye, none.
MEADOW_FAR_FN float farMeshDepthReach(float before, float centre, float after) {
    MEADOW_FAR_PRECISE float slope = 0.5f * (after - before);
    MEADOW_FAR_PRECISE float bend = (after - centre) - (centre - before);
    float step = farMin(farMax(after - centre, centre - after), farMax(centre - before, before - centre));
    return farMax(bend, -bend) <= 0.25f * step ? 0.5f * farMax(slope, -slope) : 0.0f;
}
MEADOW_FAR_FN float farMeshDepthLimit(float centre, float left, float right, float up, float down) {
    MEADOW_FAR_PRECISE float limit =
        centre - (farMeshDepthReach(left, centre, right) + farMeshDepthReach(up, centre, down));
    return limit;
}

// 2^e for e in [-126, 127], from its bits: the same value as ldexp(1, e), and x * farPow2(e) the
// same as ldexp(x, e) where the result is a normal float. llvmpipe lowers ldexp to a dozen integer
// operations per call (Mesa's lower_ldexp), and RGB9E5 is packed per far sample and near-raster
// pixel and unpacked six times per near-raster triangle: one power of two per word instead of one
// ldexp per channel (docs/BENCHMARKS.md).
MEADOW_FAR_FN float farPow2(int e) {
    return farUintBitsToFloat(uint(e + 127) << 23u);
}

// Non-negative finite radiance to RGB9E5; values above kRgb9e5Max saturate, negative ones are 0.
// The scaled channels are normal floats or round to 0 (shift lies in [-24, 8]), so each product by
// the power of two is exact.
MEADOW_FAR_FN uint packRgb9e5(float r, float g, float b) {
    float rc = farMin(farMax(r, 0.0f), kRgb9e5Max);
    float gc = farMin(farMax(g, 0.0f), kRgb9e5Max);
    float bc = farMin(farMax(b, 0.0f), kRgb9e5Max);
    float maxc = farMax(rc, farMax(gc, bc));
    // floor(log2(maxc)) from the float's exponent field, exact; below 2^-16 the format's least
    // exponent takes over (denormals and zero included).
    int e = int((farFloatBits(maxc) >> 23u) & 0xffu) - 127;
    int exponent = (e < -16 ? -16 : e) + 1 + int(kRgb9e5Bias);
    int shift = exponent - int(kRgb9e5Bias) - int(kRgb9e5MantissaBits);
    float scale = farPow2(-shift);
    float maxs = farFloor(maxc * scale + 0.5f);
    if (maxs >= 512.0f) {
        exponent += 1;
        scale *= 0.5f;
    }
    uint rs = uint(farFloor(rc * scale + 0.5f));
    uint gs = uint(farFloor(gc * scale + 0.5f));
    uint bs = uint(farFloor(bc * scale + 0.5f));
    return rs | (gs << 9u) | (bs << 18u) | (uint(exponent) << 27u);
}

MEADOW_FAR_FN FarVec3 unpackRgb9e5(uint v) {
    float scale = farPow2(int(v >> 27u) - int(kRgb9e5Bias) - int(kRgb9e5MantissaBits));
    FarVec3 c;
    c.x = float(v & 0x1ffu) * scale;
    c.y = float((v >> 9u) & 0x1ffu) * scale;
    c.z = float((v >> 18u) & 0x1ffu) * scale;
    return c;
}

// The share of `density` a far instance draws, from `surface`, its surface in pixels (the square of
// the size the coverage gains' table is indexed by): all of it up to kFarTaperFrom px^2 (8 px of
// size), kFarTaperShare of it from kFarTaperTo (16 px), linear in between. Most of a frame's
// samples belong to the larger far instances (in the default view 59 % to those above 12 px), whose
// samples each cover less than a pixel even at the lower density; the smallest keep the full
// density, as with fewer samples a clump a pixel or two across covered too much
// (docs/BENCHMARKS.md). Products and sums only, so that C++ and GLSL count alike.
MEADOW_FAR_FCONST kFarTaperFrom = 64.0f;
MEADOW_FAR_FCONST kFarTaperTo = 256.0f;
MEADOW_FAR_FCONST kFarTaperShare = 0.6f;
MEADOW_FAR_FN float farDensityShare(float surface) {
    MEADOW_FAR_PRECISE float t = (surface - kFarTaperFrom) * (1.0f / (kFarTaperTo - kFarTaperFrom));
    MEADOW_FAR_PRECISE float share = 1.0f - (1.0f - kFarTaperShare) * farMin(farMax(t, 0.0f), 1.0f);
    return share;
}

// How many of a clump's `available` shuffled samples a far instance draws: `density` samples per
// pixel of its surface's projected area, tapered for larger instances (farDensityShare). `area` is
// the surface (m^2, one side) and `pixelsPerMetre` farPixelsPerMetre at its sphere's centre; a
// sheet seen at a random angle shows half its area on average. At least 1, at most `available`.
MEADOW_FAR_FN uint farSampleCount(float area, float pixelsPerMetre, float density, uint available) {
    MEADOW_FAR_PRECISE float surface = area * (pixelsPerMetre * pixelsPerMetre);
    MEADOW_FAR_PRECISE float n = farCeil(density * farDensityShare(surface) * (0.5f * surface));
    return uint(farMax(1.0f, farMin(n, float(available))));
}

// The pixels per metre at a point `depth` (clip w) in front of the eye and `eyeDistance` from it:
// the square root of the pixels that a small patch of one square metre, facing the eye, covers
// there; `pixelsPerUnit` is GpuFrame::lodScreen.x, the pixels per unit of length at unit depth. On
// the optical axis that is pixelsPerUnit / depth. Off the axis the patch covers more: its solid
// angle falls as 1 / eyeDistance^2, but the image plane, met obliquely, takes 1 / cos^3 more pixels
// per steradian at an angle off the axis whose cosine is depth / eyeDistance. So a square metre
// covers pixelsPerUnit^2 eyeDistance / depth^3 pixels: at the corners of a 16:9 view 50 degrees
// high, 1.38 times what pixelsPerUnit / depth gives. The coverage gains are measured in
// orthographic views, where the two agree. Taken as pixelsPerUnit / depth (or / eyeDistance), the
// splats off the axis came out as many times too small as LOD 0 is drawn larger there, and the far
// field covered 5-10 % less than its reference (docs/BENCHMARKS.md, "The far field's footprints
// off the optical axis").
MEADOW_FAR_FN float farPixelsPerMetre(float pixelsPerUnit, float depth, float eyeDistance) {
    MEADOW_FAR_PRECISE float ppm = pixelsPerUnit / depth * farSqrt(eyeDistance / depth);
    return ppm;
}
// A sample's share of the screen: its share of the surface, `areaPerSample` (m^2), seen at
// `pixelsPerMetre` (farPixelsPerMetre) and turned by `cosine` (its normal against the direction to
// the eye), in pixels.
// Below one pixel the sample covers its pixel with that probability (stochastic coverage: a thin
// leaf seen edge-on lights few pixels, as it covers little of them); above, a square of about that
// area: `farSplatSide`.
MEADOW_FAR_FN float farSampleFootprint(float areaPerSample, float pixelsPerMetre, float cosine) {
    MEADOW_FAR_PRECISE float a = areaPerSample * (pixelsPerMetre * pixelsPerMetre);
    MEADOW_FAR_PRECISE float f = a * farMin(farMax(cosine, -cosine), 1.0f);
    return f;
}

// The side, in whole pixels, of the square a sample of `footprint` pixels covers (1 below 2.25
// pixels), at most kFarMaxSplatSide.
MEADOW_FAR_CONST kFarMaxSplatSide = 4u;
MEADOW_FAR_FN uint farSplatSide(float footprint) {
    float side = farFloor(farSqrt(farMax(footprint, 1.0f)) + 0.5f);
    return uint(farMin(side, float(kFarMaxSplatSide)));
}

// The first pixel (column or row) of the square of `side` pixels a sample at continuous pixel
// coordinate `pixel` covers: the square whose centre is nearest the sample. The pixel holding the
// sample, less (side - 1) / 2 in whole pixels, put a square of even side half a pixel past its
// sample on average, right and down: a clump's splats of 2 x 2 and 4 x 4 pixels sat off its
// surface's centre. Subtracting a half-integer from a pixel coordinate is exact, so C++ and GLSL
// agree.
MEADOW_FAR_FN int farSplatCorner(float pixel, uint side) {
    return int(farFloor(pixel - 0.5f * float(side - 1u)));
}

// Coverage gain (docs/ARCHITECTURE.md, The far field). Samples that each cover their pixel with
// the probability of their footprint, independently, cover a pixel that the surface fills with
// probability 1 - exp(-d) (d the footprints summed there), not 1: a solid leaf or rock looks
// thinner than it is, and more so the more of the view it fills. The precompute measures, per
// clump or rock, the gain on the footprints that makes the splats' expected coverage equal LOD 0's
// rasterised coverage (pipeline/far_samples.h), over a table of projected sizes and view
// elevations; the splat pass multiplies each sample's footprint by the instance's gain,
// interpolated in that table.
//   - size: sqrt(surface area) in pixels, kFarGainSizes bins at 2, 4, 8, ... px (log2 spaced);
//   - elevation: of the eye above the clump's horizon, kFarGainElevations bins at 0, 30, 60, 90
//     degrees.
MEADOW_FAR_CONST kFarGainSizes = 5u;
MEADOW_FAR_CONST kFarGainElevations = 4u;
MEADOW_FAR_FCONST kFarGainFirstSize = 2.0f; // px; bin i at kFarGainFirstSize * 2^i
// The density the gains are measured at and the run time uses by default (samples per pixel of
// projected surface, before farDensityShare's taper; farSampleCount). About two thirds of an iris
// clump's samples are in sight from some of a view's cell (the visibility bits below), so 5 leaves
// 3 for the surface that shows: enough that the gains stay near 1 and each sample covers about its
// own share of the pixels. At 2 the gains rose to about 2.3, squares of 2x2 pixels took over and
// the far field came out 6-11 % too bright at 1280x720 (docs/BENCHMARKS.md).
MEADOW_FAR_FCONST kFarDefaultDensity = 5.0f;

// The streams of the two random numbers that pick a sample's visibility view: index + stream (a
// clump has fewer than 2^24 samples).
MEADOW_FAR_CONST kFarAzimuthStream = 1u << 24u;
MEADOW_FAR_CONST kFarElevationStream = 2u << 24u;
// The random number in [0, 1) that decides whether sample `index` of far instance `instance`
// covers its pixel: a PCG hash (Jarzynski and Olano 2020) of both, 24 bits so the float is exact.
// The same every frame, so the far field does not shimmer.
MEADOW_FAR_FN float farSampleRandom(uint instance, uint index) {
    uint state = (instance * 1664525u + index * 2654435769u) * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return float(((word >> 22u) ^ word) >> 8u) * (1.0f / 16777216.0f);
}

// Which of its clump's `available` shuffled samples a far instance draws: `count` consecutive ones
// (cyclically) from a start of its own, the k-th at farSampleSlot(start, k, available). A prefix of
// one shuffle is an unbiased subset of the surface only on average over shuffles. A field has a
// few clumps and thousands of instances of each, so with every instance drawing its clump's prefix,
// the prefix's own chance mix showed over the whole field: at a few pixels per clump an instance
// draws about ten samples, and one or two petals more or less among them made the low view 4.7 %
// bluer than its reference (docs/BENCHMARKS.md). A start per instance averages the mix out over
// the field; an instance's own samples still grow continuously with its count.
MEADOW_FAR_CONST kFarStartStream = 3u << 24u;
MEADOW_FAR_FN uint farSampleStart(uint instance, uint available) {
    MEADOW_FAR_PRECISE float start = farFloor(farSampleRandom(instance, kFarStartStream) * float(available));
    return uint(farMin(start, float(available - 1u)));
}
MEADOW_FAR_FN uint farSampleSlot(uint start, uint k, uint available) {
    uint slot = start + k;
    return slot >= available ? slot - available : slot;
}

// Self-occlusion (docs/ARCHITECTURE.md, The far field). LOD 0 shows only the surface that nothing
// of its own clump hides; the splats, which cover their pixels with a probability, let every sample
// show through the ones in front of it. Where a clump is a few pixels across, its leaves and
// petals pile up in each pixel, so the far field showed the inner, lower, shadowed parts and the
// back sides of leaves about as often as the outer ones, and looked dark (docs/BENCHMARKS.md). Each
// sample therefore carries the directions from which it is seen from outside its clump, measured
// in the precompute by casting a ray towards each of the coverage gains' views (the 8 azimuths of
// the lower 3 elevations, and straight down) against LOD 0, its cut-out texels let through. A bit
// per view:
//   - azimuth a (0..7, at (a + 1/2) x 45 degrees about +y) and elevation e (0..2, at e x 30
//     degrees): bit e x 8 + a;
//   - straight down (90 degrees, the same from every azimuth): bit 24.
// The direction towards the eye of view (a, e) in clump space is (-sin A cos E, sin E, cos A cos E).
// A sample that is hidden from the view nearest the instance's eye direction is not drawn; which
// of the two views around that direction (in azimuth and in elevation) decides is chosen per sample
// at random, in proportion to the eye's nearness to each, so that a moving camera hands samples
// from one view to the next one by one instead of all at once.
MEADOW_FAR_CONST kFarVisibilityAzimuths = 8u;
MEADOW_FAR_CONST kFarVisibilityTopBit = 24u;
MEADOW_FAR_CONST kFarAllVisible = 0x1ffffffu; // bits 0..24

// The bit of view (azimuth, elevation), elevation in 0..kFarGainElevations - 1.
MEADOW_FAR_FN uint farVisibilityBit(uint azimuth, uint elevation) {
    return elevation + 1u >= kFarGainElevations ? kFarVisibilityTopBit : elevation * kFarVisibilityAzimuths + azimuth;
}

// The eye's elevation above an instance's base, in units of 30 degrees (the views' and the gain
// table's elevation bins), 0 to kFarGainElevations - 1: (dx, dy, dz) is the direction from the
// base towards the eye, any length (world or clump space: turning about y and mirroring in a
// vertical plane leave it the same). Once per instance; farVisibilityBitAt and farCoverageGain take
// it.
MEADOW_FAR_FN float farEyeElevation(float dx, float dy, float dz) {
    float length = farSqrt(dx * dx + dy * dy + dz * dz);
    float sinElevation = farMin(farMax(dy / farMax(length, 1e-20f), 0.0f), 1.0f);
    return farMin(farAsin(sinElevation) * (6.0f / 3.14159265f), float(kFarGainElevations - 1u));
}

// The eye's azimuth about an instance's base in clump space, in units of 45 degrees from view 0's
// centre, in [0, 8): (dx, dz) is the horizontal part of the direction from the base towards the eye
// with the instance's yaw and mirror undone. Azimuth A is where (-sin A, cos A) = (dx, dz) /
// length; view a sits at a + 1/2. Once per instance.
MEADOW_FAR_FN float farEyeAzimuth(float dx, float dz) {
    float a = farAtan2(-dx, dz) * (4.0f / 3.14159265f) - 0.5f;
    return a - 8.0f * farFloor(a * 0.125f);
}

// The bit that decides a sample's visibility, from the instance's eye azimuth and elevation
// (farEyeAzimuth, farEyeElevation) and the sample's two random numbers r1 and r2 in [0, 1)
// (farSampleRandom, kFarAzimuthStream and kFarElevationStream), which pick between the views
// either side of the eye in proportion to its nearness to each.
MEADOW_FAR_FN uint farVisibilityBitAt(float azimuth, float elevation, float r1, float r2) {
    float e0 = farFloor(elevation);
    uint e = uint(e0) + (r2 < elevation - e0 ? 1u : 0u);
    e = e < kFarGainElevations ? e : kFarGainElevations - 1u;
    float a0 = farFloor(azimuth);
    uint a = (uint(a0) + (r1 < azimuth - a0 ? 1u : 0u)) % kFarVisibilityAzimuths;
    return farVisibilityBit(a, e);
}

// An instance's size for its coverage gain: the square root of its surface (`area`, m²) in pixels
// at its base, `pixelsPerMetre` there (farPixelsPerMetre).
MEADOW_FAR_FN float farInstanceSize(float area, float pixelsPerMetre) {
    return farSqrt(area) * pixelsPerMetre;
}

// An instance's coverage gain: its clump's table (GpuClump::farGain) at its size (`size`, the
// square root of its surface in pixels at its base's depth) and the eye's elevation above it
// (farEyeElevation), bilinear; the sizes clamp to the table's ends.
MEADOW_FAR_FN float farCoverageGain(GpuClump clump, float size, float elevation) {
    float s = farMin(farMax(farLog2(farMax(size, 1e-6f) / kFarGainFirstSize), 0.0f), float(kFarGainSizes - 1u));
    uint s0 = uint(s), e0 = uint(elevation);
    e0 = e0 < kFarGainElevations ? e0 : kFarGainElevations - 1u;
    uint s1 = s0 + 1u < kFarGainSizes ? s0 + 1u : kFarGainSizes - 1u;
    uint e1 = e0 + 1u < kFarGainElevations ? e0 + 1u : kFarGainElevations - 1u;
    float fs = s - float(s0), fe = elevation - float(e0);
    float g0 = farMix(clump.farGain[s0][farIndex(e0)], clump.farGain[s0][farIndex(e1)], fe);
    float g1 = farMix(clump.farGain[s1][farIndex(e0)], clump.farGain[s1][farIndex(e1)], fe);
    return farMix(g0, g1, fs);
}

#ifdef __cplusplus
} // namespace meadow::gpu
#else
#undef FarVec3
#undef farFloatBits
#undef farUintBitsToFloat
#undef farMax
#undef farMin
#undef farFloor
#undef farCeil
#undef farSqrt
#undef farAtan2
#undef farAsin
#undef farLog2
#undef farMix
#undef farIndex
#endif
#undef MEADOW_FAR_CONST
#undef MEADOW_FAR_FCONST
#undef MEADOW_FAR_FN
#undef MEADOW_FAR_PRECISE
#endif
