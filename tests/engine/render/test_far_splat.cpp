// The far field's shared arithmetic (shaders/shared/far_splat.h): the visibility word's depth key
// and RGB9E5 colour, the sample count and splat size from projected size, and the far hand-over in
// the LOD coordinate (lod_select.h).
#include "far_splat.h"
#include "lod_select.h"
#include "render/camera.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

using namespace meadow::gpu;

namespace {

// The 64-bit word atomicMin keeps: depth key high, colour low.
uint64_t word(float depth, float r, float g, float b) {
    return (uint64_t(farDepthKey(depth)) << 32) | packRgb9e5(r, g, b);
}

} // namespace

TEST(FarSplat, NearerDepthsHaveSmallerKeys) {
    // Reversed Z: depth 1 at the near plane, 0 at infinity.
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 10000; ++i) {
        const float a = u(rng), b = u(rng);
        if (a > b) {
            EXPECT_LT(farDepthKey(a), farDepthKey(b)) << a << " " << b;
        } else if (a < b) {
            EXPECT_GT(farDepthKey(a), farDepthKey(b)) << a << " " << b;
        }
    }
    EXPECT_LT(farDepthKey(1.0f), farDepthKey(std::nextafter(1.0f, 0.0f)));
    EXPECT_LT(farDepthKey(1e-30f), farDepthKey(0.0f));
    EXPECT_EQ(farDepthKey(-0.5f), farDepthKey(0.0f)); // behind the far end: as far as can be
    for (float depth : {0.0f, 1e-30f, 0.25f, 0.75f, 1.0f})
        EXPECT_EQ(farKeyDepth(farDepthKey(depth)), depth); // the key gives its depth back
    EXPECT_EQ(farKeyDepth(kFarEmpty), 0.0f);
    EXPECT_LT(word(0.0f, 0.0f, 0.0f, 0.0f), (uint64_t(kFarEmpty) << 32) | kFarEmpty); // any sample beats empty
}

// The resolve's test: a word shows where its depth is nearer than the meshes' limit (strictly: the
// meshes win ties, as the splat pass's per-sample test did); an empty word never shows, not even
// over the sky (depth 0).
TEST(FarSplat, AWordShowsOnlyWhereItIsNearerThanTheMeshes) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 10000; ++i) {
        const float sample = u(rng), mesh = u(rng);
        EXPECT_EQ(farWordShows(farDepthKey(sample), mesh), sample > mesh) << sample << " " << mesh;
    }
    EXPECT_FALSE(farWordShows(farDepthKey(0.25f), 0.25f));
    EXPECT_TRUE(farWordShows(farDepthKey(std::nextafter(0.25f, 1.0f)), 0.25f));
    EXPECT_TRUE(farWordShows(farDepthKey(1e-30f), 0.0f));
    EXPECT_FALSE(farWordShows(kFarEmpty, 0.0f));
}

// The meshes' limit at a pixel: where the neighbours continue the centre's plane, the depth half a
// pixel's change further in x and in y; where either neighbour of an axis breaks off (a silhouette
// on one side, a blade a pixel wide on both), that axis adds nothing.
TEST(FarSplat, TheMeshesReachHalfAPixelsChangeBehindTheirCentreWhereTheyArePlanar) {
    // A plane's reversed depth is affine on the screen: 0.5 at the centre, 0.02 more per pixel in
    // x and 0.1 per pixel in y (the ground seen at a grazing angle).
    EXPECT_FLOAT_EQ(farMeshDepthLimit(0.5f, 0.48f, 0.52f, 0.4f, 0.6f), 0.5f - 0.01f - 0.05f);
    EXPECT_FLOAT_EQ(farMeshDepthLimit(0.5f, 0.52f, 0.48f, 0.6f, 0.4f), 0.5f - 0.01f - 0.05f); // either sign
    EXPECT_EQ(farMeshDepthLimit(0.5f, 0.5f, 0.5f, 0.5f, 0.5f), 0.5f); // facing the eye: the centre's depth
    // A step on one side in y (the ground's far edge against the sky, depth 0): y adds nothing.
    EXPECT_FLOAT_EQ(farMeshDepthLimit(0.5f, 0.48f, 0.52f, 0.0f, 0.6f), 0.5f - 0.01f);
    // A blade a pixel wide before ground far behind on both sides in x: x adds nothing.
    EXPECT_FLOAT_EQ(farMeshDepthLimit(0.5f, 0.05f, 0.06f, 0.4f, 0.6f), 0.5f - 0.05f);
    // Gently curved (a rolling terrain): still counted; sharply bent: not.
    EXPECT_FLOAT_EQ(farMeshDepthLimit(0.5f, 0.5f, 0.5f, 0.41f, 0.6f), 0.5f - 0.5f * 0.5f * (0.6f - 0.41f));
    EXPECT_EQ(farMeshDepthLimit(0.5f, 0.5f, 0.5f, 0.2f, 0.6f), 0.5f);
    // A sample just behind the centre's depth on a grazing ground shows; one behind the reach does not.
    const float limit = farMeshDepthLimit(0.5f, 0.5f, 0.5f, 0.4f, 0.6f);
    EXPECT_TRUE(farWordShows(farDepthKey(0.46f), limit));
    EXPECT_FALSE(farWordShows(farDepthKey(0.44f), limit));
}

