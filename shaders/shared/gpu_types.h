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
MEADOW_CONST kAnimateGroupSize = 64;
MEADOW_CONST kLightGroupSize = 64;
MEADOW_CONST kTonemapGroupSize = 8;
// The resolve (far_resolve.comp) and the ground light map (ground_map.comp), a thread per pixel or
// texel, run in workgroups of a run of this many pixels of one row. On lavapipe the resolve took
// 9.3 ms a frame with these against 12.4 with tiles of 8x8 and 10.0 with runs of 64, and the ground
// map 23 ms a light frame against 28-36 with tiles of 8x8 (docs/BENCHMARKS.md, "The resolve in
// runs of a row"); on a GPU, four warps on adjacent pixels.
MEADOW_CONST kRowRunWidth = 128;
// The far field (far_splat.h): a splat workgroup takes kFarInstancesPerGroup far instances at once,
// its width / kFarInstancesPerGroup threads ("lanes") striding over each one's samples; one
// workgroup per kFarInstancesPerGroup listed instances, at most kFarMaxGroups, each then taking
// every kFarMaxGroups-th set; the resolve pass one thread per pixel. The width is specialized per
// device (FieldScenery::farLanes): kFarGroupSize, 2 lanes, on a CPU, where most far instances' few
// dozen samples keep both SIMD halves busy; up to kFarMaxLanes on a GPU, which needs far more
// threads in flight than there are far instances. The picture is the same at any width.
MEADOW_CONST kFarGroupSize = 64;
MEADOW_CONST kFarMaxLanes = 32;
MEADOW_CONST kFarInstancesPerGroup = 32;
MEADOW_CONST kFarMaxGroups = 65535;

// Motion steps the animate pass takes at most in one frame: 10 s of motion, so the field keeps
// real time at any frame rate down to 0.1 fps. After a longer stall (a minimised window, a
// debugger) the motion resumes where it stopped instead of stepping every instance thousands of
// times.
MEADOW_CONST kMaxMotionStepsPerFrame = 300;
// Per clump vertex and light variant: irradiance of the front and back side in RGB, each with its
// gradient in the vertex's displacement, (E, dE/dx, dE/dy, dE/dz) per side and channel, as half
// floats: 24 halves in 3 uvec4 (packHalf2x16 pairs: value k of the 24 in word k / 2).
MEADOW_CONST kLightVec4sPerVertex = 3;
// One frame of the sky day in the skyData buffer: floats [0, 27) the RGB SH (sh[3 i + c], order
// 3), [28, 31) the sun direction, [32, 35) the sun disk's radiance, then from kSkyFrameHeaderFloats
// the backdrop image (light/latlong.h layout, RGB).
MEADOW_CONST kSkyFrameHeaderFloats = 36;
// One grid cell in a texel's list of the ground light map (render/ground_light_map.h), a uvec2: x
// the vertexLight vec4 of the cell's lowest grid point (row, column), y the bilinear weights along
// the row and the column, kGroundWeightBits bits each (unorm), and the grid's points per side less
// one in the top 8 bits (grids have at most kGroundGridMaxPoints a side).
MEADOW_CONST kGroundWeightBits = 12;
MEADOW_CONST kGroundGridMaxPoints = 256;
// Debug views (GpuFrame::motion.z).
MEADOW_CONST kDebugViewNone = 0;
MEADOW_CONST kDebugViewLod = 1;
// GpuFrame::motion.w: the far field's instances are drawn as LOD 0 meshes, not splats (its reference).
MEADOW_CONST kFrameFarAsLod0 = 1;
// GpuFrame::motion.w: the mesh LODs of instances small enough on the screen are drawn by the near
// raster (near_raster.h), not the mesh pass.
MEADOW_CONST kFrameNearRaster = 2;

