// The light pass on a real device against the CPU's SH evaluation of the same transfer.
// ctest runs these at two lavapipe vector widths (LP_NATIVE_VECTOR_WIDTH=128 and 256).
#include "gpu_fixture.h"
#include "library/mesh.h"
#include "library/terrain.h"
#include "light/sh.h"
#include "render/field_renderer.h"
#include "render/ground_light_map.h"
#include "render/offscreen.h"
#include "sh_light.h"
#include "vk/memory.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>
#include <random>

using namespace meadow;
using namespace meadow::test;

namespace {

// A static tuft of `blades` whose light takes three yaw bins over [-0.3, 0.5) radians, with a ground
// grid of `points` a side over 1 m (its transfer left to the test).
FieldClump clumpWithGroundGrid(uint32_t blades, uint32_t points) {
    FieldClump clump = staticFieldClump(makeTuftMesh(blades), 1);
    clump.yawLow = -0.3f;
    clump.yawHigh = 0.5f;
    clump.yawBins = 3;
    clump.groundResolution = points;
    clump.groundSize = 1.0f;
    return clump;
}

// Open ground's transfer: the clamped cosine about +y, in SH.
std::array<double, 9> openGroundTransfer() {
    double up[9];
    sh::evaluate(3, glm::dvec3(0.0, 1.0, 0.0), up);
    const double lobe[9] = {M_PI,     2 * M_PI / 3, 2 * M_PI / 3, 2 * M_PI / 3, M_PI / 4,
                            M_PI / 4, M_PI / 4,     M_PI / 4,     M_PI / 4};
    std::array<double, 9> open;
    for (int i = 0; i < 9; ++i)
        open[i] = lobe[i] * up[i];
    return open;
}

} // namespace