TEST(FarSplat, TheMinimumIsTheSameInAnyOrder) {
    // Many samples on few pixels, equal depths included: the kept word per pixel does not depend
    // on the order the samples arrive in.
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> depthStep(0, 3), pixel(0, 7);
    std::uniform_real_distribution<float> colour(0.0f, 4.0f);
    struct Splat {
        int pixel;
        uint64_t word;
    };
    std::vector<Splat> splats;
    for (int i = 0; i < 400; ++i)
        splats.push_back({pixel(rng), word(0.25f * float(depthStep(rng)), colour(rng), colour(rng), colour(rng))});
    auto resolve = [](const std::vector<Splat>& in) {
        std::vector<uint64_t> buffer(8, ~uint64_t(0));
        for (const Splat& s : in)
            buffer[size_t(s.pixel)] = std::min(buffer[size_t(s.pixel)], s.word);
        return buffer;
    };
    const std::vector<uint64_t> first = resolve(splats);
    for (int shuffle = 0; shuffle < 20; ++shuffle) {
        std::shuffle(splats.begin(), splats.end(), rng);
        EXPECT_EQ(resolve(splats), first);
    }
    for (uint64_t w : first)
        EXPECT_EQ(uint32_t(w >> 32), farDepthKey(0.75f)); // the nearest depth used won each pixel
}

TEST(FarSplat, Rgb9e5MatchesTheVulkanConversion) {
    // Exact cases: representable values come back unchanged.
    for (float v : {0.0f, 1.0f, 0.5f, 3.0f, 511.0f, 65408.0f, 1.0f / 1024.0f}) {
        const FarVec3 c = unpackRgb9e5(packRgb9e5(v, v, v));
        EXPECT_EQ(c.x, v);
        EXPECT_EQ(c.y, v);
        EXPECT_EQ(c.z, v);
    }
    // The shared exponent follows the largest channel; the smaller ones lose bits below it.
    const uint one = packRgb9e5(1.0f, 0.0f, 0.0f);
    EXPECT_EQ(one >> 27, 16u); // 1.0 = 256 * 2^(16 - 15 - 9)
    EXPECT_EQ(one & 0x1ffu, 256u);
    // Saturation, negatives and zero.
    const FarVec3 big = unpackRgb9e5(packRgb9e5(1e9f, -1.0f, 0.0f));
    EXPECT_EQ(big.x, kRgb9e5Max);
    EXPECT_EQ(big.y, 0.0f);
    EXPECT_EQ(packRgb9e5(0.0f, 0.0f, 0.0f), 0u);
    // Rounding to nearest: the error of each channel is at most half a step of the shared
    // exponent, a step being 2^-9 of the power of two above the largest channel (twice that when
    // the largest channel rounds up to the next power of two).
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> logScale(-12.0f, 15.0f), u(0.0f, 1.0f);
    for (int i = 0; i < 20000; ++i) {
        const float scale = std::exp2(logScale(rng));
        const float rgb[3] = {u(rng) * scale, u(rng) * scale, u(rng) * scale};
        const uint packed = packRgb9e5(rgb[0], rgb[1], rgb[2]);
        const FarVec3 c = unpackRgb9e5(packed);
        const float maxc = std::max({rgb[0], rgb[1], rgb[2]});
        const int above = int(std::floor(std::log2(maxc))) + 1;
        const int exponent = int(packed >> 27) - 15;
        ASSERT_TRUE(exponent == above || (exponent == above + 1 && maxc >= std::ldexp(511.5f / 512.0f, above)))
            << maxc << " " << exponent;
        const float half = std::ldexp(0.5f, exponent - 9);
        EXPECT_LE(std::abs(c.x - rgb[0]), half) << rgb[0];
        EXPECT_LE(std::abs(c.y - rgb[1]), half) << rgb[1];
        EXPECT_LE(std::abs(c.z - rgb[2]), half) << rgb[2];
    }
}

