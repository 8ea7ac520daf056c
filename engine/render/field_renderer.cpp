#include "render/field_renderer.h"

#include "vk/barriers.h"
#include "vk/context.h"
#include "vk/timestamps.h"
#include "vk/vk_check.h"

#include <algorithm>
#include <cstring>

namespace meadow {

FieldRenderer createFieldRenderer(Context& ctx, std::span<const Mesh> meshes,
                                  std::span<const gpu::GpuInstance> instances, const RgbaImage& atlas,
                                  const FieldScenery& scenery) {
    if (instances.empty())
        throw Error("the field has no instances to draw");
    if (meshes.empty())
        throw Error("the field has no meshes to draw");
    if (atlas.rgba.size() != size_t(atlas.width) * atlas.height * 4 || atlas.width == 0)
        throw Error("the field's texture atlas is empty or the wrong size");
    if (scenery.terrain.indices.empty() || glm::length(scenery.windDirection) < 1e-6f)
        throw Error("the field has no terrain or no wind direction");
    if (scenery.lodCount == 0 || scenery.lodCount > gpu::kLodSelectCount || meshes.size() % scenery.lodCount != 0)
        throw Error("the field has " + std::to_string(meshes.size()) + " meshes for " +
                    std::to_string(scenery.lodCount) + " levels of detail per clump");
    FieldRenderer r;
    r.instanceCount = static_cast<uint32_t>(instances.size());
    r.meshCount = static_cast<uint32_t>(meshes.size());
    r.lodCount = scenery.lodCount;
    r.lodParams = scenery.lod;
    const uint32_t clumpCount = r.meshCount / r.lodCount;

    r.cull = createComputePipeline(ctx, "cull.comp");
    r.tonemap = createComputePipeline(ctx, "tonemap.comp");
    GraphicsPipelineDesc skyDesc{"sky.vert", "sky.frag", kHdrFormat, kDepthFormat};
    skyDesc.depthTest = false;
    skyDesc.depthWrite = false;
    r.sky = createGraphicsPipeline(ctx, skyDesc);
    r.ground =
        createGraphicsPipeline(ctx, GraphicsPipelineDesc{"ground.vert", "ground.frag", kHdrFormat, kDepthFormat});
    GraphicsPipelineDesc instanceDesc{"instance.vert", "instance.frag", kHdrFormat, kDepthFormat};
    instanceDesc.pushConstantSize = sizeof(glm::vec4);
    r.instance = createGraphicsPipeline(ctx, instanceDesc);
    const glm::vec2 wind = glm::normalize(scenery.windDirection);
    r.mirrorNormal = glm::vec4(-wind.y, 0.0f, wind.x, 0.0f);

    // All meshes share one vertex and one index buffer; each gets one indirect draw whose
    // instance range in the visible list holds room for all of that mesh's instances.
    std::vector<gpu::GpuVertex> vertices;
    std::vector<uint32_t> indices;
    std::vector<gpu::GpuDrawIndexedCommand> draws(meshes.size());
    for (size_t m = 0; m < meshes.size(); ++m) {
        draws[m].indexCount = uint32_t(meshes[m].indices.size());
        draws[m].firstIndex = uint32_t(indices.size());
        draws[m].vertexOffset = int32_t(vertices.size());
        vertices.insert(vertices.end(), meshes[m].vertices.begin(), meshes[m].vertices.end());
        indices.insert(indices.end(), meshes[m].indices.begin(), meshes[m].indices.end());
        r.meshTriangles.push_back(uint32_t(meshes[m].indices.size() / 3));
    }
    // Each bucket's range holds every instance of its clump: an instance lands in at most one
    // range per LOD of its clump (two while crossfading, never twice in one).
    std::vector<uint32_t> perClump(clumpCount, 0);
    for (const gpu::GpuInstance& inst : instances) {
        if (inst.mesh >= clumpCount)
            throw Error("a field instance names clump " + std::to_string(inst.mesh) + " of " +
                        std::to_string(clumpCount));
        perClump[inst.mesh]++;
    }
    uint32_t first = 0;
    for (size_t m = 0; m < meshes.size(); ++m) {
        draws[m].firstInstance = first;
        first += perClump[m / r.lodCount];
    }

    const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    r.frameUniforms = createBuffer(ctx, sizeof(gpu::GpuFrame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUse::Upload);
    r.instances = createBuffer(ctx, instances.size_bytes(), storage, MemoryUse::Device);
    r.vertices = createBuffer(ctx, vertices.size() * sizeof(gpu::GpuVertex), storage, MemoryUse::Device);
    r.indices = createBuffer(ctx, indices.size() * sizeof(uint32_t),
                             VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Device);
    VkDeviceSize drawBytes = draws.size() * sizeof(gpu::GpuDrawIndexedCommand);
    r.drawCommands =
        createBuffer(ctx, drawBytes, storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                     MemoryUse::Device);
    r.drawCommandTemplate = createBuffer(
        ctx, drawBytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Device);
    r.visibleList = createBuffer(ctx, size_t(first) * sizeof(uint32_t), storage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                 MemoryUse::Device);
    r.lodState = createBuffer(ctx, instances.size() * sizeof(float), storage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                              MemoryUse::Device);
    const std::vector<float> lodStart(instances.size(), 0.0f);
    uploadToBuffer(ctx, r.lodState, lodStart.data(), r.lodState.size);
    r.stats =
        createBuffer(ctx, sizeof(gpu::GpuCullStats), storage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Device);
    r.statsReadback =
        createBuffer(ctx, sizeof(gpu::GpuCullStats) + drawBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
    std::memset(r.statsReadback.mapped(), 0, r.statsReadback.size);

    uploadToBuffer(ctx, r.instances, instances.data(), instances.size_bytes());
    uploadToBuffer(ctx, r.vertices, vertices.data(), r.vertices.size);
    uploadToBuffer(ctx, r.indices, indices.data(), r.indices.size);
    uploadToBuffer(ctx, r.drawCommandTemplate, draws.data(), drawBytes);
    uploadToBuffer(ctx, r.drawCommands, draws.data(), drawBytes);
    r.atlas = createTexture(ctx, {atlas.width, atlas.height}, VK_FORMAT_R8G8B8A8_SRGB, atlas.rgba.data());
    r.sampler = createLinearSampler(ctx);

    r.terrainVertices =
        createBuffer(ctx, scenery.terrain.vertices.size() * sizeof(gpu::GpuVertex), storage, MemoryUse::Device);
    r.terrainIndices =
        createBuffer(ctx, scenery.terrain.indices.size() * sizeof(uint32_t),
                     VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Device);
    uploadToBuffer(ctx, r.terrainVertices, scenery.terrain.vertices.data(), r.terrainVertices.size);
    uploadToBuffer(ctx, r.terrainIndices, scenery.terrain.indices.data(), r.terrainIndices.size);
    r.terrainIndexCount = uint32_t(scenery.terrain.indices.size());
    return r;
}

void destroyFieldRenderer(Context& ctx, FieldRenderer& r) {
    for (Pipeline* p : {&r.cull, &r.tonemap, &r.sky, &r.ground, &r.instance})
        destroyPipeline(ctx, *p);
    for (Buffer* b : {&r.frameUniforms, &r.instances, &r.vertices, &r.indices, &r.drawCommands, &r.drawCommandTemplate,
                      &r.visibleList, &r.stats, &r.statsReadback, &r.terrainVertices, &r.terrainIndices, &r.lodState})
        destroyBuffer(ctx, *b);
    destroyImage(ctx, r.atlas);
    if (r.sampler)
        vkDestroySampler(ctx.device, r.sampler, nullptr);
    r = FieldRenderer{};
}

void updateFrameUniforms(FieldRenderer& r, const gpu::GpuFrame& frame) {
    gpu::GpuFrame f = frame;
    f.counts.y = r.meshCount;
    f.counts.w = r.lodCount;
    f.lodSwitchRadius = glm::vec4(r.lodParams.switchRadius[0], r.lodParams.switchRadius[1], r.lodParams.switchRadius[2],
                                  r.lodParams.switchRadius[3]);
    f.lodBand = glm::vec4(r.lodParams.band, r.lodParams.jitter, r.lodParams.hysteresis, 0.0f);
    std::memcpy(r.frameUniforms.mapped(), &f, sizeof(f));
}

void recordFieldFrame(Context& ctx, FieldRenderer& r, VkCommandBuffer cmd, const RenderTargets& t, GpuTimer* timer) {
    if (timer)
        beginTimestamps(ctx, *timer, cmd);

    // Reset the draws' instance counts (from the template) and the statistics. The previous frame
    // read them as indirect commands, in the vertex shader and as copy sources.
    barrier(cmd, access::kIndirectRead | access::kVertexShaderRead | access::kComputeReadWrite | access::kTransferRead,
            access::kTransferWrite);
    VkBufferCopy drawsRegion{0, 0, r.drawCommands.size};
    vkCmdCopyBuffer(cmd, r.drawCommandTemplate.buffer, r.drawCommands.buffer, 1, &drawsRegion);
    vkCmdFillBuffer(cmd, r.stats.buffer, 0, sizeof(gpu::GpuCullStats), 0);
    barrier(cmd, access::kTransferWrite, access::kComputeReadWrite);

    bindPipeline(ctx, cmd, r.cull, {r.frameUniforms, r.instances, r.drawCommands, r.visibleList, r.stats, r.lodState});
    dispatchCovering(cmd, r.cull, r.instanceCount);
    if (timer)
        markTimestamp(*timer, cmd, "cull");

    barrier(cmd, access::kComputeReadWrite, access::kIndirectRead | access::kVertexShaderRead);
    // The previous frame's tonemap read the HDR image and wrote the LDR image; the contents are
    // not needed again, so both start from UNDEFINED.
    imageBarrier(cmd, t.hdr.image, VK_IMAGE_ASPECT_COLOR_BIT, access::kComputeRead | access::kTransferRead,
                 VK_IMAGE_LAYOUT_UNDEFINED, access::kColorAttachmentWrite, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    imageBarrier(cmd, t.depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, access::kDepthAttachment, VK_IMAGE_LAYOUT_UNDEFINED,
                 access::kDepthAttachment, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);

    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = t.hdr.view;
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE; // the sky covers every pixel
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = t.depth.view;
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
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

    bindPipeline(ctx, cmd, r.sky, {r.frameUniforms});
    vkCmdDraw(cmd, 3, 1, 0, 0);

    bindPipeline(ctx, cmd, r.ground, {r.frameUniforms, r.terrainVertices});
    vkCmdBindIndexBuffer(cmd, r.terrainIndices.buffer, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, r.terrainIndexCount, 1, 0, 0, 0);

    bindPipeline(ctx, cmd, r.instance,
                 {r.frameUniforms, r.instances, r.visibleList, r.vertices, r.lodState,
                  Binding(r.atlas.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, r.sampler)});
    vkCmdPushConstants(cmd, r.instance.layout, r.instance.pushConstantStages, 0, sizeof(glm::vec4), &r.mirrorNormal);
    vkCmdBindIndexBuffer(cmd, r.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexedIndirect(cmd, r.drawCommands.buffer, 0, r.meshCount, sizeof(gpu::GpuDrawIndexedCommand));
    vkCmdEndRendering(cmd);
    if (timer)
        markTimestamp(*timer, cmd, "draw");

    imageBarrier(cmd, t.hdr.image, VK_IMAGE_ASPECT_COLOR_BIT, access::kColorAttachmentWrite,
                 VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, access::kComputeRead, VK_IMAGE_LAYOUT_GENERAL);
    imageBarrier(cmd, t.ldr.image, VK_IMAGE_ASPECT_COLOR_BIT, access::kComputeReadWrite | access::kTransferRead,
                 VK_IMAGE_LAYOUT_UNDEFINED, access::kComputeWrite, VK_IMAGE_LAYOUT_GENERAL);
    bindPipeline(
        ctx, cmd, r.tonemap,
        {r.frameUniforms, Binding(t.hdr.view, VK_IMAGE_LAYOUT_GENERAL), Binding(t.ldr.view, VK_IMAGE_LAYOUT_GENERAL)});
    dispatchCovering(cmd, r.tonemap, t.extent.width, t.extent.height);
    if (timer)
        markTimestamp(*timer, cmd, "tonemap");

    barrier(cmd, access::kComputeReadWrite | access::kIndirectRead, access::kTransferRead);
    VkBufferCopy statsRegion{0, 0, sizeof(gpu::GpuCullStats)};
    vkCmdCopyBuffer(cmd, r.stats.buffer, r.statsReadback.buffer, 1, &statsRegion);
    VkBufferCopy drawsBack{0, sizeof(gpu::GpuCullStats), r.drawCommands.size};
    vkCmdCopyBuffer(cmd, r.drawCommands.buffer, r.statsReadback.buffer, 1, &drawsBack);
    barrier(cmd, access::kTransferWrite, access::kHostRead);
}

FieldStats readFieldStats(const FieldRenderer& r) {
    gpu::GpuCullStats s;
    std::memcpy(&s, r.statsReadback.mapped(), sizeof(s));
    FieldStats out;
    out.visibleInstances = s.visibleInstances;
    out.testedInstances = s.testedInstances;
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

} // namespace meadow