// light.comp against an independent CPU evaluation: a static clump's unshadowed transfer lit by
// the sky must give, for every yaw bin and mirror, the irradiance of the world sky on the
// vertex's normal as the instance turns it (clamped cosine in SH at R M n); a transfer with
// gradients gives T̄ and G dotted with the sky in the clump's frame (sh_light.h).
TEST_F(Gpu, LightPassMatchesCpuReference) {
    const glm::vec2 wind = glm::normalize(glm::vec2(1.0f, 0.25f));
    // A ground grid of open ground with one shaded point, a quarter of the light, in the middle.
    FieldClump plain = clumpWithGroundGrid(5, 3);
    const std::array<double, 9> open = openGroundTransfer();
    for (uint32_t point = 0; point < 9; ++point)
        for (uint32_t c = 0; c < 3; ++c)
            for (uint32_t i = 0; i < 9; ++i)
                plain.groundTransfer.push_back(float(open[i] * (point == 4 ? 0.25 : 1.0)));
    FieldClump graded = plain;
    uint64_t seed = 5;
    for (size_t i = 0; i < graded.mesh.vertices.size() * 216; ++i) {
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        graded.transfer.push_back(float(seed >> 40) / float(1 << 24) - 0.3f);
    }
    FieldScenery scenery = testScenery();
    scenery.windDirection = wind;
    gpu::GpuInstance inst{};
    inst.positionScale = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    inst.boundingRadius = 1.0f;
    FieldRenderer renderer = createFieldRenderer(*context, std::vector<FieldClump>{plain, graded},
                                                 std::vector<gpu::GpuInstance>{inst}, testAtlas(), scenery);
    Offscreen offscreen = createOffscreen(*context, {16, 16});
    renderOffscreenFrame(*context, renderer, offscreen, frameState(Camera{}, 16, 16));
    std::vector<glm::vec4> light(renderer.vertexLight.size / sizeof(glm::vec4));
    readbackBuffer(*context, renderer.vertexLight, light.data(), renderer.vertexLight.size);
    std::vector<glm::uvec4> words(light.size());
    std::memcpy(words.data(), light.data(), words.size() * sizeof(glm::uvec4));
    // (E, gradient) of side-and-channel sc at a vertex's first uvec4: half floats, two per word.
    auto lit = [&](size_t first, uint32_t sc) {
        const glm::uvec4 w = words[first + sc / 2];
        const uint32_t a = sc % 2 == 0 ? w.x : w.z, b = sc % 2 == 0 ? w.y : w.w;
        return glm::vec4(glm::unpackHalf2x16(a), glm::unpackHalf2x16(b));
    };

    const std::vector<float>& sky = scenery.sky.frames[0].sh;
    std::vector<glm::dvec3> skyRgb(9);
    for (int i = 0; i < 9; ++i)
        skyRgb[i] = glm::dvec3(sky[3 * i], sky[3 * i + 1], sky[3 * i + 2]);
    const double band[9] = {M_PI,     2 * M_PI / 3, 2 * M_PI / 3, 2 * M_PI / 3, M_PI / 4,
                            M_PI / 4, M_PI / 4,     M_PI / 4,     M_PI / 4};
    const glm::dvec3 mirrorNormal(-wind.y, 0.0, wind.x);
    const uint32_t variants = 2 * plain.yawBins, vertices = uint32_t(plain.mesh.vertices.size());
    double worst = 0.0, scale = 0.0;
    for (uint32_t v = 0; v < vertices; ++v)
        for (uint32_t variant = 0; variant < variants; ++variant) {
            const bool mirrored = variant >= plain.yawBins;
            const double yaw =
                plain.yawLow + (variant % plain.yawBins + 0.5) * (plain.yawHigh - plain.yawLow) / plain.yawBins;
            glm::dvec3 n = glm::normalize(glm::dvec3(plain.mesh.vertices[v].normalV));
            if (mirrored)
                n -= 2.0 * glm::dot(n, mirrorNormal) * mirrorNormal;
            const glm::dvec3 turned(std::cos(yaw) * n.x + std::sin(yaw) * n.z, n.y,
                                    -std::sin(yaw) * n.x + std::cos(yaw) * n.z);
            for (uint32_t side = 0; side < 2; ++side) {
                double y[9];
                sh::evaluate(3, side == 0 ? turned : -turned, y);
                glm::dvec3 e(0.0);
                for (int i = 0; i < 9; ++i)
                    e += band[i] * y[i] * skyRgb[i];
                for (uint32_t c = 0; c < 3; ++c) {
                    const glm::vec4 g = lit((size_t(v) * variants + variant) * gpu::kLightVec4sPerVertex, side * 3 + c);
                    worst = std::max(worst, std::abs(double(g.x) - e[c]));
                    scale = std::max(scale, std::abs(e[c]));
                    EXPECT_EQ(g.y, 0.0f);
                }
            }
        }
    EXPECT_GT(scale, 0.01);
    EXPECT_LT(worst, 1e-3 * scale) << "irradiance of the unshadowed clump (half floats)";
    // Its ground: open ground passes all the light, the shaded point a quarter, in every variant.
    const size_t groundBase = size_t(vertices) * variants * gpu::kLightVec4sPerVertex;
    for (uint32_t variant = 0; variant < variants; ++variant)
        for (uint32_t point = 0; point < 9; ++point) {
            const glm::vec4 ratio = light[groundBase + variant * 9 + point];
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(ratio[c], point == 4 ? 0.25f : 1.0f, 1e-4f) << "variant " << variant << " point " << point;
        }

    // The graded clump: T̄ and the gradient, per side and channel, against sh_light.h on the CPU.
    const size_t base = groundBase + variants * 9;
    worst = 0.0;
    scale = 0.0;
    for (uint32_t v = 0; v < vertices; ++v)
        for (uint32_t variant = 0; variant < variants; ++variant) {
            const bool mirrored = variant >= plain.yawBins;
            const float yaw = plain.yawLow + (float(variant % plain.yawBins) + 0.5f) * (plain.yawHigh - plain.yawLow) /
                                                 float(plain.yawBins);
            float in[27], local[27];
            std::copy(sky.begin(), sky.end(), in);
            gpu::shSkyToClumpFrame(in, gpu::shClumpFrameSign(mirrored),
                                   gpu::shClumpFrameDelta(yaw, mirrored, std::atan2(wind.x, wind.y)), local);
            for (uint32_t sc = 0; sc < 6; ++sc) {
                glm::dvec4 expected(0.0);
                for (uint32_t i = 0; i < 9; ++i)
                    for (uint32_t k = 0; k < 4; ++k)
                        expected[k] +=
                            double(graded.transfer[(size_t(v) * 54 + sc * 9 + i) * 4 + k]) * local[3 * i + sc % 3];
                const glm::vec4 g = lit(base + (size_t(v) * variants + variant) * gpu::kLightVec4sPerVertex, sc);
                for (int k = 0; k < 4; ++k) {
                    worst = std::max(worst, std::abs(double(g[k]) - expected[k]));
                    scale = std::max(scale, std::abs(expected[k]));
                }
            }
        }
    EXPECT_GT(scale, 0.01);
    EXPECT_LT(worst, 1e-3 * scale) << "transfer with gradients (half floats)";
    destroyOffscreen(*context, offscreen);
    destroyFieldRenderer(*context, renderer);
}