// Per frame: the only data the CPU writes each frame (uniform buffer, set 0).
struct GpuFrame {
    mat4 viewProj;         // world -> clip, Vulkan clip space (y down, z in [0, 1])
    mat4 inverseViewProj;  // clip -> world, for the sky backdrop's view rays
    vec4 frustumPlanes[6]; // world-space planes (xyz normal pointing inside, w offset), normalised
    vec4 cameraPosition;   // xyz eye, w unused
    vec4 sunDirection;     // xyz unit vector towards the sun (blended between the sky frames), w unused
    vec4 sunColor;         // rgb the sun disk's radiance, w its angular radius (radians)
    vec4 skyZenith;        // rgb unused, w exposure (radiance -> display, before the tone curve)
    vec4 skyHorizon;       // rgb radiance of the sky at the horizon (haze), w unused
    uvec4 counts;          // x instance count, y draw buckets, z frame index, w LODs per clump (1: no choice)
    vec4 lodScreen;        // x pixels per unit of radius at unit distance (0.5 height P[1][1]), y far-field
                           // samples per pixel of projected surface (far_splat.h), z width, w height (px)
    vec4 lodSwitchRadius;  // GpuLodParams::switchRadius (lod_select.h), px
    vec4 lodBand;          // x band, y jitter, z hysteresis, w far radius (GpuLodParams; 0: no far field)
    // The wind over the field (wind_field.h): travelling waves and gusts of wind level.
    vec4 windWave;  // xy unit (x, z) direction the waves travel, z base level, w wave amplitude (levels)
    vec4 windShape; // x 1 / wavelength (1/m), y wave cycles per motion tick, z gust amplitude (levels),
                    // w gust cells per metre
    vec4 windGust;  // x gust cells travelled per motion tick, yzw unused
    uvec4 motion;   // x the first motion tick this frame steps to, y steps this frame, z debug view, w flags
                    // (kFrameFarAsLod0)
    // The sky: two frames of the library's day (SKYD) blended; light.comp projects onto it.
    uvec4 skyFrames; // x first frame, y second frame, zw unused
    vec4 skyBlend;   // x weight of the second frame, y azimuth of the simulation wind (mirror plane), zw unused
    vec4 groundMap;  // the ground light map's rectangle: x, y its lowest world x and z, z, w 1 / its size in x, z
    // The two sky frames' SH coefficients of order 3 blended at skyBlend.x (rgb; w unused), for the
    // terrain's vertex light: uniform reads instead of 54 gathers from the sky buffer per vertex.
    vec4 skySh[9];
};

// One plant instance (storage buffer, read by cull and the vertex shader).
struct GpuInstance {
    vec4 positionScale;   // xyz world position of the base, w uniform scale; negative: mirrored about the
                          // vertical plane holding the wind direction (instance.vert.glsl)
    float yaw;            // radians about +y
    float boundingRadius; // of the mesh's sphere (unscaled), centred half a radius above the base
    float pad0;           // keeps the struct 32 bytes (std430); always 0
    uint mesh;            // which mesh (draw bucket) this instance uses
};

// One clump (or rock) of the field: where its data lie in the shared buffers. Static meshes have
// no motion modes and a one-node motion graph.
struct GpuClump {
    uvec4 motion;     // x first far-field coordinate (motionData: per frame the last LOD's coordinates,
                      // GpuFarMotion), y first coordinate (motionData), z coordinates per frame, w frames
    uvec4 graph;      // offsets into motionGraph: x edgeStart, y edgeTarget, z edgeWeight, w naturalNext
    uvec4 graphSizes; // x edges, y wind levels, z blend frames, w far-field coordinates per frame (motion.x)
    uvec4 light;      // x first vec4 in vertexLight, y light variants per mirror state (yaw bins),
                      // z first value in transfer, w vertices
    vec4 yawBins;     // x lowest yaw, y bins per radian (0: one bin), z bin width (radians), w ground grid
                      // side (m)
    uvec4 ground;     // the ground grid around the clump: x first vec4 of its transfer in transfer (27 per
                      // point), y first vec4 of its light (per variant, per point), z points per side (0:
                      // none), w unused
    vec4 albedo;      // rgb constant albedo, w 1: use it instead of the atlas
    uvec4 far;        // the far field's surface samples: x first GpuFarSample, y samples, z their surface
                      // (m^2, float bits), w 1: a closed surface (a rock), whose samples facing away are
                      // hidden, 0: two-sided sheets
    vec4 farGain[5];  // the far field's coverage gains (far_splat.h): [size bin], its elevation bins in xyzw
};
// A GpuClump read as RGBA32 texels (instance.vert): how many it takes, and which is its albedo.
MEADOW_CONST kClumpTexels = 13;
MEADOW_CONST kClumpAlbedoTexel = 6;

