// Compile-time proof that the C++ view of the structs of shaders/shared that live in buffers
// (gpu_types.h, draw_instance.h) matches the std140/std430 layout the shaders see: every member's
// offset and every size. A failing assert means a member that the two languages lay out
// differently. (GpuLodParams and GpuLodChoice of lod_select.h live in registers only.)
#include "far_splat.h"
#include "gpu_types.h"
#include "lod_select.h"
// After gpu_types.h and motion_step.h, as draw_instance.h asks.
#include "draw_instance.h"
#include "motion_step.h"

#include <cstddef>
#include <vulkan/vulkan.h>

namespace meadow::gpu {

static_assert(sizeof(vec4) == 16 && sizeof(mat4) == 64 && sizeof(uvec4) == 16);

static_assert(offsetof(GpuFrame, viewProj) == 0);
static_assert(offsetof(GpuFrame, inverseViewProj) == 64);
static_assert(offsetof(GpuFrame, frustumPlanes) == 128);
static_assert(offsetof(GpuFrame, cameraPosition) == 224);
static_assert(offsetof(GpuFrame, sunDirection) == 240);
static_assert(offsetof(GpuFrame, sunColor) == 256);
static_assert(offsetof(GpuFrame, skyZenith) == 272);
static_assert(offsetof(GpuFrame, skyHorizon) == 288);
static_assert(offsetof(GpuFrame, counts) == 304);
static_assert(offsetof(GpuFrame, lodScreen) == 320);
static_assert(offsetof(GpuFrame, lodSwitchRadius) == 336);
static_assert(offsetof(GpuFrame, lodBand) == 352);
static_assert(offsetof(GpuFrame, windWave) == 368);
static_assert(offsetof(GpuFrame, windShape) == 384);
static_assert(offsetof(GpuFrame, windGust) == 400);
static_assert(offsetof(GpuFrame, motion) == 416);
static_assert(offsetof(GpuFrame, skyFrames) == 432);
static_assert(offsetof(GpuFrame, skyBlend) == 448);
static_assert(offsetof(GpuFrame, groundMap) == 464);
static_assert(sizeof(GpuFrame) == 624);

static_assert(offsetof(GpuClump, motion) == 0);
static_assert(offsetof(GpuClump, graph) == 16);
static_assert(offsetof(GpuClump, graphSizes) == 32);
static_assert(offsetof(GpuClump, light) == 48);
static_assert(offsetof(GpuClump, yawBins) == 64);
static_assert(offsetof(GpuClump, ground) == 80);
static_assert(offsetof(GpuClump, albedo) == 96);
static_assert(offsetof(GpuClump, far) == 112);
static_assert(offsetof(GpuClump, farGain) == 128);
static_assert(sizeof(GpuClump) == 208);
static_assert(sizeof(GpuClump) == 16 * kClumpTexels && offsetof(GpuClump, albedo) == 16 * kClumpAlbedoTexel);
static_assert(kFarGainSizes == 5 && kFarGainElevations == 4, "GpuClump::farGain holds 5 sizes of 4 elevations");
static_assert(offsetof(GpuFarSample, position) == 0);
static_assert(offsetof(GpuFarSample, data) == 16);
static_assert(sizeof(GpuFarSample) == 32);
static_assert(sizeof(GpuFarMotion) == 16);
static_assert(offsetof(GpuFarDispatch, groupsX) == 0);
static_assert(offsetof(GpuFarDispatch, groupsY) == 4);
static_assert(offsetof(GpuFarDispatch, groupsZ) == 8);
static_assert(offsetof(GpuFarDispatch, count) == 12);
static_assert(sizeof(GpuFarDispatch) == 16);

static_assert(offsetof(GpuLodVertex, positionU) == 0);
static_assert(offsetof(GpuLodVertex, normalV) == 16);
static_assert(offsetof(GpuLodVertex, motion) == 32);
static_assert(sizeof(GpuLodVertex) == 48);

static_assert(offsetof(GpuMotionState, frame) == 0);
static_assert(offsetof(GpuMotionState, blendFrom) == 4);
static_assert(offsetof(GpuMotionState, blendFramesLeft) == 8);
static_assert(offsetof(GpuMotionState, counter) == 12);
static_assert(sizeof(GpuMotionState) == 16);

static_assert(offsetof(GpuDrawInstance, positionScale) == 0);
static_assert(offsetof(GpuDrawInstance, pose) == 16);
static_assert(offsetof(GpuDrawInstance, offsets) == 32);
static_assert(sizeof(GpuDrawInstance) == 48);

static_assert(offsetof(GpuInstance, positionScale) == 0);
static_assert(offsetof(GpuInstance, yaw) == 16);
static_assert(offsetof(GpuInstance, boundingRadius) == 20);
static_assert(offsetof(GpuInstance, pad0) == 24);
static_assert(offsetof(GpuInstance, mesh) == 28);
static_assert(sizeof(GpuInstance) == 32);

static_assert(offsetof(GpuVertex, positionU) == 0);
static_assert(offsetof(GpuVertex, normalV) == 16);
static_assert(sizeof(GpuVertex) == 32);

static_assert(sizeof(GpuDrawIndexedCommand) == sizeof(VkDrawIndexedIndirectCommand) &&
              sizeof(GpuDrawIndexedCommand) == 20);
static_assert(offsetof(GpuDrawIndexedCommand, indexCount) == offsetof(VkDrawIndexedIndirectCommand, indexCount));
static_assert(offsetof(GpuDrawIndexedCommand, instanceCount) == offsetof(VkDrawIndexedIndirectCommand, instanceCount));
static_assert(offsetof(GpuDrawIndexedCommand, firstIndex) == offsetof(VkDrawIndexedIndirectCommand, firstIndex));
static_assert(offsetof(GpuDrawIndexedCommand, vertexOffset) == offsetof(VkDrawIndexedIndirectCommand, vertexOffset));
static_assert(offsetof(GpuDrawIndexedCommand, firstInstance) == offsetof(VkDrawIndexedIndirectCommand, firstInstance));

static_assert(offsetof(GpuCullStats, visibleInstances) == 0);
static_assert(offsetof(GpuCullStats, testedInstances) == 4);
static_assert(offsetof(GpuCullStats, farInstances) == 8);
static_assert(offsetof(GpuCullStats, farSamples) == 12);
static_assert(offsetof(GpuCullStats, nearInstances) == 16);
static_assert(offsetof(GpuCullStats, nearTriangles) == 20);
static_assert(offsetof(GpuCullStats, nearPerLod) == 24);
static_assert(sizeof(GpuCullStats::nearPerLod) / sizeof(uint) == kLodSelectCount); // a renderer's most LODs
static_assert(sizeof(GpuCullStats) == 48);
static_assert(offsetof(GpuNearDispatch, count) == 12);
static_assert(offsetof(GpuNearDispatch, vertices) == 16);
static_assert(sizeof(GpuNearDispatch) == 32);

} // namespace meadow::gpu