TEST(FarSplat, SampleCountFollowsProjectedArea) {
    // 0.2 m^2 of leaves seen at 15 px per metre: 45 px of surface (under the taper's 64), 22.5 px
    // projected on average, 2 samples per pixel.
    EXPECT_EQ(farSampleCount(0.2f, 15.0f, 2.0f, 4096u), 45u);
    // Twice as far: a quarter (rounded up).
    EXPECT_EQ(farSampleCount(0.2f, 7.5f, 2.0f, 4096u), 12u);
    // Never fewer than one, never more than the clump has.
    EXPECT_EQ(farSampleCount(0.2f, 0.01f, 2.0f, 4096u), 1u);
    EXPECT_EQ(farSampleCount(0.2f, 1000.0f, 2.0f, 4096u), 4096u);
    // Non-increasing with distance, through the taper too.
    uint previous = 4096u;
    for (float ppm = 400.0f; ppm > 0.5f; ppm *= 0.97f) {
        const uint n = farSampleCount(0.2f, ppm, 2.0f, 4096u);
        EXPECT_LE(n, previous);
        previous = n;
    }
}

TEST(FarSplat, DensityTapersForLargerInstances) {
    // The full density up to 64 px of surface (8 px of size), 0.6 of it from 256 px (16 px), linear
    // in between and continuous at both ends.
    EXPECT_EQ(farDensityShare(1.0f), 1.0f);
    EXPECT_EQ(farDensityShare(kFarTaperFrom), 1.0f);
    EXPECT_FLOAT_EQ(farDensityShare(0.5f * (kFarTaperFrom + kFarTaperTo)), 0.8f);
    EXPECT_FLOAT_EQ(farDensityShare(kFarTaperTo), kFarTaperShare);
    EXPECT_FLOAT_EQ(farDensityShare(1e6f), kFarTaperShare);
    for (float surface = 1.0f; surface < 1000.0f; surface *= 1.01f)
        EXPECT_LE(farDensityShare(surface * 1.01f), farDensityShare(surface));
    // 0.2 m^2 at 100 px per metre: 2,000 px of surface, 1,000 px projected, 2 x 0.6 per pixel.
    EXPECT_NEAR(double(farSampleCount(0.2f, 100.0f, 2.0f, 4096u)), 1200.0, 1.0);
    // Below the taper the count is the untapered one, bit for bit.
    for (float ppm = 1.0f; ppm < 17.8f; ppm *= 1.03f)
        EXPECT_EQ(farSampleCount(0.2f, ppm, 5.0f, 4096u),
                  uint(std::max(1.0f, std::ceil(5.0f * (0.5f * 0.2f * (ppm * ppm))))))
            << ppm;
}

TEST(FarSplat, FootprintFollowsAreaDistanceAndAngle) {
    // 1 cm^2 at 100 px per metre facing the camera: one pixel; at 60 degrees half; edge-on none.
    EXPECT_FLOAT_EQ(farSampleFootprint(1e-4f, 100.0f, 1.0f), 1.0f);
    EXPECT_FLOAT_EQ(farSampleFootprint(1e-4f, 100.0f, -0.5f), 0.5f); // either side of the sheet
    EXPECT_EQ(farSampleFootprint(1e-4f, 100.0f, 0.0f), 0.0f);
    EXPECT_FLOAT_EQ(farSampleFootprint(1e-4f, 200.0f, 1.0f), 4.0f);
    // Squares only for footprints of several pixels, capped.
    EXPECT_EQ(farSplatSide(0.3f), 1u);
    EXPECT_EQ(farSplatSide(2.0f), 1u);
    EXPECT_EQ(farSplatSide(4.0f), 2u);
    EXPECT_EQ(farSplatSide(9.5f), 3u);
    EXPECT_EQ(farSplatSide(1e6f), kFarMaxSplatSide);
}

