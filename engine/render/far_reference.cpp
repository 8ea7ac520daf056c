#include "render/far_reference.h"

#include "core/error.h"
#include "far_splat.h"
#include "lod_select.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace meadow {
namespace {

constexpr float kPi = 3.14159265358979f; // common.glsl's

// far_splat.comp's octahedral normal (far_samples.h).
glm::vec3 unpackOctahedralNormal(uint32_t packed) {
    const glm::vec2 p = glm::unpackSnorm2x16(packed);
    glm::vec3 n(p.x, p.y, 1.0f - std::abs(p.x) - std::abs(p.y));
    if (n.z < 0.0f) {
        const glm::vec2 folded =
            (1.0f - glm::abs(glm::vec2(n.y, n.x))) * glm::vec2(n.x >= 0.0f ? 1.0f : -1.0f, n.y >= 0.0f ? 1.0f : -1.0f);
        n.x = folded.x;
        n.y = folded.y;
    }
    return glm::normalize(n);
}

template <typename T> const T& at(const std::vector<T>& values, size_t index, const char* what) {
    if (index >= values.size())
        throw Error(std::string("farSplatReference: ") + what + " index " + std::to_string(index) + " is outside its " +
                    std::to_string(values.size()) + " entries");
    return values[index];
}

// far_splat.comp's farSampleDisplacement: the rows the far field plays (at most kFarMotionModes)
// from the sample's motion texel (half floats).
glm::vec3 farSampleDisplacement(const FarSplatInputs& in, const gpu::GpuFarSample& farSample, const glm::uvec2& frames,
                                const gpu::GpuDrawInstance& inst) {
    const std::vector<float>& motionData = in.motionData;
    const gpu::GpuFarMotion& motion = at(in.farMotion, farSample.data.w, "far motion");
    const uint32_t rank = motion.rows.w >> gpu::kFarMotionRankShift;
    if (rank == 0u)
        return glm::vec3(0.0f);
    const uint32_t coordinate = motion.rows.w & gpu::kFarMotionOffsetMask, second = rank > 1u ? 1u : 0u;
    const uint32_t q0 = frames.x + coordinate, q1 = frames.y + coordinate;
    const bool blending = inst.pose.z > 0.0f;
    auto coordinateAt = [&](uint32_t first, uint32_t k) {
        float q = at(motionData, size_t(first) + k, "motion coordinate");
        if (blending)
            q = glm::mix(q, at(motionData, size_t(q1) + k, "motion coordinate"), inst.pose.z);
        return q;
    };
    const float qa = coordinateAt(q0, 0u), qb = coordinateAt(q0, second);
    const glm::vec2 a = glm::unpackHalf2x16(motion.rows.x), b = glm::unpackHalf2x16(motion.rows.y),
                    c = glm::unpackHalf2x16(motion.rows.z);
    return glm::vec3(a, b.x) * qa + glm::vec3(b.y, c) * qb;
}

} // namespace