// ground_map.comp against its CPU reference (render/ground_light_map.h) from the ratios the light
// pass wrote: hundreds of overlapping grids, turned, mirrored and scaled, whose ratios differ
// point by point and with the yaw bin. Within 3e-3 relative: half floats hold the map (2^-11),
// and the lists hold the bilinear weights in 12 bits (2^-13 of a step between neighbouring points,
// a few texels a texel). Anything more is a texel that multiplied in the wrong cells.
TEST_F(Gpu, GroundLightMapMatchesCpuReference) {
    FieldClump clump = clumpWithGroundGrid(3, 4);
    const std::array<double, 9> open = openGroundTransfer();
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (uint32_t point = 0; point < 16; ++point) {
        // Open ground dimmed by a factor per point, with a tilt (band 1's x and z) that the yaw turns.
        const double factor = 0.2 + 0.8 * unit(rng), tiltX = unit(rng) - 0.5, tiltZ = unit(rng) - 0.5;
        for (uint32_t c = 0; c < 3; ++c)
            for (uint32_t i = 0; i < 9; ++i) {
                double t = open[i] * factor;
                if (i == 3)
                    t += 0.5 * factor * tiltX;
                if (i == 1)
                    t += 0.5 * factor * tiltZ;
                clump.groundTransfer.push_back(float(t));
            }
    }
    FieldClump other = clump;
    other.groundResolution = 2;
    other.groundSize = 0.6f;
    other.groundTransfer.resize(4 * 27);
    std::vector<gpu::GpuInstance> instances;
    for (uint32_t i = 0; i < 400; ++i) {
        gpu::GpuInstance inst{};
        const float scale = 0.5f + unit(rng);
        inst.positionScale = glm::vec4(4.0f * unit(rng), 0.0f, 4.0f * unit(rng), i % 2 ? -scale : scale);
        inst.yaw = -1.0f + 3.0f * unit(rng);
        inst.mesh = i % 5 == 0 ? 1 : 0;
        inst.boundingRadius = 1.0f;
        instances.push_back(inst);
    }
    const std::vector<FieldClump> clumps = {clump, other};
    FieldRenderer renderer = createFieldRenderer(*context, clumps, instances, testAtlas(), testScenery());
    Offscreen offscreen = createOffscreen(*context, {16, 16});
    renderOffscreenFrame(*context, renderer, offscreen, frameState(Camera{}, 16, 16));
    std::vector<glm::uvec4> light(renderer.vertexLight.size / sizeof(glm::uvec4));
    readbackBuffer(*context, renderer.vertexLight, light.data(), renderer.vertexLight.size);
    std::vector<gpu::GpuClump> packed(clumps.size());
    readbackBuffer(*context, renderer.clumps, packed.data(), packed.size() * sizeof(gpu::GpuClump));
    const std::vector<glm::vec3> gpuMap = readGroundLightMap(*context, renderer);
    const GroundLightMapLayout layout = groundLightMapLayout(clumps, instances);
    const std::vector<GroundCaster> casters =
        groundCasters(packed, instances, layout, glm::vec2(renderer.mirrorNormal.x, renderer.mirrorNormal.z));
    destroyOffscreen(*context, offscreen);
    destroyFieldRenderer(*context, renderer);

    const std::vector<glm::vec3> cpuMap = groundLightMapReference(casters, layout.size, light);
    ASSERT_EQ(gpuMap.size(), cpuMap.size());
    ASSERT_EQ(gpuMap.size(), size_t(layout.size.width) * layout.size.height);
    size_t shaded = 0, differing = 0;
    float worst = 0.0f;
    for (size_t i = 0; i < gpuMap.size(); ++i) {
        shaded += cpuMap[i].g < 0.9f;
        float error = 0.0f;
        for (int c = 0; c < 3; ++c)
            error = std::max(error, std::abs(gpuMap[i][c] - cpuMap[i][c]) / std::max(std::abs(cpuMap[i][c]), 1e-3f));
        differing += error > 3e-3f;
        worst = std::max(worst, error);
    }
    std::printf("map %ux%u, shaded %zu, differing %zu, worst %g\n", layout.size.width, layout.size.height, shaded,
                differing, worst);
    EXPECT_GT(shaded, gpuMap.size() / 4) << "the grids shade a good part of the map";
    EXPECT_EQ(differing, 0u) << "texels off by more than the rounding, worst " << worst;
}