TEST(FarSplat, SquaresAreCentredOnTheirSample) {
    // One pixel: the pixel holding the sample, negative coordinates included.
    EXPECT_EQ(farSplatCorner(10.3f, 1u), 10);
    EXPECT_EQ(farSplatCorner(-0.2f, 1u), -1);
    // Even sides: the square whose centre is nearest the sample, whichever half of its pixel it is in.
    EXPECT_EQ(farSplatCorner(10.3f, 2u), 9);  // covers 9..10, centre 10.0
    EXPECT_EQ(farSplatCorner(10.7f, 2u), 10); // covers 10..11, centre 11.0
    EXPECT_EQ(farSplatCorner(10.7f, 4u), 9);  // covers 9..12, centre 11.0
    EXPECT_EQ(farSplatCorner(10.3f, 3u), 9);  // covers 9..11, centre 10.5
    // Over every sub-pixel position, a square's centre lies on its sample on average.
    for (uint side = 1u; side <= kFarMaxSplatSide; ++side) {
        double offset = 0.0;
        const int n = 1024;
        for (int i = 0; i < n; ++i) {
            const float pixel = 100.0f + (float(i) + 0.5f) / float(n);
            offset += double(farSplatCorner(pixel, side)) + 0.5 * double(side) - double(pixel);
        }
        EXPECT_NEAR(offset / n, 0.0, 1e-3) << side;
    }
}

TEST(FarSplat, CoverageRandomNumbersAreUniformAndFixed) {
    // The share of samples kept below a footprint f is f (stochastic coverage), whichever instance.
    for (uint instance : {0u, 7u, 123456u}) {
        uint below = 0;
        const uint n = 20000;
        for (uint k = 0; k < n; ++k) {
            const float u = farSampleRandom(instance, k);
            ASSERT_GE(u, 0.0f);
            ASSERT_LT(u, 1.0f);
            below += u < 0.3f;
        }
        // Binomial: 0.3 n +- 5 sigma.
        EXPECT_NEAR(double(below) / n, 0.3, 5.0 * std::sqrt(0.3 * 0.7 / n)) << instance;
    }
    EXPECT_EQ(farSampleRandom(5u, 9u), farSampleRandom(5u, 9u));
    EXPECT_NE(farSampleRandom(5u, 9u), farSampleRandom(6u, 9u));
}

TEST(FarSplat, InstancesDrawRunsOfTheirClumpsSamplesFromStartsOfTheirOwn) {
    // 10,000 instances of one clump of 1,000 samples, each drawing 10: every sample drawn about as
    // often (100 times), not only a prefix of ten; each instance's samples consecutive (cyclically)
    // and distinct.
    const uint available = 1000u, count = 10u, instances = 10000u;
    std::vector<uint> drawn(available, 0u);
    for (uint instance = 0; instance < instances; ++instance) {
        const uint start = farSampleStart(instance, available);
        ASSERT_LT(start, available);
        for (uint k = 0; k < count; ++k) {
            const uint slot = farSampleSlot(start, k, available);
            ASSERT_EQ(slot, (start + k) % available) << instance << " " << k;
            ++drawn[slot];
        }
    }
    // Poisson-like counts of mean 100: each within 100 +- 6 sigma.
    for (uint s = 0; s < available; ++s) {
        EXPECT_GT(drawn[s], 40u) << s;
        EXPECT_LT(drawn[s], 160u) << s;
    }
    // The same start every frame, and a run that wraps past the list's end.
    EXPECT_EQ(farSampleStart(42u, available), farSampleStart(42u, available));
    EXPECT_EQ(farSampleSlot(available - 2u, 3u, available), 1u);
    EXPECT_EQ(farSampleStart(9u, 1u), 0u);
}

// The view that decides a sample's visibility (far_splat.h): an eye exactly in a view's direction
// picks that view whatever the random numbers; straight above picks the top bit; between two views
// the random number picks each in proportion to the eye's nearness to it.
namespace {
uint farVisibilityBitTowards(float dx, float dy, float dz, float r1, float r2) {
    return farVisibilityBitAt(farEyeAzimuth(dx, dz), farEyeElevation(dx, dy, dz), r1, r2);
}
} // namespace

