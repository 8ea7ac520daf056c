// Host/shader structs and constants: the one definition, included by both C++ and GLSL.
// Every struct here is laid out for std430 (storage buffers) and std140 (the frame uniform
// block) at once: only vec4/mat4/uint/float members, vec4-aligned. engine/vk/gpu_types_check.cpp
// static_asserts every size and offset so a mismatch fails the build, not the picture.
#ifndef MEADOW_GPU_TYPES_H
#define MEADOW_GPU_TYPES_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace meadow::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
using uint = std::uint32_t;
#define MEADOW_CONST inline constexpr uint
#else
#define MEADOW_CONST const uint
#endif

// Workgroup sizes (compute shaders use these; the host reads them back from SPIR-V to check).
MEADOW_CONST kCullGroupSize = 64;
MEADOW_CONST kTonemapGroupSize = 8;

// Per frame: the only data the CPU writes each frame (uniform buffer, set 0).
struct GpuFrame {
    mat4 viewProj;         // world -> clip, Vulkan clip space (y down, z in [0, 1])
    mat4 inverseViewProj;  // clip -> world, for the sky backdrop's view rays
    vec4 frustumPlanes[6]; // world-space planes (xyz normal pointing inside, w offset), normalised
    vec4 cameraPosition;   // xyz eye, w unused
    vec4 sunDirection;     // xyz unit vector towards the sun, w sun intensity
    vec4 sunColor;         // rgb linear, w unused
    vec4 skyZenith;        // rgb linear radiance of the sky overhead, w exposure
    vec4 skyHorizon;       // rgb linear radiance of the sky at the horizon, w unused
    uvec4 counts;          // x instance count, y draw buckets, z frame index, w LODs per clump (1: no choice)
    vec4 lodScreen;        // x pixels per unit of radius at unit distance (0.5 height P[1][1]), yzw unused
    vec4 lodSwitchRadius;  // GpuLodParams::switchRadius (lod_select.h), px
    vec4 lodBand;          // x band, y jitter, z hysteresis (GpuLodParams), w unused
};

// One plant instance (storage buffer, read by cull and the vertex shader).
struct GpuInstance {
    vec4 positionScale;   // xyz world position of the base, w uniform scale; negative: mirrored about the
                          // vertical plane holding the wind direction (instance.vert.glsl)
    float yaw;            // radians about +y
    float boundingRadius; // of the mesh's sphere (unscaled), centred half a radius above the base
    float tint;           // per-instance colour variation in [0, 1]
    uint mesh;            // which mesh (draw bucket) this instance uses
};

// One mesh vertex, pulled from a storage buffer by gl_VertexIndex.
struct GpuVertex {
    vec4 positionU; // xyz object-space position, w texture u
    vec4 normalV;   // xyz object-space normal, w texture v
};

// Matches VkDrawIndexedIndirectCommand word for word.
struct GpuDrawIndexedCommand {
    uint indexCount;
    uint instanceCount;
    uint firstIndex;
    int vertexOffset;
    uint firstInstance;
};

// Written by the cull pass for benchmarks, the HUD and tests.
struct GpuCullStats {
    uint visibleInstances;
    uint testedInstances;
    uint pad0;
    uint pad1;
};

#ifdef __cplusplus
} // namespace meadow::gpu
#endif
#undef MEADOW_CONST
#endif
