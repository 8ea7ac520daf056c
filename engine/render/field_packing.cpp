#include "render/field_packing.h"

#include "core/error.h"
#include "far_splat.h"
#include "library/sh.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/packing.hpp>

namespace meadow {

namespace {

constexpr uint32_t kSidesTimesChannels = 6; // transfer.h: 2 sides x RGB
constexpr uint32_t kShCount = 9;            // order 3
constexpr uint32_t kTransferValues = kSidesTimesChannels * kShCount;

// Unshadowed transfer of a plain two-sided surface: each side the clamped cosine about its normal
// (the front's n, the back's -n) in SH, the same for the three channels, no gradient.
void appendUnshadowedTransfer(const Mesh& mesh, std::vector<float>& out) {
    const double band[3] = {M_PI, 2.0 * M_PI / 3.0, M_PI / 4.0};
    const int bandOf[kShCount] = {0, 1, 1, 1, 2, 2, 2, 2, 2};
    for (const gpu::GpuVertex& v : mesh.vertices) {
        glm::dvec3 n(v.normalV);
        n = glm::length(n) > 1e-12 ? glm::normalize(n) : glm::dvec3(0.0, 1.0, 0.0);
        double y[2][kShCount];
        sh::evaluate(3, n, y[0]);
        sh::evaluate(3, -n, y[1]);
        for (uint32_t side = 0; side < 2; ++side)
            for (uint32_t c = 0; c < 3; ++c)
                for (uint32_t i = 0; i < kShCount; ++i) {
                    out.push_back(float(band[bandOf[i]] * y[side][i]));
                    out.insert(out.end(), {0.0f, 0.0f, 0.0f});
                }
    }
}

// A clump's basis rows and coordinates into motionData: GpuClump::motion. Each basis row (a mode's
// x, y, z for one vertex) takes 4 floats, the last 0, on a 4-float boundary, so that the compute
// passes fetch it as one RGBA32F texel (motionRowTexels) rather than three floats: llvmpipe pays a
// gather per fetch (docs/BENCHMARKS.md, "The motion rows as one texel"). `basisBase` is the clump's
// first row, in rows of 4 floats.
void packMotion(const FieldClump& clump, FieldPacking& p, gpu::GpuClump& g, uint32_t& basisBase) {
    const MotionBasis& motion = clump.motion;
    const bool moving = motion.frames > 0;
    p.motionData.resize((p.motionData.size() + 3) / 4 * 4, 0.0f);
    basisBase = uint32_t(p.motionData.size() / 4);
    if (moving)
        for (size_t row = 0; row + 2 < motion.basis.size(); row += 3)
            p.motionData.insert(p.motionData.end(),
                                {motion.basis[row], motion.basis[row + 1], motion.basis[row + 2], 0.0f});
    const uint32_t coordBase = uint32_t(p.motionData.size());
    if (moving)
        p.motionData.insert(p.motionData.end(), motion.coords.begin(), motion.coords.end());
    g.motion = gpu::uvec4(0u, coordBase, moving ? motion.modesPerFrame() : 0u, moving ? motion.frames : 1u);
}

// The walk's tables into motionGraph: GpuClump::graph and graphSizes. A static clump gets one
// frame that holds still.
void packGraph(const FieldClump& clump, FieldPacking& p, gpu::GpuClump& g) {
    MotionGraph still;
    still.nodeCount = 1;
    still.levelCount = 1;
    still.edgeCount = 1;
    still.edgeStart = {0, 1};
    still.edgeTarget = {0};
    still.edgeWeight = {1};
    still.naturalNext = {gpu::kMotionNoFrame};
    const MotionGraph& graph = clump.motion.frames > 0 ? clump.graph : still;
    std::vector<uint32_t>& out = p.motionGraph;
    const uint32_t startAt = uint32_t(out.size());
    out.insert(out.end(), graph.edgeStart.begin(), graph.edgeStart.end());
    const uint32_t targetAt = uint32_t(out.size());
    out.insert(out.end(), graph.edgeTarget.begin(), graph.edgeTarget.end());
    const uint32_t weightAt = uint32_t(out.size());
    out.insert(out.end(), graph.edgeWeight.begin(), graph.edgeWeight.end());
    const uint32_t nextAt = uint32_t(out.size());
    out.insert(out.end(), graph.naturalNext.begin(), graph.naturalNext.end());
    g.graph = gpu::uvec4(startAt, targetAt, weightAt, nextAt);
    g.graphSizes = gpu::uvec4(graph.edgeCount, graph.levelCount, std::max(graph.blendFrames, 1u), 0u);
}

// Each LOD's vertices (with their motion rows) and triangles, and its draw: buckets clump-major.
// Returns the first GpuLodVertex of the last LOD.
uint32_t packLods(const FieldClump& clump, size_t clumpIndex, uint32_t lodCount, uint32_t basisBase, FieldPacking& p) {
    const MotionBasis& motion = clump.motion;
    const bool moving = motion.frames > 0;
    uint32_t lastLodBase = 0;
    for (uint32_t l = 0; l < lodCount; ++l) {
        const FieldLod& lod = clump.lods[l];
        lastLodBase = uint32_t(p.lodVertices.size());
        gpu::GpuDrawIndexedCommand& draw = p.draws[clumpIndex * lodCount + l];
        draw.indexCount = uint32_t(lod.indices.size());
        draw.firstIndex = uint32_t(p.indices.size());
        draw.vertexOffset = int32_t(p.lodVertices.size());
        for (uint32_t v : lod.vertices) {
            gpu::GpuLodVertex lv{clump.mesh.vertices[v].positionU, clump.mesh.vertices[v].normalV,
                                 gpu::uvec4(0u, 0u, v, l << 16)};
            if (moving) {
                const MotionBlock& block = motion.blocks[motion.vertexBlock[v]];
                lv.motion = gpu::uvec4(basisBase + motion.vertexRowOffset[v] / 3, block.coordOffset, v,
                                       block.ranks[std::min(l, kLodCount - 1)] | (l << 16));
            }
            p.lodVertices.push_back(lv);
        }
        p.indices.insert(p.indices.end(), lod.indices.begin(), lod.indices.end());
        p.meshTriangles.push_back(uint32_t(lod.indices.size() / 3));
        p.meshVertices.push_back(uint32_t(lod.vertices.size()));
    }
    return lastLodBase;
}

// The modes of a block that the far field plays: the last LOD's `rank`, at most kFarMotionModes.
// PCA orders a block's modes by energy, so these are its strongest. The bundled `full` library's
// last LOD plays up to 5 modes in a few blocks; the splat pass's loop over the modes past the two
// its texel holds cost 7-8 ms of the default view on lavapipe, paid for every sample (llvmpipe
// runs a loop's body once for a SIMD row even where no lane enters it; docs/BENCHMARKS.md, "The
// splat pass's loops"). The far field, below 28 px, hands over from LOD 2, which plays up to 11.
uint32_t farRank(uint32_t rank) {
    return std::min(rank, gpu::kFarMotionModes);
}

// The far field's motion coordinates: per frame, the coordinates of each block in turn that the
// far field plays (its first ranks[lastLod], at most kFarMotionModes: farRank), appended to
// motionData at GpuClump::motion.x, GpuClump::graphSizes.w of them per frame. A far instance's
// samples then read one or two cache lines of a frame's coordinates instead of one per block
// spread over all of them: on lavapipe, about 6 ms less of the
// splat pass at 1280x720 on a 2-core Zen 3, with GpuFarMotion (docs/BENCHMARKS.md, 2026-12-02
// (morning)). Returns each block's first far coordinate in a frame.
std::vector<uint32_t> packFarCoordinates(const FieldClump& clump, uint32_t lastLod, FieldPacking& p, gpu::GpuClump& g) {
    const MotionBasis& motion = clump.motion;
    std::vector<uint32_t> first(motion.blocks.size(), 0u);
    uint32_t perFrame = 0;
    for (size_t b = 0; b < motion.blocks.size(); ++b) {
        first[b] = perFrame;
        perFrame += farRank(motion.blocks[b].ranks[lastLod]);
    }
    g.motion.x = uint32_t(p.motionData.size());
    g.graphSizes.w = motion.frames > 0 ? perFrame : 0u;
    if (motion.frames == 0)
        return first;
    const size_t modesPerFrame = motion.modesPerFrame();
    for (uint32_t f = 0; f < motion.frames; ++f)
        for (const MotionBlock& block : motion.blocks)
            for (uint32_t k = 0; k < farRank(block.ranks[lastLod]); ++k)
                p.motionData.push_back(motion.coords[f * modesPerFrame + block.coordOffset + k]);
    return first;
}

// A far sample's GpuFarMotion: the motion of the last-LOD vertex it follows (`motion`, its
// GpuLodVertex::motion) at the far field's rank (farRank), its rows as half floats (zero past that
// rank) and its block's first far coordinate (`farFirst`, packFarCoordinates). The splat pass then
// reads a sample's motion as one texel rather than its LOD vertex's and one per mode. A half float
// holds a row to 2^-11 of itself (about 10 µm of a clump's sway); rows below the smallest normal
// half are stored as 0.
gpu::uvec4 farSampleMotion(const FieldPacking& p, const gpu::uvec4& motion, uint32_t farFirst, size_t clumpIndex) {
    static_assert(gpu::kFarMotionModes < (1u << (32u - gpu::kFarMotionRankShift)), "the far rank fits its bits");
    const uint32_t rank = farRank(motion.w & 0xffffu);
    if (farFirst > gpu::kFarMotionOffsetMask)
        throw Error("field clump " + std::to_string(clumpIndex) + ": a far-field sample's motion (coordinate " +
                    std::to_string(farFirst) + ") does not fit its word");
    float rows[6] = {};
    for (uint32_t k = 0; k < rank; ++k)
        for (uint32_t c = 0; c < 3; ++c) {
            const float value = p.motionData[4 * size_t(motion.x + k) + c];
            if (!(std::abs(value) <= 65504.0f))
                throw Error("field clump " + std::to_string(clumpIndex) + ": a motion row holds " +
                            std::to_string(value) + ", beyond a half float");
            rows[3 * k + c] = std::abs(value) < 6.103515625e-05f ? 0.0f : value;
        }
    return gpu::uvec4(glm::packHalf2x16(glm::vec2(rows[0], rows[1])), glm::packHalf2x16(glm::vec2(rows[2], rows[3])),
                      glm::packHalf2x16(glm::vec2(rows[4], rows[5])), farFirst | (rank << gpu::kFarMotionRankShift));
}

// The far field's samples into farSamples, each with the motion of the last LOD's vertex it
// follows (its rows at that LOD's modes: farSampleMotion) and the clump vertex whose light it
// takes: GpuClump::far.
void packFar(const FieldClump& clump, size_t clumpIndex, uint32_t lastLodBase, FieldPacking& p, gpu::GpuClump& g) {
    const std::vector<uint32_t>& lastLodVertices = clump.lods.back().vertices;
    std::vector<uint32_t> slot(clump.mesh.vertices.size(), UINT32_MAX);
    for (uint32_t k = 0; k < uint32_t(lastLodVertices.size()); ++k)
        slot[lastLodVertices[k]] = k;
    const uint32_t first = uint32_t(p.farSamples.size());
    const uint32_t lastLod = uint32_t(std::min<size_t>(clump.lods.size(), kLodCount) - 1);
    const std::vector<uint32_t> farFirst = packFarCoordinates(clump, lastLod, p, g);
    const bool moving = clump.motion.frames > 0;
    p.farMotion.resize(p.lodVertices.size());
    for (const FarSample& s : clump.far) {
        if (s.vertex >= slot.size() || slot[s.vertex] == UINT32_MAX)
            throw Error("field clump " + std::to_string(clumpIndex) + ": a far-field sample follows vertex " +
                        std::to_string(s.vertex) + ", which its last LOD does not keep");
        const float r = srgbToLinear(uint8_t(s.albedo & 0xffu)), gr = srgbToLinear(uint8_t((s.albedo >> 8) & 0xffu)),
                    b = srgbToLinear(uint8_t((s.albedo >> 16) & 0xffu));
        if (s.lightVertex >= clump.mesh.vertices.size())
            throw Error("field clump " + std::to_string(clumpIndex) + ": a far-field sample is lit by vertex " +
                        std::to_string(s.lightVertex) + " of " + std::to_string(clump.mesh.vertices.size()));
        const gpu::uvec4 motion = p.lodVertices[lastLodBase + slot[s.vertex]].motion;
        p.farSamples.push_back(
            {gpu::uvec4(glm::floatBitsToUint(s.position), s.visibility),
             gpu::uvec4(s.normal, gpu::packRgb9e5(r, gr, b), s.lightVertex, lastLodBase + slot[s.vertex])});
        const uint32_t block = moving ? clump.motion.vertexBlock[s.vertex] : 0u;
        if (moving && (motion.w & 0xffffu) != clump.motion.blocks[block].ranks[lastLod])
            throw Error("field clump " + std::to_string(clumpIndex) + ": a far-field sample's vertex plays " +
                        std::to_string(motion.w & 0xffffu) + " modes at its last LOD, its block " +
                        std::to_string(clump.motion.blocks[block].ranks[lastLod]));
        p.farMotion[lastLodBase + slot[s.vertex]] = {
            farSampleMotion(p, motion, moving ? farFirst[block] : 0u, clumpIndex)};
    }
    if (!clump.far.empty() && !(clump.farArea > 0.0f && std::isfinite(clump.farArea)))
        throw Error("field clump " + std::to_string(clumpIndex) + ": its far-field samples cover " +
                    std::to_string(clump.farArea) + " m^2");
    uint32_t areaBits;
    std::memcpy(&areaBits, &clump.farArea, sizeof areaBits);
    g.far = gpu::uvec4(first, uint32_t(clump.far.size()), areaBits, clump.farClosed ? 1u : 0u);
    for (uint32_t size = 0; size < gpu::kFarGainSizes; ++size) {
        float* row = &g.farGain[size].x;
        for (uint32_t elevation = 0; elevation < gpu::kFarGainElevations; ++elevation) {
            const float gain = clump.farGain[size * gpu::kFarGainElevations + elevation];
            if (!(gain > 0.0f && std::isfinite(gain)))
                throw Error("field clump " + std::to_string(clumpIndex) + ": its far-field coverage gain is " +
                            std::to_string(gain));
            row[elevation] = gain;
        }
    }
}

// The clump's transfer (and its ground grid's) into transfer, and where the light pass writes
// its light variants: GpuClump::light, yawBins, albedo and ground.
void packLight(const FieldClump& clump, FieldPacking& p, gpu::GpuClump& g) {
    const uint32_t vertexCount = uint32_t(clump.mesh.vertices.size());
    const uint32_t transferBase = uint32_t(p.transfer.size() / 4);
    if (clump.transfer.empty())
        appendUnshadowedTransfer(clump.mesh, p.transfer);
    else
        p.transfer.insert(p.transfer.end(), clump.transfer.begin(), clump.transfer.end());
    // A closed surface (a rock) shows only its outer side, but the draws pick a fragment's side from
    // the interpolated normal, whose sign turns a pixel or so inside the silhouette, where the inner
    // side's transfer (the inside of the rock: no light) painted a black rim. Its outer side's
    // transfer stands for both.
    if (clump.farClosed) {
        const size_t side = size_t(kTransferValues / 2) * 4;
        for (uint32_t v = 0; v < vertexCount; ++v) {
            float* values = p.transfer.data() + size_t(transferBase) * 4 + size_t(v) * kTransferValues * 4;
            std::copy(values, values + side, values + side);
        }
    }
    const uint32_t variants = 2 * clump.yawBins;
    g.light = gpu::uvec4(uint32_t(p.lightVec4s), clump.yawBins, transferBase, vertexCount);
    p.lightVec4s += uint64_t(vertexCount) * variants * gpu::kLightVec4sPerVertex;
    p.lightVertices.push_back(vertexCount);
    p.lightGroundPoints.push_back(0);
    const float range = clump.yawHigh - clump.yawLow;
    g.yawBins = range > 0.0f ? glm::vec4(clump.yawLow, float(clump.yawBins) / range, range / float(clump.yawBins), 0.0f)
                             : glm::vec4(clump.yawLow, 0.0f, 0.0f, 0.0f);
    g.albedo = clump.albedo;
    if (clump.groundResolution >= 2) {
        const uint32_t points = clump.groundResolution * clump.groundResolution;
        g.ground = gpu::uvec4(uint32_t(p.transfer.size() / 4), uint32_t(p.lightVec4s), clump.groundResolution, 0u);
        for (float t : clump.groundTransfer)
            p.transfer.insert(p.transfer.end(), {t, 0.0f, 0.0f, 0.0f});
        p.lightVec4s += uint64_t(points) * variants;
        p.lightGroundPoints.back() = points;
        g.yawBins.w = clump.groundSize;
    }
}

// Each instance's first motion state, and each bucket's range of the visible list: it holds every
// instance of its clump (an instance lands in at most one range per LOD of its clump, two while
// crossfading, never twice in one).
void packInstances(std::span<const FieldClump> clumps, std::span<const gpu::GpuInstance> instances, uint32_t lodCount,
                   FieldPacking& p) {
    const uint32_t clumpCount = uint32_t(clumps.size());
    std::vector<uint32_t> perClump(clumpCount, 0);
    p.states.assign(instances.size(), gpu::GpuMotionState{});
    for (size_t i = 0; i < instances.size(); ++i) {
        const gpu::GpuInstance& inst = instances[i];
        if (inst.mesh >= clumpCount)
            throw Error("a field instance names clump " + std::to_string(inst.mesh) + " of " +
                        std::to_string(clumpCount));
        perClump[inst.mesh]++;
        const FieldClump& clump = clumps[inst.mesh];
        // Each instance starts at its own frame so that copies never move in lock step.
        if (clump.motion.frames > 0)
            p.states[i] = initialMotionState(clump.graph, uint32_t(i));
    }
    uint32_t first = 0;
    for (uint32_t m = 0; m < uint32_t(p.draws.size()); ++m) {
        p.draws[m].firstInstance = first;
        p.drawCapacity.push_back(perClump[m / lodCount]);
        first += perClump[m / lodCount];
    }
    p.visibleCount = first;
}

} // namespace

void checkFieldClump(const FieldClump& clump, size_t index, uint32_t lodCount) {
    const std::string what = "field clump " + std::to_string(index);
    const size_t vertexCount = clump.mesh.vertices.size();
    if (vertexCount == 0)
        throw Error(what + " has no vertices");
    if (clump.lods.size() != lodCount)
        throw Error(what + " has " + std::to_string(clump.lods.size()) + " levels of detail, not " +
                    std::to_string(lodCount));
    for (size_t l = 0; l < clump.lods.size(); ++l) {
        const FieldLod& lod = clump.lods[l];
        if (lod.indices.empty() || lod.indices.size() % 3 != 0)
            throw Error(what + " LOD " + std::to_string(l) + " has no triangles or a partial one");
        for (uint32_t v : lod.vertices)
            if (v >= vertexCount)
                throw Error(what + " LOD " + std::to_string(l) + " names vertex " + std::to_string(v) + " of " +
                            std::to_string(vertexCount));
        for (uint32_t i : lod.indices)
            if (i >= lod.vertices.size())
                throw Error(what + " LOD " + std::to_string(l) + " has an index past its vertices");
    }
    const bool moving = clump.motion.frames > 0;
    if (moving != (clump.graph.nodeCount > 0))
        throw Error(what + " has motion without a motion graph or a graph without motion");
    if (moving) {
        if (clump.motion.vertexBlock.size() != vertexCount || clump.motion.vertexRowOffset.size() != vertexCount)
            throw Error(what + ": its motion basis covers " + std::to_string(clump.motion.vertexBlock.size()) +
                        " vertices, its mesh has " + std::to_string(vertexCount));
        if (clump.graph.nodeCount != clump.motion.frames || clump.graph.levelCount == 0)
            throw Error(what + ": its motion graph has " + std::to_string(clump.graph.nodeCount) + " nodes for " +
                        std::to_string(clump.motion.frames) + " motion frames");
        for (const MotionBlock& block : clump.motion.blocks)
            if (block.ranks[0] > 0xffffu)
                throw Error(what + ": a motion block has more than 65535 modes");
    }
    if (!clump.transfer.empty() && clump.transfer.size() != vertexCount * kTransferValues * 4)
        throw Error(what + ": its light transfer holds " + std::to_string(clump.transfer.size()) +
                    " values, not 216 per vertex (SH order 3, two sides, RGB, with gradients)");
    if (clump.groundResolution == 1 ||
        clump.groundTransfer.size() != size_t(clump.groundResolution) * clump.groundResolution * 27 ||
        (clump.groundResolution > 0 && !(clump.groundSize > 0.0f)))
        throw Error(what + ": its ground grid of " + std::to_string(clump.groundResolution) +
                    " points per side holds " + std::to_string(clump.groundTransfer.size()) +
                    " values (27 per point) over " + std::to_string(clump.groundSize) + " m");
    if (clump.yawBins == 0 || !(clump.yawHigh >= clump.yawLow))
        throw Error(what + ": its yaw range or yaw bins are empty");
}

FieldPacking packField(std::span<const FieldClump> clumps, std::span<const gpu::GpuInstance> instances,
                       uint32_t lodCount) {
    FieldPacking p;
    p.draws.resize(clumps.size() * lodCount);
    for (size_t ci = 0; ci < clumps.size(); ++ci) {
        const FieldClump& clump = clumps[ci];
        gpu::GpuClump g{};
        uint32_t basisBase = 0;
        packMotion(clump, p, g, basisBase);
        packGraph(clump, p, g);
        const uint32_t lastLodBase = packLods(clump, ci, lodCount, basisBase, p);
        packLight(clump, p, g);
        packFar(clump, ci, lastLodBase, p, g);
        p.clumps.push_back(g);
    }
    if (p.lightVec4s > (uint64_t(1) << 31) / 16 || p.motionData.size() > (size_t(1) << 31))
        throw Error("the field's clumps need more than 2 GiB of light or motion data");
    p.farMotion.resize(p.lodVertices.size());
    packInstances(clumps, instances, lodCount, p);
    return p;
}

size_t skyFrameFloats(const sky::SkyDay& day) {
    return gpu::kSkyFrameHeaderFloats + size_t(day.imageWidth) * day.imageHeight * 3;
}

std::vector<float> packSkyDay(const sky::SkyDay& day) {
    const size_t skyStride = skyFrameFloats(day);
    std::vector<float> skyData(skyStride * day.frames.size(), 0.0f);
    for (size_t f = 0; f < day.frames.size(); ++f) {
        const sky::SkyFrame& frame = day.frames[f];
        float* out = &skyData[f * skyStride];
        if (frame.sh.size() != 27 || frame.image.size() != skyStride - gpu::kSkyFrameHeaderFloats)
            throw Error("sky frame " + std::to_string(f) + " has the wrong number of SH values or pixels");
        std::copy(frame.sh.begin(), frame.sh.end(), out);
        for (int k = 0; k < 3; ++k) {
            out[28 + k] = frame.sunDirection[k];
            out[32 + k] = frame.sunRadiance[k];
        }
        std::copy(frame.image.begin(), frame.image.end(), out + gpu::kSkyFrameHeaderFloats);
    }
    return skyData;
}

std::vector<uint16_t> packAtlas(const RgbaImage& atlas) {
    uint16_t linear[256], alpha[256];
    for (uint32_t byte = 0; byte < 256; ++byte) {
        linear[byte] = uint16_t(glm::packHalf1x16(srgbToLinear(uint8_t(byte))));
        alpha[byte] = uint16_t(glm::packHalf1x16(float(byte) / 255.0f));
    }
    std::vector<uint16_t> texels(atlas.rgba.size());
    for (size_t i = 0; i < texels.size(); ++i)
        texels[i] = i % 4 == 3 ? alpha[atlas.rgba[i]] : linear[atlas.rgba[i]];
    return texels;
}

} // namespace meadow
