#include "render/field_renderer.h"

#include "far_splat.h"
#include "near_raster.h"
#include "render/draw_ranges.h"
#include "render/field_packing.h"
#include "render/ground_light_map.h"

#include "vk/barriers.h"
#include "vk/context.h"
#include "vk/memory_budget.h"
#include "vk/timestamps.h"
#include "vk/vk_check.h"

#include "core/error.h"
#include "library/sky_day.h"
#include "render/cpu_driver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/packing.hpp>
#include <span>
#include <utility>

namespace meadow {

namespace {

constexpr double kMotionRate = 30.0; // motion frames per second (the simulation's frame rate)
constexpr VkFormat kGroundLightFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
// The blended sky backdrop: half floats, as the HDR image it is drawn into (filterable and storable on
// every Vulkan device).
constexpr VkFormat kSkyImageFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

// Luminance of the irradiance on an upward-facing surface from RGB sky SH of order 3: only the
// m = 0 terms of bands 0 and 1 and 2 contribute at +y (sh.h's basis).
float upwardIrradianceLuminance(std::span<const float> sh) {
    const double y00 = 0.282095, y10 = 0.488603, y20 = 0.315392 * 2.0;
    double e[3];
    for (int c = 0; c < 3; ++c)
        e[c] = M_PI * y00 * sh[3 * 0 + c] + 2.0 * M_PI / 3.0 * y10 * sh[3 * 2 + c] + M_PI / 4.0 * y20 * sh[3 * 6 + c];
    return float(std::max(0.0, 0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2]));
}

} // namespace

FieldClump staticFieldClump(const Mesh& mesh, uint32_t lodCount) {
    FieldClump clump;
    clump.mesh = mesh;
    FieldLod whole;
    whole.indices = mesh.indices;
    for (uint32_t v = 0; v < mesh.vertices.size(); ++v)
        whole.vertices.push_back(v);
    clump.lods.assign(lodCount, whole);
    clump.yawLow = 0.0f;
    clump.yawHigh = glm::two_pi<float>();
    clump.yawBins = 8;
    return clump;
}

namespace {
// createFieldRenderer's work after the checks of its input; may throw with `r` half made.
void fillFieldRenderer(Context& ctx, FieldRenderer& r, std::span<const FieldClump> clumps,
                       std::span<const gpu::GpuInstance> instances, const RgbaImage& atlas,
                       const FieldScenery& scenery);
} // namespace

uint32_t farSplatLanesFor(const VkPhysicalDeviceProperties& device) {
    // On an H200, 32 lanes (a warp per instance) against 2: the splat pass 3.93 -> 0.35 ms in the
    // default view at 1920x1080, 2.05 -> 0.41 ms at a million clumps (docs/BENCHMARKS.md).
    if (device.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU)
        return gpu::kFarGroupSize / gpu::kFarInstancesPerGroup;
    return gpu::kFarMaxLanes;
}

uint32_t nearWidthFor(const Context& ctx) {
    if (ctx.properties.deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU)
        return gpu::kNearGroupSize;
    // Two rows, so that the dispatch has twice as many rows as draws (near_raster.h).
    return std::clamp(2 * ctx.subgroupSize, 2u, 1024u);
}

size_t nearListCapacity(size_t instances) {
    // Two draws an instance (a crossfade's), and the parts of the draws listed in parts.
    return instances * 2 + size_t(gpu::kNearMaxSplitDraws) * (gpu::kNearDrawParts - 1);
}

bool nearTakesDraws(const Context& ctx) {
    return ctx.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
}

FieldRenderer createFieldRenderer(Context& ctx, std::span<const FieldClump> clumps,
                                  std::span<const gpu::GpuInstance> instances, const RgbaImage& atlas,
                                  const FieldScenery& scenery) {
    if (instances.empty())
        throw Error("the field has no instances to draw");
    if (clumps.empty())
        throw Error("the field has no clumps to draw");
    if (atlas.rgba.size() != size_t(atlas.width) * atlas.height * 4 || atlas.width == 0)
        throw Error("the field's texture atlas is empty or the wrong size");
    if (scenery.terrain.indices.empty() || glm::length(scenery.windDirection) < 1e-6f)
        throw Error("the field has no terrain or no wind direction");
    if (scenery.lodCount == 0 || scenery.lodCount > gpu::kLodSelectCount)
        throw Error("the field asks for " + std::to_string(scenery.lodCount) + " levels of detail per clump");
    const sky::SkyDay& day = scenery.sky;
    if (day.frames.empty() || day.shOrder != 3 || day.imageWidth == 0 || day.imageHeight == 0)
        throw Error("the field's sky has " + std::to_string(day.frames.size()) + " frames of SH order " +
                    std::to_string(day.shOrder) + "; the renderer needs at least one frame of order 3");
    if (clumps.size() > 0xffff)
        throw Error("the field has " + std::to_string(clumps.size()) + " clumps; the renderer draws at most 65535");
    for (size_t c = 0; c < clumps.size(); ++c)
        checkFieldClump(clumps[c], c, scenery.lodCount);
    if (scenery.farLanes > gpu::kFarMaxLanes || (scenery.farLanes & (scenery.farLanes - 1)) != 0)
        throw Error("the far field's " + std::to_string(scenery.farLanes) +
                    " threads per instance are not a power of two up to " + std::to_string(gpu::kFarMaxLanes));
    if (scenery.lod.farRadius > 0.0f) {
        if (scenery.lodCount != gpu::kLodSelectCount)
            throw Error("the far field follows LOD 4: it needs all five levels of detail");
        // A far radius at or above a mesh switch's band skips the LODs below it (lodMeshLevels):
        // any radius is a valid choice.
        if (!(scenery.farDensity > 0.0f && scenery.farDensity <= 64.0f))
            throw Error("the far field's density of " + std::to_string(scenery.farDensity) +
                        " samples per pixel is outside (0, 64]");
        for (size_t c = 0; c < clumps.size(); ++c)
            if (clumps[c].far.empty() || clumps[c].far.size() >= (1u << 24))
                throw Error("field clump " + std::to_string(c) + " has " + std::to_string(clumps[c].far.size()) +
                            " far-field samples; the far field needs 1 to 16777215 per clump (rebuild the library)");
    }

    if (scenery.nearWidth > 1024)
        throw Error("the near raster's workgroup width of " + std::to_string(scenery.nearWidth) +
                    " threads is above 1024");
    if (scenery.nearTakeDraws < -1 || scenery.nearTakeDraws > 1)
        throw Error("FieldScenery::nearTakeDraws is " + std::to_string(scenery.nearTakeDraws) +
                    "; it must be -1 (the device's way), 0 (dealt in turn) or 1 (taken)");
    FieldRenderer r;
    try {
        fillFieldRenderer(ctx, r, clumps, instances, atlas, scenery);
    } catch (...) {
        destroyFieldRenderer(ctx, r); // whatever was created before the error
        throw;
    }
    return r;
}

