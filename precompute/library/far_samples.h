// The far field's surface samples of a clump or rock (docs/ARCHITECTURE.md; issue 18): points
// spread uniformly by area over LOD 0's surface, each with its normal, albedo and the far-LOD
// vertex whose motion and light it plays, shuffled so that any run of consecutive samples is an
// unbiased subset (stochastic pruning, Cook et al. 2007): a far instance draws n of them from a
// start of its own (far_splat.h farSampleStart, wrapping past the end) and scales each sample's
// footprint to area / n. pipeline/far_samples.h builds them; the FARS section stores them.
#pragma once

#include "far_splat.h"

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace meadow {

// One surface sample of a clump or rock for the far field (docs/ARCHITECTURE.md).
struct FarSample {
    glm::vec3 position{0.0f}; // clump space, at the clump's mean pose (the mesh the library stores), m
    uint32_t normal = 0;      // unit normal of the surface at the sample (one side of a two-sided sheet),
                              // octahedral: two snorm16 (x low), packOctahedral
    uint32_t albedo = 0;      // RGBA8, r in the low byte (GLSL unpackUnorm4x8): rgb sRGB-encoded from the
                              // atlas at the sample's UV (rocks: their constant albedo), a 255
    uint32_t vertex = 0;      // the clump vertex (index into the clump mesh) whose motion and light the
                              // sample plays: a vertex of the far LOD (the last LOD) of the same motion
                              // block (rod) as the triangle's nearest vertex where there is one, else
                              // the nearest far-LOD vertex
    uint32_t lightVertex = 0; // the clump vertex (of LOD 0) whose light transfer lights the sample: the
                              // sample's triangle's nearest vertex (its normal and shadowing)
    uint32_t visibility = gpu::kFarAllVisible; // the views from some of whose cell nothing of its own
                                               // clump hides the sample, a bit each (far_splat.h);
                                               // other bits 0
};

struct FarSamples {
    // Shuffled: any run of consecutive samples (cyclically) is an unbiased subset (a random
    // permutation from the scene seed).
    std::vector<FarSample> samples;
    // m^2: the surface the samples cover (one side); each of n drawn samples stands for area / n.
    float area = 0.0f;
    // The coverage gain on the samples' footprints (far_splat.h), size-major: gain[size *
    // kFarGainElevations + elevation]; positive and finite; 1 until measured (farCoverageGains).
    std::array<float, gpu::kFarGainSizes* gpu::kFarGainElevations> gain = [] {
        std::array<float, gpu::kFarGainSizes * gpu::kFarGainElevations> ones;
        ones.fill(1.0f);
        return ones;
    }();
};

// Bytes of one sample in the FARS section: position (3 x f32), normal, albedo, vertex, lightVertex,
// visibility (u32 each). Each clump's or rock's entry also holds its area, gain table and count.
inline constexpr uint32_t kFarSampleBytes = 32;

// Octahedral normal encoding (Meyer et al. 2010), the same in C++ and GLSL:
//   p = n.xy / (|n.x| + |n.y| + |n.z|);
//   if n.z < 0: p = (1 - |p.yx|) * s, with s = (p.x >= 0 ? 1 : -1, p.y >= 0 ? 1 : -1);
//   packed = packSnorm2x16(p): round(clamp(p, -1, 1) * 32767) as two int16, x in the low 16 bits.
// Decoding (GLSL: p = unpackSnorm2x16(packed), i.e. clamp(int16 / 32767, -1, 1)):
//   n = (p.x, p.y, 1 - |p.x| - |p.y|); if n.z < 0: n.xy = (1 - |n.yx|) * s (s as above, of n.xy);
//   n = normalize(n).
// A zero vector packs as +z. Round trip within 1e-4 (about 0.006 degrees) for any unit vector.
uint32_t packOctahedral(glm::vec3 n);
glm::vec3 unpackOctahedral(uint32_t packed);

} // namespace meadow
