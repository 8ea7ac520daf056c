#include "render/cpu_driver.h"

#include "core/error.h"
#include "far_splat.h"
#include "near_raster.h"
#include "render/cull_reference.h"
#include "vk/context.h"
#include "wind_field.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <tbb/parallel_for.h>

namespace meadow {

struct CpuDriver {
    std::vector<gpu::GpuInstance> instances;
    std::vector<MotionGraph> graphs;         // per clump (static clumps: none)
    std::vector<gpu::MotionTables> tables;   // views of graphs
    std::vector<gpu::GpuMotionState> states; // what the GPU states would hold
    std::vector<float> lodX;
    std::vector<gpu::GpuClump> clumps;
    std::vector<gpu::GpuDrawIndexedCommand> drawTemplate;
    uint32_t lodCount = 1;
    // Staging, host-visible: per-instance draw records, draw commands, statistics, the visible
    // list, the far list and the far field's dispatch, in this order.
    Buffer staging;
    size_t recordsAt = 0, drawsAt = 0, statsAt = 0, visibleAt = 0, farListAt = 0, farDispatchAt = 0;
    size_t nearListAt = 0, nearDispatchAt = 0;
    std::vector<glm::uvec4> nearMeshes;      // per bucket, as the near raster reads them (near_raster.h)
    uint32_t farEntries = 0;                 // written this frame
    uint32_t nearEntries = 0;                // written this frame
    uint32_t visibleEntries = 0;             // written this frame
    std::vector<VkBufferCopy> visibleCopies; // this frame's used part of each bucket's range
    std::vector<VkBufferCopy> recordCopies;  // this frame's visible instances' records, in runs
    uint64_t recordBytes = 0;
};

void enableCpuDriver(Context& ctx, FieldRenderer& r, std::span<const FieldClump> clumps,
                     std::span<const gpu::GpuInstance> instances) {
    if (instances.size() != r.instanceCount || clumps.size() != r.clumpCount)
        throw Error("the CPU-driven path needs the clumps and instances the renderer was created with");
    auto d = std::make_unique<CpuDriver>();
    d->instances.assign(instances.begin(), instances.end());
    d->lodCount = r.lodCount;
    d->graphs.resize(clumps.size());
    d->tables.resize(clumps.size());
    for (size_t c = 0; c < clumps.size(); ++c)
        if (clumps[c].motion.frames > 0) {
            d->graphs[c] = clumps[c].graph;
            d->tables[c] = makeMotionTables(d->graphs[c]);
        }
    d->states.resize(instances.size());
    readbackBuffer(ctx, r.motionStates, d->states.data(), d->states.size() * sizeof(gpu::GpuMotionState));
    d->lodX.assign(instances.size(), 0.0f);
    d->clumps.resize(clumps.size());
    readbackBuffer(ctx, r.clumps, d->clumps.data(), d->clumps.size() * sizeof(gpu::GpuClump));
    d->drawTemplate.resize(r.meshCount);
    readbackBuffer(ctx, r.drawCommandTemplate, d->drawTemplate.data(),
                   d->drawTemplate.size() * sizeof(gpu::GpuDrawIndexedCommand));
    d->recordsAt = 0;
    d->drawsAt = d->recordsAt + instances.size() * sizeof(gpu::GpuDrawInstance);
    d->statsAt = d->drawsAt + d->drawTemplate.size() * sizeof(gpu::GpuDrawIndexedCommand);
    d->visibleAt = d->statsAt + sizeof(gpu::GpuCullStats);
    d->farListAt = d->visibleAt + r.visibleList.size;
    d->farDispatchAt = d->farListAt + instances.size() * 2 * sizeof(uint32_t);
    d->nearMeshes.resize(r.meshCount);
    readbackBuffer(ctx, r.nearMeshes, d->nearMeshes.data(), d->nearMeshes.size() * sizeof(glm::uvec4));
    d->nearListAt = d->farDispatchAt + sizeof(gpu::GpuFarDispatch);
    d->nearDispatchAt = d->nearListAt + (r.nearRasterOn ? nearListCapacity(instances.size()) * sizeof(glm::uvec4) : 0);
    d->staging = createBuffer(ctx, d->nearDispatchAt + sizeof(gpu::GpuNearDispatch), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                              MemoryUse::Upload);
    r.cpuDriver = std::move(d);
}

void cpuDriverUpdate(Context& ctx, CpuDriver& d, const gpu::GpuFrame& frame) {
    // Motion: every instance steps at the wind of its place (independent per instance).
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, d.instances.size(), 4096), [&](const tbb::blocked_range<size_t>& range) {
            for (size_t i = range.begin(); i < range.end(); ++i) {
                const uint32_t c = d.instances[i].mesh;
                if (d.tables[c].levelCount == 0) { // static: holds its one frame
                    d.states[i].counter += frame.motion.y;
                    continue;
                }
                for (uint32_t s = 0; s < frame.motion.y; ++s) {
                    const float level = gpu::windLevelAt(frame, d.instances[i].positionScale.x,
                                                         d.instances[i].positionScale.z, frame.motion.x + s);
                    gpu::motionStep(d.tables[c], d.states[i], gpu::windTargetLevel(level, d.tables[c].levelCount),
                                    uint32_t(i));
                }
            }
        });

    // Cull and LOD, straight into the staging draw commands and visible list.
    // Every write into the staging buffer goes through hostWriteAt, which counts it.
    const size_t drawBytes = d.drawTemplate.size() * sizeof(gpu::GpuDrawIndexedCommand);
    auto* draws = static_cast<gpu::GpuDrawIndexedCommand*>(hostWriteAt(ctx, d.staging, d.drawsAt, drawBytes));
    d.recordCopies.clear();
    d.recordBytes = 0;
    auto record = [&](uint32_t i, float x, bool lodChoice) {
        const gpu::GpuInstance& inst = d.instances[i];
        const VkDeviceSize at = VkDeviceSize(i) * sizeof(gpu::GpuDrawInstance);
        *static_cast<gpu::GpuDrawInstance*>(
            hostWriteAt(ctx, d.staging, d.recordsAt + at, sizeof(gpu::GpuDrawInstance))) =
            gpu::makeDrawInstance(inst, d.clumps[inst.mesh], d.states[i], x, lodChoice);
        if (!d.recordCopies.empty() && d.recordCopies.back().dstOffset + d.recordCopies.back().size == at)
            d.recordCopies.back().size += sizeof(gpu::GpuDrawInstance);
        else
            d.recordCopies.push_back({d.recordsAt + at, at, sizeof(gpu::GpuDrawInstance)});
        d.recordBytes += sizeof(gpu::GpuDrawInstance);
    };
    std::memcpy(draws, d.drawTemplate.data(), drawBytes);
    gpu::GpuCullStats stats{};
    d.visibleEntries = 0;
    auto append = [&](uint32_t bucket, uint32_t entry) {
        const VkDeviceSize slot = VkDeviceSize(draws[bucket].firstInstance + draws[bucket].instanceCount++);
        *static_cast<uint32_t*>(hostWriteAt(ctx, d.staging, d.visibleAt + slot * sizeof(uint32_t), sizeof(uint32_t))) =
            entry;
        ++d.visibleEntries;
    };
    // The far field's list, as cull.comp's appendFar writes it: the entry (the fade bit on the second
    // draw of a crossfade) and the samples its projected surface wants.
    d.farEntries = 0;
    const bool farAsLod0 = (frame.motion.w & gpu::kFrameFarAsLod0) != 0u;
    auto appendFar = [&](uint32_t entry, const gpu::GpuInstance& inst) {
        const float scale = std::abs(inst.positionScale.w);
        const glm::vec3 center =
            glm::vec3(inst.positionScale) + glm::vec3(0.0f, inst.boundingRadius * scale * 0.5f, 0.0f);
        const glm::vec3 d3 = center - glm::vec3(frame.cameraPosition);
        const float dist = std::max(std::sqrt(d3.x * d3.x + d3.y * d3.y + d3.z * d3.z), 1e-3f);
        const glm::mat4& vp = frame.viewProj;
        const float depth = std::max(vp[0][3] * center.x + vp[1][3] * center.y + vp[2][3] * center.z + vp[3][3], 1e-3f);
        const gpu::GpuClump& clump = d.clumps[inst.mesh];
        float area;
        std::memcpy(&area, &clump.far.z, sizeof area);
        const uint32_t count =
            gpu::farSampleCount(area * scale * scale, gpu::farPixelsPerMetre(frame.lodScreen.x, depth, dist),
                                frame.lodScreen.y, clump.far.y);
        const uint32_t item[2] = {entry, count};
        std::memcpy(hostWriteAt(ctx, d.staging, d.farListAt + size_t(d.farEntries) * sizeof item, sizeof item), item,
                    sizeof item);
        ++d.farEntries;
        ++stats.farInstances;
        stats.farSamples += count;
    };
    // The near raster's list, as cull.comp's appendLod writes it: the entry, its bucket, its vertices'
    // place and its subpixel grid, or the draw pass when the near raster does not take it.
    d.nearEntries = 0;
    uint32_t nearVertices = 0, nearSplit = 0;
    auto appendLod = [&](uint32_t bucket, uint32_t entry, int sub) {
        if (sub > 0) {
            const glm::uvec4 mesh = d.nearMeshes[bucket];
            const uint32_t start = nearVertices;
            nearVertices += mesh.y;
            if (uint64_t(start) + mesh.y <= gpu::kNearMaxVertices) {
                const uint32_t parts =
                    gpu::nearSplitsDraw(sub) && nearSplit++ < gpu::kNearMaxSplitDraws ? gpu::kNearDrawParts : 1u;
                for (uint32_t part = 0; part < parts; ++part) {
                    const glm::uvec4 item(entry, bucket, start, gpu::nearListedWord(sub, part, parts));
                    std::memcpy(
                        hostWriteAt(ctx, d.staging, d.nearListAt + size_t(d.nearEntries) * sizeof item, sizeof item),
                        &item, sizeof item);
                    ++d.nearEntries;
                }
                ++stats.nearInstances;
                stats.nearTriangles += mesh.w / 3u;
                ++stats.nearPerLod[bucket % d.lodCount];
                return;
            }
        }
        append(bucket, entry);
    };
    for (uint32_t i = 0; i < d.instances.size(); ++i) {
        ++stats.testedInstances;
        if (!instanceVisible(frame, d.instances[i]))
            continue;
        ++stats.visibleInstances;
        const uint32_t first = d.instances[i].mesh * d.lodCount;
        if (d.lodCount <= 1) {
            record(i, 0.0f, false);
            append(first, i);
            continue;
        }
        const gpu::GpuLodChoice choice = lodReference(frame, d.instances[i], i, d.lodX[i]);
        d.lodX[i] = choice.x;
        record(i, choice.x, true);
        const bool far = choice.lod == gpu::kLodFar, farFade = choice.fadeLod == gpu::kLodFar && !far;
        const uint32_t lod = std::min(choice.lod, d.lodCount - 1), fade = std::min(choice.fadeLod, d.lodCount - 1);
        const int nearSub = nearRasterReference(frame, d.instances[i]);
        if (!far)
            appendLod(first + lod, i, nearSub);
        if (fade != lod && !farFade)
            appendLod(first + fade, i | gpu::kLodFadeEntryBit, nearSub);
        if ((far || farFade) && farAsLod0) {
            append(first, (farFade ? i | gpu::kLodFadeEntryBit : i) | gpu::kLodFarMeshEntryBit);
            ++stats.farInstances;
        } else if (far || farFade) {
            appendFar(farFade ? i | gpu::kLodFadeEntryBit : i, d.instances[i]);
        }
    }
    const uint32_t farGroups = (d.farEntries + gpu::kFarInstancesPerGroup - 1) / gpu::kFarInstancesPerGroup;
    const gpu::GpuFarDispatch dispatch{std::min(farGroups, gpu::kFarMaxGroups), 1u, 1u, d.farEntries};
    std::memcpy(hostWriteAt(ctx, d.staging, d.farDispatchAt, sizeof dispatch), &dispatch, sizeof dispatch);
    const gpu::GpuNearDispatch nearDispatch{
        std::min(d.nearEntries, gpu::kNearMaxGroups), 1u, 1u, d.nearEntries, nearVertices, nearSplit, 0u, 0u};
    std::memcpy(hostWriteAt(ctx, d.staging, d.nearDispatchAt, sizeof nearDispatch), &nearDispatch, sizeof nearDispatch);
    d.visibleCopies.clear();
    for (size_t m = 0; m < d.drawTemplate.size(); ++m)
        if (draws[m].instanceCount > 0)
            d.visibleCopies.push_back({d.visibleAt + draws[m].firstInstance * sizeof(uint32_t),
                                       draws[m].firstInstance * sizeof(uint32_t),
                                       draws[m].instanceCount * sizeof(uint32_t)});
    writeMapped(ctx, d.staging, &stats, sizeof(stats), d.statsAt);
}