namespace {

// The passes' pipelines, and the mirror plane the field's mirrored instances reflect about.
void createPipelines(Context& ctx, FieldRenderer& r, const FieldScenery& scenery) {
    r.animate = createComputePipeline(ctx, "animate.comp");
    r.cull = createComputePipeline(ctx, "cull.comp");
    r.light = createComputePipeline(ctx, "light.comp", sizeof(uint32_t));
    r.lightGround = createComputePipeline(ctx, "light.comp", sizeof(uint32_t), 0, {1u}); // kGroundPoints
    r.tonemap = createComputePipeline(ctx, "tonemap.comp");
    GraphicsPipelineDesc skyDesc{"sky.vert", "sky.frag", kHdrFormat, kDepthFormat};
    skyDesc.depthWrite = false; // at infinite depth (0): drawn where the depth is still the clear value
    skyDesc.depthCompare = VK_COMPARE_OP_GREATER_OR_EQUAL;
    r.sky = createGraphicsPipeline(ctx, skyDesc);
    r.skyBlend = createComputePipeline(ctx, "sky_blend.comp");
    r.ground =
        createGraphicsPipeline(ctx, GraphicsPipelineDesc{"ground.vert", "ground.frag", kHdrFormat, kDepthFormat});
    GraphicsPipelineDesc instanceDesc{"instance.vert", "instance.frag", kHdrFormat, kDepthFormat};
    instanceDesc.pushConstantSize = sizeof(glm::vec4);
    r.instance = createGraphicsPipeline(ctx, instanceDesc);
    r.groundMap = createComputePipeline(ctx, "ground_map.comp");
    const uint32_t farLanes = scenery.farLanes > 0 ? scenery.farLanes : farSplatLanesFor(ctx.properties);
    r.farSplat = createComputePipeline(ctx, "far_splat.comp", sizeof(glm::vec4), gpu::kFarInstancesPerGroup * farLanes);
    r.farSplatLodView = createComputePipeline(ctx, "far_splat.comp", sizeof(glm::vec4),
                                              gpu::kFarInstancesPerGroup * farLanes, {1u}); // kLodView
    r.farResolve = createComputePipeline(ctx, "far_resolve.comp");
    r.farResolveLdrOnly = createComputePipeline(ctx, "far_resolve.comp", 0, 0, {0u}); // kStoreHdr false
    const uint32_t nearWidth = scenery.nearWidth > 0 ? scenery.nearWidth : nearWidthFor(ctx);
    const uint32_t take = scenery.nearTakeDraws < 0 ? uint32_t(nearTakesDraws(ctx)) : uint32_t(scenery.nearTakeDraws);
    r.nearVertices = createComputePipeline(ctx, "near_vertices.comp", sizeof(glm::vec4), nearWidth, {take});
    r.nearRaster = createComputePipeline(ctx, "near_raster.comp", 0, nearWidth, {0u, take}); // kLodView, kTakeDraws
    r.nearRasterLodView = createComputePipeline(ctx, "near_raster.comp", 0, nearWidth, {1u, take});
    const glm::vec2 wind = glm::normalize(scenery.windDirection);
    r.mirrorNormal = glm::vec4(-wind.y, 0.0f, wind.x, 0.0f);
    r.windAzimuth = std::atan2(wind.x, wind.y); // light/sh.h: from +z towards +x
}

// Every range a draw reads, against the buffer it reads it from, before anything is drawn.
void checkDraws(const FieldPacking& p) {
    std::vector<std::string> rangeProblems =
        checkDrawRanges(p.draws, {p.indices, p.lodVertices.size(), p.visibleCount, p.drawCapacity});
    if (!rangeProblems.empty())
        throw Error("the field's draws read outside their buffers: " + rangeProblems.front() + " (" +
                    std::to_string(rangeProblems.size()) + " problems)");
}

// Everything the field puts in device memory, checked against what the device has before the
// first allocation: a field too large fails here with the figures, not with a device lost later.
void checkMemory(Context& ctx, const FieldPacking& p, size_t instanceCount, size_t clumpCount, const RgbaImage& atlas,
                 const FieldScenery& scenery, const GroundLightMapLists& ground) {
    const VkExtent2D mapSize = ground.size;
    const sky::SkyDay& day = scenery.sky;
    const uint64_t perInstanceBytes =
        sizeof(gpu::GpuInstance) + sizeof(gpu::GpuMotionState) + sizeof(float) + sizeof(gpu::GpuDrawInstance);
    const uint64_t neededBytes =
        uint64_t(instanceCount) * perInstanceBytes + uint64_t(p.visibleCount) * sizeof(uint32_t) +
        p.clumps.size() * sizeof(gpu::GpuClump) + p.lodVertices.size() * sizeof(gpu::GpuLodVertex) +
        p.indices.size() * sizeof(uint32_t) + (p.motionData.size() + p.transfer.size()) * sizeof(float) +
        p.motionGraph.size() * sizeof(uint32_t) + p.lightVec4s * 16 +
        skyFrameFloats(day) * day.frames.size() * sizeof(float) +
        2 * p.draws.size() * sizeof(gpu::GpuDrawIndexedCommand) + uint64_t(atlas.width) * atlas.height * 8 +
        uint64_t(mapSize.width) * mapSize.height * 8 + uint64_t(day.imageWidth) * day.imageHeight * 8 +
        scenery.terrain.vertices.size() * sizeof(gpu::GpuVertex) + scenery.terrain.indices.size() * sizeof(uint32_t) +
        p.farSamples.size() * sizeof(gpu::GpuFarSample) + p.farMotion.size() * sizeof(gpu::GpuFarMotion) +
        uint64_t(instanceCount) * 8 + sizeof(gpu::GpuFarDispatch) + ground.texelStart.size() * sizeof(uint32_t) +
        ground.entries.size() * sizeof(glm::uvec2) +
        (scenery.nearRaster ? uint64_t(gpu::kNearMaxVertices) * 32 + uint64_t(instanceCount) * 32 : 0);
    checkFieldMemory(ctx, neededBytes,
                     "the field (" + std::to_string(instanceCount) + " instances of " + std::to_string(clumpCount) +
                         " meshes)");
}

// The field's buffers, filled with what packField made; the atlas, the sampler and the terrain.
void createBuffers(Context& ctx, FieldRenderer& r, const FieldPacking& p, std::span<const gpu::GpuInstance> instances,
                   const GroundLightMapLists& ground, const std::vector<float>& skyData, const RgbaImage& atlas,
                   const FieldScenery& scenery) {
    const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    // Buffers also read as texel buffers (the splat pass, the ground light map).
    const VkBufferUsageFlags texels = VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
    auto deviceBuffer = [&](Buffer& buffer, const void* data, size_t bytes, VkBufferUsageFlags extra = 0) {
        buffer = createBuffer(ctx, std::max<size_t>(bytes, 16), storage | extra, MemoryUse::Device);
        if (data && bytes > 0)
            uploadToBuffer(ctx, buffer, data, bytes);
    };
    r.frameUniforms = createBuffer(ctx, sizeof(gpu::GpuFrame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUse::Upload);
    deviceBuffer(r.instances, instances.data(), instances.size_bytes());
    deviceBuffer(r.motionStates, p.states.data(), p.states.size() * sizeof(gpu::GpuMotionState),
                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    const std::vector<float> lodStart(instances.size(), 0.0f);
    deviceBuffer(r.lodState, lodStart.data(), lodStart.size() * sizeof(float), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    deviceBuffer(r.clumps, p.clumps.data(), p.clumps.size() * sizeof(gpu::GpuClump),
                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT | texels); // read back by the CPU-driven path
    deviceBuffer(r.drawInstances, nullptr, instances.size() * sizeof(gpu::GpuDrawInstance),
                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT | texels);
    deviceBuffer(r.lodVertices, p.lodVertices.data(), p.lodVertices.size() * sizeof(gpu::GpuLodVertex),
                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT | texels);
    deviceBuffer(r.motionData, p.motionData.data(), p.motionData.size() * sizeof(float),
                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT | texels);
    deviceBuffer(r.motionGraph, p.motionGraph.data(), p.motionGraph.size() * sizeof(uint32_t));
    deviceBuffer(r.transfer, p.transfer.data(), p.transfer.size() * sizeof(float), texels);
    deviceBuffer(r.vertexLight, nullptr, size_t(p.lightVec4s) * 16, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | texels);
    deviceBuffer(r.skyData, skyData.data(), skyData.size() * sizeof(float));
    r.indices = createBuffer(ctx, p.indices.size() * sizeof(uint32_t),
                             VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT | // read back by tests (draw_ranges.h)
                                 texels,                            // the near raster
                             MemoryUse::Device);
    uploadToBuffer(ctx, r.indices, p.indices.data(), r.indices.size);
    VkDeviceSize drawBytes = p.draws.size() * sizeof(gpu::GpuDrawIndexedCommand);
    deviceBuffer(r.drawCommands, p.draws.data(), drawBytes,
                 VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    r.drawCommandTemplate = createBuffer(
        ctx, drawBytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Device);
    uploadToBuffer(ctx, r.drawCommandTemplate, p.draws.data(), drawBytes);
    deviceBuffer(r.visibleList, nullptr, size_t(p.visibleCount) * sizeof(uint32_t),
                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT | texels);
    deviceBuffer(r.farSamples, p.farSamples.data(), p.farSamples.size() * sizeof(gpu::GpuFarSample),
                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT | texels);
    deviceBuffer(r.farMotion, p.farMotion.data(), p.farMotion.size() * sizeof(gpu::GpuFarMotion),
                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT | texels);
    if (r.farField) {
        r.farSampleTexels =
            createTexelBufferView(ctx, r.farSamples, VK_FORMAT_R32G32B32A32_UINT, 16, "the far samples");
        r.farMotionTexels =
            createTexelBufferView(ctx, r.farMotion, VK_FORMAT_R32G32B32A32_UINT, 16, "the far samples' motion");
    }
    // Read by the mesh pass's vertex shader (all of these), the near raster's vertex pass and the
    // splat pass.
    r.visibleTexels = createTexelBufferView(ctx, r.visibleList, VK_FORMAT_R32_UINT, 4, "the visible list");
    r.drawInstanceTexels =
        createTexelBufferView(ctx, r.drawInstances, VK_FORMAT_R32G32B32A32_UINT, 16, "the draw records");
    r.clumpTexels = createTexelBufferView(ctx, r.clumps, VK_FORMAT_R32G32B32A32_UINT, 16, "the clumps");
    r.lodVertexTexels = createTexelBufferView(ctx, r.lodVertices, VK_FORMAT_R32G32B32A32_UINT, 16, "the LOD vertices");
    r.motionTexels = createTexelBufferView(ctx, r.motionData, VK_FORMAT_R32_SFLOAT, 4, "the motion data");
    r.motionRowTexels =
        createTexelBufferView(ctx, r.motionData, VK_FORMAT_R32G32B32A32_SFLOAT, 16, "the motion basis rows");
    if (r.nearRasterOn)
        r.indexTexels = createTexelBufferView(ctx, r.indices, VK_FORMAT_R32_UINT, 4, "the LOD meshes' indices");
    r.transferTexels = createTexelBufferView(ctx, r.transfer, VK_FORMAT_R32G32B32A32_SFLOAT, 16, "the light transfer");
    r.vertexLightTexels =
        createTexelBufferView(ctx, r.vertexLight, VK_FORMAT_R32G32B32A32_UINT, 16, "the vertex light");
    deviceBuffer(r.groundTexelStart, ground.texelStart.data(), ground.texelStart.size() * sizeof(uint32_t), texels);
    deviceBuffer(r.groundEntries, ground.entries.data(), ground.entries.size() * sizeof(glm::uvec2), texels);
    r.groundTexelStartTexels =
        createTexelBufferView(ctx, r.groundTexelStart, VK_FORMAT_R32_UINT, 4, "the ground light map's texels");
    r.groundEntryTexels =
        createTexelBufferView(ctx, r.groundEntries, VK_FORMAT_R32G32_UINT, 8, "the ground light map's lists");
    // (motionData, farSamples, farMotion, farList and farDispatch are read back by the splat pass's
    // reference test.)
    deviceBuffer(r.farList, nullptr, instances.size() * 2 * sizeof(uint32_t), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    deviceBuffer(r.farDispatch, nullptr, sizeof(gpu::GpuFarDispatch),
                 VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    // The near raster (near_raster.h): an instance's two LOD draws while it crossfades, at most two
    // entries each; where each bucket's mesh lies (read by the cull pass, so always there).
    std::vector<glm::uvec4> nearMeshes(p.draws.size());
    for (size_t b = 0; b < p.draws.size(); ++b)
        nearMeshes[b] = glm::uvec4(uint32_t(p.draws[b].vertexOffset), p.meshVertices[b], p.draws[b].firstIndex,
                                   p.draws[b].indexCount);
    deviceBuffer(r.nearMeshes, nearMeshes.data(), nearMeshes.size() * sizeof(glm::uvec4),
                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT); // read back by the CPU-driven path
    deviceBuffer(r.nearList, nullptr, r.nearRasterOn ? nearListCapacity(instances.size()) * sizeof(glm::uvec4) : 0,
                 VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    deviceBuffer(r.nearDispatch, nullptr, sizeof(gpu::GpuNearDispatch),
                 VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    deviceBuffer(r.nearTaken, nullptr, 2 * sizeof(uint32_t), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    deviceBuffer(r.nearShaded, nullptr, r.nearRasterOn ? size_t(gpu::kNearMaxVertices) * 2 * sizeof(glm::uvec4) : 0,
                 texels);
    if (r.nearRasterOn)
        r.nearShadedTexels =
            createTexelBufferView(ctx, r.nearShaded, VK_FORMAT_R32G32B32A32_UINT, 16, "the near raster's vertices");
    deviceBuffer(r.stats, nullptr, sizeof(gpu::GpuCullStats), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
    r.statsReadback =
        createBuffer(ctx, sizeof(gpu::GpuCullStats) + drawBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
    const std::vector<uint8_t> zeros(r.statsReadback.size, 0);
    writeMapped(ctx, r.statsReadback, zeros.data(), zeros.size());
    const std::vector<uint16_t> atlasTexels = packAtlas(atlas);
    r.atlas = createTexture(ctx, {atlas.width, atlas.height}, VK_FORMAT_R16G16B16A16_SFLOAT, atlasTexels.data(),
                            4 * sizeof(uint16_t));
    r.sampler = createLinearSampler(ctx);
    r.atlasSampler = createLinearSampler(ctx, atlasMaxLod(atlas.width));
    r.pointSampler = createNearestSampler(ctx);
    r.skyImage =
        createImage2D(ctx, {scenery.sky.imageWidth, scenery.sky.imageHeight}, kSkyImageFormat,
                      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    r.skySampler = createPanoramaSampler(ctx);

    deviceBuffer(r.terrainVertices, scenery.terrain.vertices.data(),
                 scenery.terrain.vertices.size() * sizeof(gpu::GpuVertex));
    r.terrainIndices =
        createBuffer(ctx, scenery.terrain.indices.size() * sizeof(uint32_t),
                     VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Device);
    uploadToBuffer(ctx, r.terrainIndices, scenery.terrain.indices.data(), r.terrainIndices.size);
    r.terrainIndexCount = uint32_t(scenery.terrain.indices.size());
}

void fillFieldRenderer(Context& ctx, FieldRenderer& r, std::span<const FieldClump> clumps,
                       std::span<const gpu::GpuInstance> instances, const RgbaImage& atlas,
                       const FieldScenery& scenery) {
    r.instanceCount = static_cast<uint32_t>(instances.size());
    r.clumpCount = static_cast<uint32_t>(clumps.size());
    r.lodCount = scenery.lodCount;
    r.meshCount = r.clumpCount * r.lodCount;
    r.lodParams = scenery.lod;
    r.farDensity = scenery.farDensity;
    r.farAsLod0 = scenery.farAsLod0;
    r.farField = scenery.lod.farRadius > 0.0f;
    r.nearRasterOn = scenery.nearRaster && r.lodCount > 1;
    r.skyDay = scenery.sky;
    createPipelines(ctx, r, scenery);

    const FieldPacking packed = packField(clumps, instances, r.lodCount);
    r.meshTriangles = packed.meshTriangles;
    r.lightVertices = packed.lightVertices;
    r.lightGroundPoints = packed.lightGroundPoints;
    r.drawCapacity = packed.drawCapacity;
    r.lodVertexCount = packed.lodVertices.size();
    r.visibleCount = packed.visibleCount;
    const GroundLightMapLayout map = groundLightMapLayout(clumps, instances);
    r.groundRect = map.rect;
    const GroundLightMapLists ground = groundLightMapLists(
        groundCasters(packed.clumps, instances, map, glm::vec2(r.mirrorNormal.x, r.mirrorNormal.z)), map.size);
    checkDraws(packed);
    checkMemory(ctx, packed, instances.size(), clumps.size(), atlas, scenery, ground);

    r.groundLight =
        createImage2D(ctx, map.size, kGroundLightFormat,
                      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    const std::vector<float> skyData = packSkyDay(scenery.sky);
    r.brightestIrradiance = 0.0f;
    for (const sky::SkyFrame& frame : scenery.sky.frames)
        r.brightestIrradiance = std::max(r.brightestIrradiance, upwardIrradianceLuminance(frame.sh));
    createBuffers(ctx, r, packed, instances, ground, skyData, atlas, scenery);
}

} // namespace

void destroyFieldRenderer(Context& ctx, FieldRenderer& r) {
    for (Pipeline* p : {&r.animate, &r.cull, &r.light, &r.lightGround, &r.tonemap, &r.sky, &r.skyBlend, &r.ground,
                        &r.instance, &r.groundMap, &r.farSplat, &r.farSplatLodView, &r.farResolve, &r.farResolveLdrOnly,
                        &r.nearVertices, &r.nearRaster, &r.nearRasterLodView})
        destroyPipeline(ctx, *p);
    for (VkBufferView* view :
         {&r.transferTexels, &r.farSampleTexels, &r.farMotionTexels, &r.visibleTexels, &r.drawInstanceTexels,
          &r.clumpTexels, &r.lodVertexTexels, &r.motionTexels, &r.motionRowTexels, &r.vertexLightTexels,
          &r.groundTexelStartTexels, &r.groundEntryTexels, &r.indexTexels, &r.nearShadedTexels})
        if (*view) {
            vkDestroyBufferView(ctx.device, *view, nullptr);
            *view = VK_NULL_HANDLE;
        }
    for (Buffer* b : {&r.frameUniforms, &r.instances,   &r.motionStates,  &r.lodState,        &r.drawInstances,
                      &r.clumps,        &r.lodVertices, &r.indices,       &r.motionData,      &r.motionGraph,
                      &r.transfer,      &r.vertexLight, &r.skyData,       &r.drawCommands,    &r.drawCommandTemplate,
                      &r.visibleList,   &r.stats,       &r.statsReadback, &r.terrainVertices, &r.terrainIndices,
                      &r.farSamples,    &r.farMotion,   &r.farList,       &r.farDispatch,     &r.groundTexelStart,
                      &r.groundEntries, &r.nearList,    &r.nearDispatch,  &r.nearMeshes,      &r.nearShaded,
                      &r.nearTaken})
        destroyBuffer(ctx, *b);
    destroyImage(ctx, r.atlas);
    destroyImage(ctx, r.groundLight);
    destroyImage(ctx, r.skyImage);
    if (r.cpuDriver)
        destroyCpuDriver(ctx, *r.cpuDriver);
    if (r.sampler)
        vkDestroySampler(ctx.device, r.sampler, nullptr);
    if (r.atlasSampler)
        vkDestroySampler(ctx.device, r.atlasSampler, nullptr);
    if (r.pointSampler)
        vkDestroySampler(ctx.device, r.pointSampler, nullptr);
    if (r.skySampler)
        vkDestroySampler(ctx.device, r.skySampler, nullptr);
    r = FieldRenderer{};
}

gpu::GpuFrame frameUniforms(const FieldRenderer& r, const FrameState& state) {
    if (state.width == 0 || state.height == 0)
        throw Error("a frame of size " + std::to_string(state.width) + "x" + std::to_string(state.height));
    gpu::GpuFrame f = makeCameraUniforms(state.camera, state.width, state.height, r.instanceCount);
    f.counts.y = r.meshCount;
    f.counts.w = r.lodCount;
    f.lodSwitchRadius = glm::vec4(r.lodParams.switchRadius[0], r.lodParams.switchRadius[1], r.lodParams.switchRadius[2],
                                  r.lodParams.switchRadius[3]);
    const bool far = r.farField;
    f.lodBand =
        glm::vec4(r.lodParams.band, r.lodParams.jitter, r.lodParams.hysteresis, far ? r.lodParams.farRadius : 0.0f);
    f.lodScreen.y = r.farDensity;
    f.lodScreen.z = float(state.width);
    f.lodScreen.w = float(state.height);

    // Wind: waves and gusts travel along the direction the clumps were simulated in.
    const WindState& w = state.wind;
    const glm::vec2 dir(r.mirrorNormal.z, -r.mirrorNormal.x);
    f.windWave = glm::vec4(dir.x, dir.y, w.baseLevel, w.waveAmplitude);
    f.windShape = glm::vec4(1.0f / w.wavelength, float(w.waveSpeed / w.wavelength / kMotionRate), w.gustAmplitude,
                            1.0f / w.gustSize);
    f.windGust = glm::vec4(float(w.gustSpeed / w.gustSize / kMotionRate), 0.0f, 0.0f, 0.0f);

    // Motion: one step per 1/30 s of scene time since the frame the states show.
    const int64_t tick = int64_t(std::floor(std::max(state.seconds, 0.0) * kMotionRate));
    uint32_t steps = 0;
    if (r.lastTick >= 0 && tick > r.lastTick)
        steps = uint32_t(std::min<int64_t>(tick - r.lastTick, gpu::kMaxMotionStepsPerFrame));
    f.motion =
        gpu::uvec4(uint32_t(tick - int64_t(steps) + 1), steps, state.debugView,
                   (far && r.farAsLod0 ? gpu::kFrameFarAsLod0 : 0u) | (r.nearRasterOn ? gpu::kFrameNearRaster : 0u));
    f.counts.z = uint32_t(tick);

    // Sky: the two frames of the day around the hour; the sun from them; exposure from the
    // light on open ground, so a dim evening is shown brighter but night stays dark.
    const sky::SkyBlend blend = sky::skyBlendAt(r.skyDay, state.hours);
    const sky::SkyFrame& a = r.skyDay.frames[blend.first];
    const sky::SkyFrame& b = r.skyDay.frames[blend.second];
    const float t = float(blend.weight);
    f.skyFrames = gpu::uvec4(blend.first, blend.second, r.skyDay.imageWidth, r.skyDay.imageHeight);
    f.skyBlend = glm::vec4(t, r.windAzimuth, 0.0f, 0.0f);
    f.groundMap = r.groundRect;
    const glm::vec3 sun = glm::mix(a.sunDirection, b.sunDirection, t);
    f.sunDirection = glm::vec4(glm::length(sun) > 1e-6f ? glm::normalize(sun) : glm::vec3(0, 1, 0), 0.0f);
    f.sunColor = glm::vec4(glm::mix(a.sunRadiance, b.sunRadiance, t), float(sky::kSunAngularRadius));
    std::array<float, 27> sh; // on the stack: this runs every frame
    for (size_t i = 0; i < sh.size(); ++i)
        sh[i] = (1.0f - t) * a.sh[i] + t * b.sh[i];
    for (size_t i = 0; i < 9; ++i)
        f.skySh[i] = glm::vec4(sh[3 * i], sh[3 * i + 1], sh[3 * i + 2], 0.0f);
    const float irradiance = std::max(upwardIrradianceLuminance(sh), 0.02f * r.brightestIrradiance);
    // White paper lying on the ground at 0.6 of the tone curve's linear range.
    const float exposure = irradiance > 0.0f ? 0.6f * float(M_PI) / irradiance : 1.0f;
    f.skyZenith = glm::vec4(0.0f, 0.0f, 0.0f, exposure);
    // The haze the ground fades into: the backdrop's mean over its row just above the horizon.
    glm::vec3 horizon(0.0f);
    const uint32_t width = r.skyDay.imageWidth, row = r.skyDay.imageHeight / 2 - 1;
    for (uint32_t x = 0; x < width; ++x)
        for (int c = 0; c < 3; ++c) {
            const size_t i = 3 * (size_t(row) * width + x) + c;
            horizon[c] += ((1.0f - t) * a.image[i] + t * b.image[i]) / float(width);
        }
    f.skyHorizon = glm::vec4(horizon, 0.0f);
    return f;
}

void updateFrame(Context& ctx, FieldRenderer& r, const FrameState& state) {
    const gpu::GpuFrame f = frameUniforms(r, state);
    r.lastTick = int64_t(f.counts.z);
    // The light pass (and the ground light map) follow the sky in steps of 1/32 of the blend
    // between two sky frames (9 s of daylight with the full preset's 5-minute frames): finer
    // steps change no pixel that anyone could see, and each costs a pass over every clump vertex.
    r.lightThisFrame = !r.lightValid || f.skyFrames.x != r.litSky.x || f.skyFrames.y != r.litSky.y ||
                       std::abs(f.skyBlend.x - r.litWeight) >= 1.0f / 32.0f;
    if (r.lightThisFrame) {
        r.litSky = f.skyFrames;
        r.litWeight = f.skyBlend.x;
        r.lightValid = true;
    }
    // The sky image is the exact blend the frame asks for: made again whenever that changes.
    r.skyBlendThisFrame =
        f.skyFrames.x != r.blendedSky.x || f.skyFrames.y != r.blendedSky.y || f.skyBlend.x != r.blendedWeight;
    if (r.skyBlendThisFrame) {
        r.blendedSky = f.skyFrames;
        r.blendedWeight = f.skyBlend.x;
    }
    r.cullThisFrame = !(state.freezeCulling && r.culledOnce);
    if (r.cpuDriver && r.cullThisFrame)
        cpuDriverUpdate(ctx, *r.cpuDriver, f);
    r.culledOnce = true;
    writeMapped(ctx, r.frameUniforms, &f, sizeof(f));
    r.lastFrame = f;
}

void advanceMotion(Context& ctx, FieldRenderer& r, const FrameState& state) {
    const int64_t target = int64_t(std::floor(std::max(state.seconds, 0.0) * kMotionRate));
    if (r.lastTick < 0)
        r.lastTick = 0; // the states as created show tick 0
    while (r.lastTick < target) {
        FrameState step = state;
        const int64_t next = std::min<int64_t>(r.lastTick + gpu::kMaxMotionStepsPerFrame, target);
        step.seconds = (double(next) + 0.5) / kMotionRate;
        const gpu::GpuFrame f = frameUniforms(r, step);
        writeMapped(ctx, r.frameUniforms, &f, sizeof(f));
        submitAndWait(ctx, [&](VkCommandBuffer cmd) {
            barrier(cmd, access::kVertexShaderRead | access::kComputeReadWrite, access::kComputeReadWrite);
            bindPipeline(ctx, cmd, r.animate, {r.frameUniforms, r.instances, r.clumps, r.motionGraph, r.motionStates});
            dispatchCovering(cmd, r.animate, r.instanceCount);
            barrier(cmd, access::kComputeReadWrite, access::kComputeReadWrite | access::kVertexShaderRead);
        });
        r.lastTick = next;
    }
}

namespace {

// The visibility buffer and the resolve run with the far field or the near raster. Both run on both
// paths: the CPU-driven one uploads the lists and dispatches that the cull pass would write
// (cpu_driver.h).
bool farRuns(const FieldRenderer& r) {
    return r.farField || r.nearRasterOn;
}

void markPass(GpuTimer* timer, VkCommandBuffer cmd, const char* pass) {
    if (timer)
        markTimestamp(*timer, cmd, pass);
}

// Resets the draws' instance counts (from the template) and the statistics, or, on the CPU-driven
// path, records the host's uploads of what animate and cull would write. The previous frame read
// them as indirect commands, in the vertex shader and as copy sources.
void recordReset(FieldRenderer& r, VkCommandBuffer cmd) {
    barrier(cmd,
            access::kIndirectRead | access::kVertexShaderRead | access::kFragmentShaderRead |
                access::kComputeReadWrite | access::kTransferRead,
            access::kTransferWrite | access::kComputeReadWrite);
    if (r.cpuDriver) {
        if (r.cullThisFrame)
            cpuDriverRecordUploads(*r.cpuDriver, r, cmd);
    } else if (r.cullThisFrame) {
        VkBufferCopy drawsRegion{0, 0, r.drawCommands.size};
        vkCmdCopyBuffer(cmd, r.drawCommandTemplate.buffer, r.drawCommands.buffer, 1, &drawsRegion);
        vkCmdFillBuffer(cmd, r.stats.buffer, 0, sizeof(gpu::GpuCullStats), 0);
        // The far list empty: no workgroups (x and the count 0), y and z 1.
        vkCmdFillBuffer(cmd, r.farDispatch.buffer, 0, sizeof(uint32_t), 0);
        vkCmdFillBuffer(cmd, r.farDispatch.buffer, sizeof(uint32_t), 2 * sizeof(uint32_t), 1);
        vkCmdFillBuffer(cmd, r.farDispatch.buffer, 3 * sizeof(uint32_t), sizeof(uint32_t), 0);
        vkCmdFillBuffer(cmd, r.nearDispatch.buffer, 0, sizeof(uint32_t), 0);
        vkCmdFillBuffer(cmd, r.nearDispatch.buffer, sizeof(uint32_t), 2 * sizeof(uint32_t), 1);
        vkCmdFillBuffer(cmd, r.nearDispatch.buffer, 3 * sizeof(uint32_t), 3 * sizeof(uint32_t),
                        0); // count, vertices, split
    }
}

// Motion: the states step at the wind of this frame (the previous frame's vertex shader read
// them: ordered by the reset's barrier).
void recordAnimatePass(Context& ctx, FieldRenderer& r, VkCommandBuffer cmd) {
    if (r.cpuDriver)
        return;
    bindPipeline(ctx, cmd, r.animate, {r.frameUniforms, r.instances, r.clumps, r.motionGraph, r.motionStates});
    dispatchCovering(cmd, r.animate, r.instanceCount);
}

// The cull pass reads the motion states animate wrote (for the draw records) and the reset
// draws; its barrier also hands the reset and the CPU-driven uploads to the draws.
void recordCullPass(Context& ctx, FieldRenderer& r, VkCommandBuffer cmd) {
    barrier(cmd, access::kTransferWrite | access::kComputeReadWrite,
            access::kComputeReadWrite | access::kIndirectRead | access::kVertexShaderRead | access::kTransferRead);
    if (!r.cullThisFrame || r.cpuDriver)
        return;
    bindPipeline(ctx, cmd, r.cull,
                 {r.frameUniforms, r.instances, r.drawCommands, r.visibleList, r.stats, r.lodState, r.clumps,
                  r.motionStates, r.drawInstances, r.farList, r.farDispatch, r.nearList, r.nearDispatch, r.nearMeshes});
    dispatchCovering(cmd, r.cull, r.instanceCount);
}

// Light: every clump vertex and variant onto the sky, when the sky changed. Its barrier hands the
// compute passes' results (the cull's draws and draw records, the light) to everything drawn,
// including the compute passes that read the light as texels (sampled reads).
void recordLightPass(Context& ctx, FieldRenderer& r, VkCommandBuffer cmd) {
    if (r.lightThisFrame) {
        // The previous frame's passes read the vertex light this pass writes again. (On lavapipe
        // the barrier also ends the command stream's batch, so that the cull pass's timestamp is
        // written before these dispatches run and not after them.)
        barrier(cmd, access::kVertexShaderRead | access::kFragmentShaderRead | access::kComputeRead,
                access::kComputeWrite);
        // The clumps' vertices, then their ground grids' points, each through a pipeline of its own
        // (light.comp's kGroundPoints). The dispatches write disjoint parts of vertexLight.
        const std::pair<Pipeline*, const std::vector<uint32_t>*> passes[] = {{&r.light, &r.lightVertices},
                                                                             {&r.lightGround, &r.lightGroundPoints}};
        for (const auto& [pipeline, threads] : passes) {
            bindPipeline(ctx, cmd, *pipeline,
                         {r.frameUniforms, r.clumps, Binding(r.transferTexels), r.skyData, r.vertexLight});
            for (uint32_t c = 0; c < r.clumpCount; ++c) {
                if ((*threads)[c] == 0)
                    continue;
                pushConstants(ctx, cmd, *pipeline, &c, sizeof(uint32_t));
                dispatchCovering(cmd, *pipeline, (*threads)[c]);
            }
        }
    }
    barrier(cmd, access::kComputeReadWrite,
            access::kIndirectRead | access::kVertexShaderRead | access::kFragmentShaderRead | access::kComputeRead |
                access::kComputeSampledRead);
}

// The ground light map, with the light: every texel made again from the light pass's ratios
// (ground_map.comp, a thread per texel); left ready for the terrain's fragment shader.
void recordGroundLightMap(Context& ctx, FieldRenderer& r, VkCommandBuffer cmd) {
    if (!r.lightThisFrame)
        return;
    imageBarrier(cmd, r.groundLight.image, VK_IMAGE_ASPECT_COLOR_BIT, access::kFragmentShaderRead,
                 VK_IMAGE_LAYOUT_UNDEFINED, access::kComputeWrite, VK_IMAGE_LAYOUT_GENERAL);
    bindPipeline(ctx, cmd, r.groundMap,
                 {Binding(r.groundTexelStartTexels), Binding(r.groundEntryTexels), Binding(r.vertexLightTexels),
                  Binding(r.groundLight.view, VK_IMAGE_LAYOUT_GENERAL)});
    dispatchCovering(cmd, r.groundMap, r.groundLight.extent.width, r.groundLight.extent.height);
    imageBarrier(cmd, r.groundLight.image, VK_IMAGE_ASPECT_COLOR_BIT, access::kComputeWrite, VK_IMAGE_LAYOUT_GENERAL,
                 access::kFragmentShaderRead, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

// This frame's sky backdrop, when the sky moved: the two sky frames around the hour blended into the
// sky image (sky_blend.comp, a thread per texel), left ready for sky.frag. The previous frame's sky
// draw read it; every texel is written again, so it starts from UNDEFINED.
void recordSkyBlend(Context& ctx, FieldRenderer& r, VkCommandBuffer cmd) {
    if (!r.skyBlendThisFrame)
        return;
    imageBarrier(cmd, r.skyImage.image, VK_IMAGE_ASPECT_COLOR_BIT, access::kFragmentShaderRead,
                 VK_IMAGE_LAYOUT_UNDEFINED, access::kComputeWrite, VK_IMAGE_LAYOUT_GENERAL);
    bindPipeline(ctx, cmd, r.skyBlend, {r.frameUniforms, r.skyData, Binding(r.skyImage.view, VK_IMAGE_LAYOUT_GENERAL)});
    dispatchCovering(cmd, r.skyBlend, r.skyImage.extent.width, r.skyImage.extent.height);
    imageBarrier(cmd, r.skyImage.image, VK_IMAGE_ASPECT_COLOR_BIT, access::kComputeWrite, VK_IMAGE_LAYOUT_GENERAL,
                 access::kFragmentShaderRead, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

// The HDR image and depth: near to far, so that depth testing rejects as much as it can before
// shading, the clumps LOD by LOD (LOD 0 is nearest; buckets are clump-major, so LOD l's are every
// lodCount-th command), then the terrain, then the sky where nothing else was drawn.
void recordDrawPass(Context& ctx, FieldRenderer& r, VkCommandBuffer cmd, const RenderTargets& t) {
    // The previous frame's tonemap read the HDR image and wrote the LDR image; the contents are
    // not needed again, so both start from UNDEFINED.
    imageBarrier(cmd, t.hdr.image, VK_IMAGE_ASPECT_COLOR_BIT, access::kComputeRead | access::kTransferRead,
                 VK_IMAGE_LAYOUT_UNDEFINED, access::kColorAttachmentWrite, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    imageBarrier(cmd, t.depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, access::kDepthAttachment | access::kComputeSampledRead,
                 VK_IMAGE_LAYOUT_UNDEFINED, access::kDepthAttachment, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);

    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = t.hdr.view;
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE; // the sky covers every pixel
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = t.depth.view;
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = farRuns(r) ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE; // the splats test it
    depth.clearValue.depthStencil = {0.0f, 0}; // reversed Z: 0 is infinitely far
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, t.extent};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachments = &color;
    rendering.pDepthAttachment = &depth;
    vkCmdBeginRendering(cmd, &rendering);

    VkViewport viewport{0.0f, 0.0f, float(t.extent.width), float(t.extent.height), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, t.extent};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);

    bindPipeline(ctx, cmd, r.instance,
                 {r.frameUniforms, Binding(r.visibleTexels), Binding(r.drawInstanceTexels), Binding(r.clumpTexels),
                  Binding(r.lodVertexTexels), Binding(r.motionTexels), Binding(r.vertexLightTexels),
                  Binding(r.atlas.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, r.atlasSampler),
                  Binding(r.motionRowTexels)});
    pushConstants(ctx, cmd, r.instance, &r.mirrorNormal, sizeof(glm::vec4));
    vkCmdBindIndexBuffer(cmd, r.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
    for (uint32_t lod = 0; lod < r.lodCount; ++lod)
        vkCmdDrawIndexedIndirect(cmd, r.drawCommands.buffer, lod * sizeof(gpu::GpuDrawIndexedCommand), r.clumpCount,
                                 r.lodCount * sizeof(gpu::GpuDrawIndexedCommand));

    bindPipeline(ctx, cmd, r.ground,
                 {r.frameUniforms, r.terrainVertices,
                  Binding(r.groundLight.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, r.sampler)});
    vkCmdBindIndexBuffer(cmd, r.terrainIndices.buffer, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, r.terrainIndexCount, 1, 0, 0, 0);

    bindPipeline(ctx, cmd, r.sky,
                 {r.frameUniforms, Binding(r.skyImage.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, r.skySampler)});
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
}

// Whether the frame being recorded shows the LOD view (FrameState::debugView): its near raster and
// splat pass then bind the pipelines that paint it (kLodView).
bool lodViewShown(const FieldRenderer& r) {
    return r.lastFrame.motion.z == gpu::kDebugViewLod;
}

// The far field (far_splat.h): the visibility buffer emptied and every far instance's samples
// splatted into it. The winners are resolved against the meshes' depth by the tone map pass
// (far_resolve.comp), which reads the depth in SHADER_READ_ONLY layout and the HDR image in GENERAL.
void recordFarPass(Context& ctx, FieldRenderer& r, VkCommandBuffer cmd, const RenderTargets& t, GpuTimer* timer) {
    imageBarrier(cmd, t.depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, access::kDepthAttachment,
                 VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, access::kComputeSampledRead,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    imageBarrier(cmd, t.hdr.image, VK_IMAGE_ASPECT_COLOR_BIT, access::kColorAttachmentWrite,
                 VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, access::kComputeReadWrite, VK_IMAGE_LAYOUT_GENERAL);
    // The previous frame's resolve read the visibility buffer (as texels).
    barrier(cmd, access::kComputeSampledRead, access::kTransferWrite);
    vkCmdFillBuffer(cmd, t.farVisibility.buffer, 0, VK_WHOLE_SIZE, gpu::kFarEmpty);
    if (r.nearRasterOn) // the previous frame's near raster took its draws with these counters
        vkCmdFillBuffer(cmd, r.nearTaken.buffer, 0, VK_WHOLE_SIZE, 0);
    barrier(cmd, access::kTransferWrite, access::kComputeReadWrite);
    if (r.nearRasterOn) {
        // Every vertex of the listed draws moved and lit once, then their triangles drawn.
        bindPipeline(ctx, cmd, r.nearVertices,
                     {r.frameUniforms, r.nearList, r.nearDispatch, r.drawInstances, r.nearMeshes,
                      Binding(r.lodVertexTexels), Binding(r.motionTexels), Binding(r.vertexLightTexels), r.nearShaded,
                      Binding(r.motionRowTexels), r.nearTaken});
        pushConstants(ctx, cmd, r.nearVertices, &r.mirrorNormal, sizeof(glm::vec4));
        vkCmdDispatchIndirect(cmd, r.nearDispatch.buffer, 0);
        markPass(timer, cmd, "nearVertices");
        barrier(cmd, access::kComputeWrite, access::kComputeSampledRead);
        bindPipeline(ctx, cmd, lodViewShown(r) ? r.nearRasterLodView : r.nearRaster,
                     {r.frameUniforms, r.nearList, r.nearDispatch, r.drawInstances, r.clumps, r.nearMeshes,
                      Binding(r.indexTexels), Binding(r.nearShadedTexels),
                      Binding(r.atlas.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, r.atlasSampler), t.farVisibility,
                      r.nearTaken});
        vkCmdDispatchIndirect(cmd, r.nearDispatch.buffer, 0);
        markPass(timer, cmd, "nearRaster");
        if (!r.farField)
            return;
        // Both passes merge into the visibility buffer with atomics, in any order; the barrier
        // only orders the two dispatches' writes for the validation layer's hazard tracking.
        barrier(cmd, access::kComputeReadWrite, access::kComputeReadWrite);
    }
    Pipeline& splat = lodViewShown(r) ? r.farSplatLodView : r.farSplat;
    bindPipeline(ctx, cmd, splat,
                 {r.frameUniforms, r.farList, r.farDispatch, r.drawInstances, r.clumps, Binding(r.farSampleTexels),
                  Binding(r.motionTexels), Binding(r.vertexLightTexels), t.farVisibility, r.instances,
                  Binding(r.farMotionTexels)});
    pushConstants(ctx, cmd, splat, &r.mirrorNormal, sizeof(glm::vec4));
    vkCmdDispatchIndirect(cmd, r.farDispatch.buffer, 0);
}

// HDR -> LDR: the draw's image, read in GENERAL layout by a compute pass that writes the LDR one.
// With the far field, that pass is the resolve (far_resolve.comp): it first writes the far field's
// winners that lie nearer than the meshes into the HDR image.
void recordTonemapPass(Context& ctx, FieldRenderer& r, VkCommandBuffer cmd, const RenderTargets& t) {
    imageBarrier(cmd, t.ldr.image, VK_IMAGE_ASPECT_COLOR_BIT, access::kComputeReadWrite | access::kTransferRead,
                 VK_IMAGE_LAYOUT_UNDEFINED, access::kComputeWrite, VK_IMAGE_LAYOUT_GENERAL);
    if (farRuns(r)) {
        // The HDR image is in GENERAL since the far pass; wait for the splat pass's atomics, whose
        // words the resolve reads as texels.
        barrier(cmd, access::kComputeReadWrite, access::kComputeReadWrite | access::kComputeSampledRead);
        Pipeline& resolve = t.hdrContents == HdrContents::Frame ? r.farResolve : r.farResolveLdrOnly;
        bindPipeline(ctx, cmd, resolve,
                     {r.frameUniforms, Binding(t.farVisibilityTexels), Binding(t.hdr.view, VK_IMAGE_LAYOUT_GENERAL),
                      Binding(t.depth.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, r.pointSampler),
                      Binding(t.ldr.view, VK_IMAGE_LAYOUT_GENERAL)});
        dispatchCovering(cmd, resolve, t.extent.width, t.extent.height);
    } else {
        imageBarrier(cmd, t.hdr.image, VK_IMAGE_ASPECT_COLOR_BIT, access::kColorAttachmentWrite,
                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, access::kComputeRead, VK_IMAGE_LAYOUT_GENERAL);
        bindPipeline(ctx, cmd, r.tonemap,
                     {r.frameUniforms, Binding(t.hdr.view, VK_IMAGE_LAYOUT_GENERAL),
                      Binding(t.ldr.view, VK_IMAGE_LAYOUT_GENERAL)});
        dispatchCovering(cmd, r.tonemap, t.extent.width, t.extent.height);
    }
}

// The cull's statistics and the draws' instance counts, copied where the host reads them
// (readFieldStats) once the frame is done.
void recordStatsReadback(FieldRenderer& r, VkCommandBuffer cmd) {
    barrier(cmd, access::kComputeReadWrite | access::kIndirectRead, access::kTransferRead);
    VkBufferCopy statsRegion{0, 0, sizeof(gpu::GpuCullStats)};
    vkCmdCopyBuffer(cmd, r.stats.buffer, r.statsReadback.buffer, 1, &statsRegion);
    VkBufferCopy drawsBack{0, sizeof(gpu::GpuCullStats), r.drawCommands.size};
    vkCmdCopyBuffer(cmd, r.drawCommands.buffer, r.statsReadback.buffer, 1, &drawsBack);
    barrier(cmd, access::kTransferWrite, access::kHostRead);
}

} // namespace

void recordFieldFrame(Context& ctx, FieldRenderer& r, VkCommandBuffer cmd, const RenderTargets& t, GpuTimer* timer) {
    if (timer)
        beginTimestamps(ctx, *timer, cmd);
    recordReset(r, cmd);
    recordAnimatePass(ctx, r, cmd);
    markPass(timer, cmd, "animate");
    recordCullPass(ctx, r, cmd);
    markPass(timer, cmd, "cull");
    recordLightPass(ctx, r, cmd);
    markPass(timer, cmd, "light");
    recordGroundLightMap(ctx, r, cmd);
    markPass(timer, cmd, "groundMap");
    recordSkyBlend(ctx, r, cmd);
    markPass(timer, cmd, "sky");
    recordDrawPass(ctx, r, cmd, t);
    markPass(timer, cmd, "draw");
    if (farRuns(r)) {
        recordFarPass(ctx, r, cmd, t, timer);
        if (r.farField)
            markPass(timer, cmd, "farSplat");
    }
    recordTonemapPass(ctx, r, cmd, t);
    markPass(timer, cmd, "tonemap"); // with the far field, the resolve pass (far_resolve.comp)
    recordStatsReadback(r, cmd);
}

std::vector<uint32_t> FieldStats::drawsPerLod() const {
    std::vector<uint32_t> perLod = nearPerLod;
    for (size_t m = 0; m < visiblePerMesh.size() && !perLod.empty(); ++m)
        perLod[m % perLod.size()] += visiblePerMesh[m];
    return perLod;
}

FieldStats readFieldStats(const FieldRenderer& r) {
    gpu::GpuCullStats s;
    std::memcpy(&s, r.statsReadback.mapped(), sizeof(s));
    FieldStats out;
    out.visibleInstances = s.visibleInstances;
    out.testedInstances = s.testedInstances;
    out.farInstances = s.farInstances;
    out.farSamples = s.farSamples;
    out.nearInstances = s.nearInstances;
    out.nearTriangles = s.nearTriangles;
    out.nearPerLod.assign(s.nearPerLod, s.nearPerLod + r.lodCount); // at most kLodSelectCount (createFieldRenderer)
    std::vector<gpu::GpuDrawIndexedCommand> draws(r.meshCount);
    std::memcpy(draws.data(), static_cast<const char*>(r.statsReadback.mapped()) + sizeof(s),
                draws.size() * sizeof(gpu::GpuDrawIndexedCommand));
    out.trianglesDrawn = r.terrainIndexCount / 3 + 1; // terrain and sky
    for (uint32_t m = 0; m < r.meshCount; ++m) {
        out.visiblePerMesh.push_back(draws[m].instanceCount);
        out.trianglesDrawn += uint64_t(draws[m].instanceCount) * r.meshTriangles[m];
    }
    return out;
}

namespace {

// The RGB of a half-float RGBA image that the fragment shaders read.
std::vector<glm::vec3> readHalfRgb(Context& ctx, const Image& image) {
    const std::vector<uint8_t> bytes =
        readImageBytes(ctx, image, VK_IMAGE_ASPECT_COLOR_BIT, 8, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                       access::kFragmentShaderRead);
    std::vector<uint16_t> halves(bytes.size() / 2);
    std::memcpy(halves.data(), bytes.data(), bytes.size());
    std::vector<glm::vec3> rgb(halves.size() / 4);
    for (size_t i = 0; i < rgb.size(); ++i)
        for (int c = 0; c < 3; ++c)
            rgb[i][c] = glm::unpackHalf1x16(halves[4 * i + c]);
    return rgb;
}

} // namespace

std::vector<glm::vec3> readGroundLightMap(Context& ctx, const FieldRenderer& r) {
    return readHalfRgb(ctx, r.groundLight);
}

std::vector<glm::vec3> readSkyImage(Context& ctx, const FieldRenderer& r) {
    return readHalfRgb(ctx, r.skyImage);
}

} // namespace meadow