std::vector<uint64_t> farSplatReference(const FarSplatInputs& in) {
    const gpu::GpuFrame& frame = in.frame;
    if (frame.motion.z == gpu::kDebugViewLod)
        throw Error("farSplatReference: the LOD debug view's colours are not modelled");
    const int width = int(frame.lodScreen.z), height = int(frame.lodScreen.w);
    if (width <= 0 || height <= 0)
        throw Error("farSplatReference: the frame's size is " + std::to_string(width) + "x" + std::to_string(height));
    const uint64_t empty = (uint64_t(gpu::kFarEmpty) << 32) | gpu::kFarEmpty;
    std::vector<uint64_t> visibility(size_t(width) * size_t(height), empty);
    const glm::vec3 m(in.mirrorNormal.x, 0.0f, in.mirrorNormal.z);

    for (const glm::uvec2& listed : in.farList) {
        const uint32_t entry = listed.x, count = listed.y;
        const uint32_t instance = entry & gpu::kLodEntryIndexMask;
        const gpu::GpuDrawInstance& inst = at(in.drawInstances, instance, "draw instance");
        const bool isFadeLod = (entry & gpu::kLodFadeEntryBit) != 0u;
        const float fade = inst.pose.w;
        const gpu::GpuClump& clump = at(in.clumps, inst.offsets.w >> 16u, "clump");
        const bool mirrored = inst.positionScale.w < 0.0f;
        const float c = inst.pose.x, s = inst.pose.y;
        const glm::mat3 yaw(c, 0.0f, -s, 0.0f, 1.0f, 0.0f, s, 0.0f, c);
        const float scale = std::abs(inst.positionScale.w);
        float clumpArea;
        std::memcpy(&clumpArea, &clump.far.z, sizeof clumpArea);
        const float area = clumpArea * scale * scale;
        const float areaPerSample = area / float(count);
        const glm::vec3 base(inst.positionScale);
        const glm::vec3 toEye = glm::vec3(frame.cameraPosition) - base;
        const float elevation = gpu::farEyeElevation(toEye.x, toEye.y, toEye.z);
        const float baseW = std::max((frame.viewProj * glm::vec4(base, 1.0f)).w, 1e-3f);
        const float gain = gpu::farCoverageGain(
            clump, gpu::farInstanceSize(area, gpu::farPixelsPerMetre(frame.lodScreen.x, baseW, glm::length(toEye))),
            elevation);
        glm::vec3 eye = toEye * yaw;
        if (mirrored)
            eye -= 2.0f * glm::dot(eye, m) * m;
        const float azimuth = gpu::farEyeAzimuth(eye.x, eye.z);
        const uint32_t start = gpu::farSampleStart(instance, clump.far.y);
        const glm::uvec2 farFrames = clump.motion.x + (glm::uvec2(inst.offsets.x, inst.offsets.y) - clump.motion.y) /
                                                          std::max(clump.motion.z, 1u) * clump.graphSizes.w;
        for (uint32_t k = 0; k < count; ++k) {
            const gpu::GpuFarSample& farSample =
                at(in.farSamples, size_t(clump.far.x) + gpu::farSampleSlot(start, k, clump.far.y), "far sample");
            const uint32_t bit =
                gpu::farVisibilityBitAt(azimuth, elevation, gpu::farSampleRandom(instance, k + gpu::kFarAzimuthStream),
                                        gpu::farSampleRandom(instance, k + gpu::kFarElevationStream));
            if ((farSample.position.w >> bit & 1u) == 0u)
                continue;
            const glm::vec3 d = farSampleDisplacement(in, farSample, farFrames, inst);
            glm::vec3 p = glm::uintBitsToFloat(glm::uvec3(farSample.position)) + d,
                      n = unpackOctahedralNormal(farSample.data.x);
            if (mirrored) {
                p -= 2.0f * glm::dot(p, m) * m;
                n -= 2.0f * glm::dot(n, m) * m;
            }
            const glm::vec3 world = base + yaw * (p * scale);
            const glm::vec4 clip = frame.viewProj * glm::vec4(world, 1.0f);
            if (clip.w <= 0.0f)
                continue;
            const glm::vec3 ndc = glm::vec3(clip) / clip.w;
            if (ndc.z <= 0.0f || ndc.z > 1.0f)
                continue;
            const glm::vec3 toEye = glm::vec3(frame.cameraPosition) - world;
            const float eyeDistance = glm::length(toEye);
            const float cosine = glm::dot(yaw * n, toEye) / std::max(eyeDistance, 1e-6f);
            if (cosine < 0.0f && clump.far.w != 0u)
                continue;
            const float footprint =
                gpu::farSampleFootprint(areaPerSample, gpu::farPixelsPerMetre(frame.lodScreen.x, clip.w, eyeDistance),
                                        cosine) *
                gain;
            if (footprint < 1.0f && gpu::farSampleRandom(instance, k) >= footprint)
                continue;
            const int side = int(gpu::farSplatSide(footprint));
            const glm::vec2 pixel = (glm::vec2(ndc) * 0.5f + 0.5f) * glm::vec2(float(width), float(height));
            const glm::ivec2 corner(gpu::farSplatCorner(pixel.x, uint32_t(side)),
                                    gpu::farSplatCorner(pixel.y, uint32_t(side)));
            if (corner.x >= width || corner.y >= height || corner.x + side <= 0 || corner.y + side <= 0)
                continue;

            const bool front = cosine >= 0.0f;
            const size_t light = size_t(inst.offsets.z) + size_t(farSample.data.z) * (inst.offsets.w & 0xffffu);
            const glm::uvec4 w0 = at(in.vertexLight, light, "vertex light"),
                             w1 = at(in.vertexLight, light + 1, "vertex light"),
                             w2 = at(in.vertexLight, light + 2, "vertex light");
            auto halves = [](uint32_t a, uint32_t b) {
                return glm::vec4(glm::unpackHalf2x16(a), glm::unpackHalf2x16(b));
            };
            glm::vec3 irradiance;
            if (front) {
                const glm::vec4 l0 = halves(w0.x, w0.y), l1 = halves(w0.z, w0.w), l2 = halves(w1.x, w1.y);
                irradiance = glm::vec3(l0.x + glm::dot(glm::vec3(l0.y, l0.z, l0.w), d),
                                       l1.x + glm::dot(glm::vec3(l1.y, l1.z, l1.w), d),
                                       l2.x + glm::dot(glm::vec3(l2.y, l2.z, l2.w), d));
            } else {
                const glm::vec4 l3 = halves(w1.z, w1.w), l4 = halves(w2.x, w2.y), l5 = halves(w2.z, w2.w);
                irradiance = glm::vec3(l3.x + glm::dot(glm::vec3(l3.y, l3.z, l3.w), d),
                                       l4.x + glm::dot(glm::vec3(l4.y, l4.z, l4.w), d),
                                       l5.x + glm::dot(glm::vec3(l5.y, l5.z, l5.w), d));
            }
            const gpu::FarVec3 a = gpu::unpackRgb9e5(farSample.data.y);
            const glm::vec3 radiance = glm::vec3(a.x, a.y, a.z) * glm::max(irradiance, glm::vec3(0.0f)) / kPi;
            const uint64_t word =
                (uint64_t(gpu::farDepthKey(ndc.z)) << 32) | gpu::packRgb9e5(radiance.r, radiance.g, radiance.b);

            for (int j = 0; j < side; ++j)
                for (int i = 0; i < side; ++i) {
                    const glm::ivec2 px = corner + glm::ivec2(i, j);
                    if (px.x < 0 || px.y < 0 || px.x >= width || px.y >= height)
                        continue;
                    if (fade > 0.0f && !gpu::lodDitherKeeps(isFadeLod, fade, uint32_t(px.x), uint32_t(px.y)))
                        continue;
                    const size_t index = size_t(px.y) * size_t(width) + size_t(px.x);
                    visibility[index] = std::min(visibility[index], word);
                }
        }
    }
    return visibility;
}

} // namespace meadow