void cpuDriverRecordUploads(CpuDriver& d, const FieldRenderer& r, VkCommandBuffer cmd) {
    const VkBuffer from = d.staging.buffer;
    VkBufferCopy draws{d.drawsAt, 0, d.statsAt - d.drawsAt};
    VkBufferCopy stats{d.statsAt, 0, sizeof(gpu::GpuCullStats)};
    if (!d.recordCopies.empty())
        vkCmdCopyBuffer(cmd, from, r.drawInstances.buffer, uint32_t(d.recordCopies.size()), d.recordCopies.data());
    vkCmdCopyBuffer(cmd, from, r.drawCommands.buffer, 1, &draws);
    vkCmdCopyBuffer(cmd, from, r.stats.buffer, 1, &stats);
    if (!d.visibleCopies.empty())
        vkCmdCopyBuffer(cmd, from, r.visibleList.buffer, uint32_t(d.visibleCopies.size()), d.visibleCopies.data());
    if (d.farEntries > 0) {
        VkBufferCopy farList{d.farListAt, 0, VkDeviceSize(d.farEntries) * 2 * sizeof(uint32_t)};
        vkCmdCopyBuffer(cmd, from, r.farList.buffer, 1, &farList);
    }
    VkBufferCopy farDispatch{d.farDispatchAt, 0, sizeof(gpu::GpuFarDispatch)};
    vkCmdCopyBuffer(cmd, from, r.farDispatch.buffer, 1, &farDispatch);
    if (d.nearEntries > 0) {
        VkBufferCopy nearList{d.nearListAt, 0, VkDeviceSize(d.nearEntries) * sizeof(glm::uvec4)};
        vkCmdCopyBuffer(cmd, from, r.nearList.buffer, 1, &nearList);
    }
    VkBufferCopy nearDispatch{d.nearDispatchAt, 0, sizeof(gpu::GpuNearDispatch)};
    vkCmdCopyBuffer(cmd, from, r.nearDispatch.buffer, 1, &nearDispatch);
}

const std::vector<gpu::GpuMotionState>& cpuDriverStates(const CpuDriver& d) {
    return d.states;
}

void destroyCpuDriver(Context& ctx, CpuDriver& d) {
    destroyBuffer(ctx, d.staging);
}

} // namespace meadow