TEST(FarSplat, VisibilityViewFollowsTheEyesDirection) {
    for (uint e = 0; e + 1 < kFarGainElevations; ++e)
        for (uint a = 0; a < kFarVisibilityAzimuths; ++a) {
            const float az = (float(a) + 0.5f) * 0.78539816f, el = float(e) * 0.52359878f;
            for (float r : {0.01f, 0.5f, 0.99f}) // (rounding may put the eye a hair off the view)
                EXPECT_EQ(farVisibilityBitTowards(-std::sin(az) * std::cos(el) * 3.0f, std::sin(el) * 3.0f,
                                                  std::cos(az) * std::cos(el) * 3.0f, r, r),
                          e * 8u + a)
                    << a << " " << e << " " << r;
        }
    EXPECT_EQ(farVisibilityBitTowards(0.0f, 2.0f, 0.0f, 0.3f, 0.7f), kFarVisibilityTopBit);
    EXPECT_EQ(farVisibilityBitTowards(0.01f, 2.0f, 0.0f, 0.3f, 0.7f), kFarVisibilityTopBit);
    // Below the horizon counts as level.
    EXPECT_EQ(farVisibilityBitTowards(-std::sin(0.3927f), -0.5f, std::cos(0.3927f), 0.9f, 0.9f), 0u);
    // A quarter of the way from view 1 (67.5 degrees) to view 2 (112.5), level: view 2 for a
    // quarter of the random numbers.
    const float az = 78.75f * 0.017453293f;
    uint second = 0;
    for (uint i = 0; i < 1000; ++i) {
        const uint bit = farVisibilityBitTowards(-std::sin(az), 0.0f, std::cos(az), (float(i) + 0.5f) / 1000.0f, 0.0f);
        ASSERT_TRUE(bit == 1u || bit == 2u) << bit;
        second += bit == 2u;
    }
    EXPECT_NEAR(double(second), 250.0, 2.0);
    // Past the last view the next is the first again (337.5 -> 22.5 degrees).
    const float wrap = 0.0f; // 360 degrees: halfway between views 7 and 0
    EXPECT_EQ(farVisibilityBitTowards(-std::sin(wrap), 0.0f, std::cos(wrap), 0.2f, 0.0f), 0u);
    EXPECT_EQ(farVisibilityBitTowards(-std::sin(wrap), 0.0f, std::cos(wrap), 0.8f, 0.0f), 7u);
}

// The size the gain table is looked up at: the square root of the surface, in pixels at the base
// (4 m² is 2 m across; at 10 px per metre, 20 px).
TEST(FarSplat, InstanceSizeIsItsSurfacesSideInPixels) {
    EXPECT_FLOAT_EQ(farInstanceSize(4.0f, 10.0f), 20.0f);
    EXPECT_FLOAT_EQ(farInstanceSize(4.0f, 5.0f), 10.0f);
    EXPECT_FLOAT_EQ(farInstanceSize(16.0f, 5.0f), 20.0f);
    // On the optical axis (distance = depth), pixelsPerUnit / depth.
    EXPECT_FLOAT_EQ(farPixelsPerMetre(100.0f, 10.0f, 10.0f), 10.0f);
    EXPECT_FLOAT_EQ(farPixelsPerMetre(100.0f, 10.0f, 40.0f), 20.0f);
}