// One surface sample of a clump for the far field (precompute/library/far_samples.h), as the
// splat pass reads it (32 bytes).
struct GpuFarSample {
    uvec4 position; // xyz the bits of its clump-space position at the mean pose (floats), w the views
                    // from which its own clump does not hide it (far_splat.h)
    uvec4 data;     // x normal (octahedral snorm16 pair), y linear albedo (RGB9E5, far_splat.h), z the clump vertex
                    // whose light it takes, w the GpuLodVertex of the last LOD whose motion it follows
};
// The motion of a last-LOD vertex as far samples follow it (farMotion, in GpuLodVertex order, set
// for the last LOD's vertices): a texel that the splat pass reads instead of the vertex's motion
// word and a row per mode. The far field plays at most kFarMotionModes modes of a vertex's block,
// its strongest (the last LOD's first), so the texel holds all the rows it plays.
struct GpuFarMotion {
    uvec4 rows; // xyz its first two rows as half floats (x: row 0's x and y, y: row 0's z and row 1's x, z: row
                // 1's y and z; zero past its rank), w its block's first far-field coordinate in a frame
                // (GpuClump::motion.x) | its far rank (at most kFarMotionModes) << kFarMotionRankShift
                // (far_splat.comp's farSampleDisplacement)
};
// The most modes of its block a far sample plays (field_packing.cpp, farSampleMotion).
MEADOW_CONST kFarMotionModes = 2;
// GpuFarSample::motion.w: the rank above the coordinate offset.
MEADOW_CONST kFarMotionRankShift = 24;
MEADOW_CONST kFarMotionOffsetMask = 0xffffff;

// One vertex of a clump's LOD mesh, pulled by gl_VertexIndex: the clump vertex at its mean pose
// and where its motion rows and light lie. LODs share clump vertices, so a vertex appears once
// per LOD that keeps it (with that LOD's rank).
struct GpuLodVertex {
    vec4 positionU; // xyz mean position (clump space), w texture u
    vec4 normalV;   // xyz mean normal, w texture v
    uvec4 motion;   // x first basis row in motionData, in rows of 4 floats (one per mode: x, y, z, 0), y
                    // the vertex's first coordinate in a frame of q, z clump-local vertex index (its
                    // light), w modes at this LOD (low 16 bits) and the LOD (high 16 bits)
};

// One instance's walk, integers only (16 bytes; std430 and std140 compatible). The vertex shader
// blends frame with blendFrom by the weight blendFramesLeft / blendFrames (1 right after a jump,
// so the first blended frame equals the natural continuation and nothing pops).
struct GpuMotionState {
    uint frame;           // the motion frame (column of q) to show
    uint blendFrom;       // the old path's frame while a jump is being blended
    uint blendFramesLeft; // 0: no blend; counts down by one per step
    uint counter;         // steps taken: the per-instance random stream position
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
    uint farInstances;  // drawn (in part, while crossfading) as the far field
    uint farSamples;    // splats those instances draw
    uint nearInstances; // LOD draws (an instance's one or two while crossfading) the near raster takes
    uint nearTriangles; // the triangles of those draws
    // Those draws per LOD (the LOD mesh bucket modulo the LOD count; lod_select.h's
    // kLodSelectCount of them), one per listed draw however many parts the near list holds it in:
    // with the mesh pass's per bucket (the draw commands' instanceCount), the draws of each LOD.
    uint nearPerLod[5];
    uint pad0;
};

// The splat pass's indirect dispatch (VkDispatchIndirectCommand) and the far list's length.
struct GpuFarDispatch {
    uint groupsX;
    uint groupsY;
    uint groupsZ;
    uint count; // far instances listed this frame
};

// The near raster's dispatches (near_raster.h): VkDispatchIndirectCommand, the near list's length and
// the shaded vertices it holds in the near raster's vertex buffer.
struct GpuNearDispatch {
    uint groupsX;
    uint groupsY;
    uint groupsZ;
    uint count;    // LOD draws listed this frame
    uint vertices; // vertices asked for (the listed draws' and any that did not fit)
    uint split;    // draws listed in parts, and any that were listed whole past the cap (near_raster.h)
    uint pad1, pad2;
};
#ifdef __cplusplus
} // namespace meadow::gpu
#endif
#undef MEADOW_CONST
#endif