// farPixelsPerMetre against the projection itself: a small square facing the eye, anywhere in a
// 16:9 view 50 degrees high, covers farPixelsPerMetre^2 times its area in pixels (to the square's
// own perspective, well under 0.1 %), and off the axis clearly more than pixelsPerUnit / depth
// gives (38 % at the corners), the splats' footprints and counts follow that (far_splat.h).
TEST(FarSplat, PixelsPerMetreMatchTheProjectionAcrossTheView) {
    meadow::Camera camera;
    camera.eye = glm::vec3(3.0f, 7.0f, -11.0f);
    camera.target = glm::vec3(-2.0f, 0.5f, 6.0f);
    camera.fovYDegrees = 50.0f;
    const uint width = 1280, height = 720;
    const GpuFrame frame = meadow::makeCameraUniforms(camera, width, height, 1);
    const glm::mat4 view = meadow::viewMatrix(camera);
    const glm::mat3 toWorld = glm::transpose(glm::mat3(view)); // the view's axes in world space
    // In double precision: the squares cover a few pixels, far from the image's origin.
    const glm::dmat4 viewProj(frame.viewProj);
    const auto pixel = [&](glm::dvec3 p) {
        const glm::dvec4 clip = viewProj * glm::dvec4(p, 1.0);
        return (glm::dvec2(clip) / clip.w * 0.5 + 0.5) * glm::dvec2(double(width), double(height));
    };
    const float tanY = std::tan(glm::radians(25.0f)), tanX = tanY * 16.0f / 9.0f;
    float largestExcess = 0.0f;
    for (float sx : {-0.98f, -0.5f, 0.0f, 0.3f, 0.98f})
        for (float sy : {-0.98f, 0.0f, 0.6f, 0.98f})
            for (float depth : {12.0f, 45.0f}) {
                // A point at (sx, sy) of the view's half-extents, `depth` in front of the eye.
                const glm::vec3 p = camera.eye + toWorld * glm::vec3(sx * tanX * depth, sy * tanY * depth, -depth);
                const glm::vec3 toEye = camera.eye - p;
                const float eyeDistance = glm::length(toEye);
                const glm::vec3 n = toEye / eyeDistance;
                const glm::vec3 u = glm::normalize(glm::cross(n, glm::vec3(0.0f, 1.0f, 0.0f)));
                const glm::vec3 v = glm::cross(n, u);
                const double h = 1e-3 * double(depth); // m: about a pixel at either depth
                const glm::dvec3 q(p), du = h * glm::dvec3(u), dv = h * glm::dvec3(v);
                const glm::dvec2 a = pixel(q - du - dv), b = pixel(q + du - dv), c = pixel(q + du + dv),
                                 d = pixel(q - du + dv);
                const float pixels = float(0.5 * std::abs((a.x * b.y - b.x * a.y) + (b.x * c.y - c.x * b.y) +
                                                          (c.x * d.y - d.x * c.y) + (d.x * a.y - a.x * d.y)));
                const float square = float(4.0 * h * h);
                const float clipW = (frame.viewProj * glm::vec4(p, 1.0f)).w;
                EXPECT_NEAR(clipW, depth, 1e-3f * depth);
                const float ppm = farPixelsPerMetre(frame.lodScreen.x, clipW, eyeDistance);
                EXPECT_NEAR(pixels / (square * ppm * ppm), 1.0f, 1e-3f) << sx << " " << sy << " " << depth;
                const float onAxis = frame.lodScreen.x / clipW;
                largestExcess = std::max(largestExcess, pixels / (square * onAxis * onAxis));
            }
    EXPECT_GT(largestExcess, 1.3f);
}

// The coverage gain's table (far_splat.h): exact at its bins, linear between them in log2 of the
// size and in the elevation's 30-degree units, clamped at both ends.
TEST(FarSplat, CoverageGainInterpolatesItsTable) {
    GpuClump clump{};
    for (uint size = 0; size < kFarGainSizes; ++size)
        for (uint e = 0; e < kFarGainElevations; ++e)
            clump.farGain[size][int(e)] = 1.0f + float(size) + 0.25f * float(e);
    for (uint size = 0; size < kFarGainSizes; ++size)
        for (uint e = 0; e < kFarGainElevations; ++e)
            EXPECT_FLOAT_EQ(farCoverageGain(clump, kFarGainFirstSize * float(1u << size), float(e)),
                            1.0f + float(size) + 0.25f * float(e))
                << size << " " << e;
    EXPECT_NEAR(farCoverageGain(clump, kFarGainFirstSize * std::sqrt(2.0f), 1.5f), 1.5f + 0.375f, 1e-5f);
    EXPECT_FLOAT_EQ(farCoverageGain(clump, 0.1f, 0.0f), 1.0f);     // smaller than the first bin
    EXPECT_FLOAT_EQ(farCoverageGain(clump, 1000.0f, 3.0f), 5.75f); // larger than the last
    // The elevation of an eye straight above is the table's last column, from any side.
    EXPECT_FLOAT_EQ(farEyeElevation(0.0f, 2.0f, 0.0f), 3.0f);
    EXPECT_FLOAT_EQ(farEyeElevation(1.0f, -1.0f, 0.0f), 0.0f);
    EXPECT_NEAR(farEyeElevation(std::cos(0.5235988f), std::sin(0.5235988f), 0.0f), 1.0f, 1e-5f);
}

namespace {

// Mesh LOD switches at 200, 80, 30 and 10 px, bands of 10 %, 30 % jitter, no far field yet.
GpuLodParams fourSwitches() {
    GpuLodParams p{};
    const float radii[4] = {200.0f, 80.0f, 30.0f, 10.0f};
    for (int i = 0; i < 4; ++i)
        p.switchRadius[i] = radii[i];
    p.band = 0.1f;
    p.jitter = 0.3f;
    p.hysteresis = 0.1f;
    return p;
}

} // namespace

TEST(FarSplat, TheFarFieldTakesOverBelowItsRadiusLikeAnyLod) {
    GpuLodParams p = fourSwitches();
    // Without a far field the coordinate stops at LOD 4.
    EXPECT_EQ(lodCoordinate(p, 1.0f, 0.5f), 4.0f);
    EXPECT_EQ(lodSelect(p, 1.0f, 0.5f, 4.0f).fadeLod, 4u);
    // With one at 5 px: LOD 4 alone between the bands, far alone below 4.5 px (5 px, band 0.1),
    // a crossfade with the same jitter across the band.
    p.farRadius = 5.0f;
    EXPECT_EQ(lodCoordinate(p, 7.0f, 0.5f), 4.0f);
    EXPECT_EQ(lodCoordinate(p, 4.0f, 0.5f), float(kLodFar));
    GpuLodChoice c = lodSelect(p, 5.0f, 0.5f, 4.5f);
    EXPECT_EQ(c.lod, 4u);
    EXPECT_EQ(c.fadeLod, kLodFar);
    EXPECT_NEAR(c.fade, 0.5f, 1e-5f);
    // Jittered per instance: 0.85x .. 1.15x of the far radius.
    EXPECT_NEAR(lodCoordinate(p, 5.0f * 0.85f, 0.0f), 4.5f, 1e-5f);
    EXPECT_NEAR(lodCoordinate(p, 5.0f * 1.15f, 1.0f), 4.5f, 1e-5f);
    // Hysteresis inside the band, as for the meshes.
    c = lodSelect(p, 5.05f, 0.5f, 4.5f);
    EXPECT_EQ(c.x, 4.5f);
}

TEST(FarSplat, AFarRadiusAboveLod4sSwitchHandsLod3ToTheFarField) {
    GpuLodParams p = fourSwitches();
    EXPECT_EQ(lodMeshLevels(p), 5u);
    // 8 px: its band (7.2 .. 8.8 px) lies below LOD 4's (9 .. 11 px): every mesh LOD is drawn.
    p.farRadius = 8.0f;
    EXPECT_EQ(lodMeshLevels(p), 5u);
    EXPECT_EQ(lodSelect(p, 8.95f, 0.5f, 4.0f).lod, 4u);
    // 9 px: the bands would overlap, so LOD 4 is never drawn and LOD 3 hands over at 9 px.
    p.farRadius = 9.0f;
    EXPECT_EQ(lodMeshLevels(p), 4u);
    // 20 px: the same, the switch at 20 px.
    p.farRadius = 20.0f;
    EXPECT_EQ(lodMeshLevels(p), 4u);
    for (float r = 0.5f; r < 400.0f; r *= 1.05f) {
        const GpuLodChoice c = lodSelect(p, r, 0.5f, lodCoordinate(p, r, 0.5f));
        EXPECT_NE(c.lod, 4u) << r;
        EXPECT_NE(c.fadeLod, 4u) << r;
    }
    EXPECT_EQ(lodSelect(p, 25.0f, 0.5f, 3.0f).lod, 3u);
    GpuLodChoice c = lodSelect(p, 20.0f, 0.5f, 3.5f);
    EXPECT_EQ(c.lod, 3u);
    EXPECT_EQ(c.fadeLod, kLodFar);
    EXPECT_NEAR(c.fade, 0.5f, 1e-5f);
    c = lodSelect(p, 15.0f, 0.5f, 4.0f);
    EXPECT_EQ(c.lod, kLodFar);
    EXPECT_EQ(c.fadeLod, kLodFar);
    EXPECT_EQ(c.fade, 0.0f);
    // Jitter and hysteresis as for any switch.
    EXPECT_NEAR(lodCoordinate(p, 20.0f * 0.85f, 0.0f), 3.5f, 1e-5f);
    EXPECT_EQ(lodSelect(p, 20.2f, 0.5f, 3.5f).x, 3.5f);
    // 40 px: LODs 3 and 4 both skipped.
    p.farRadius = 40.0f;
    EXPECT_EQ(lodMeshLevels(p), 3u);
    c = lodSelect(p, 40.0f, 0.5f, 2.5f);
    EXPECT_EQ(c.lod, 2u);
    EXPECT_EQ(c.fadeLod, kLodFar);
}
