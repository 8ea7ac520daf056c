#include "library/sections.h"

#include "core/error.h"

#include <cmath>

namespace meadow {
namespace {

void writeClump(ByteWriter& w, const LibraryClump& m) {
    const Mesh& mesh = m.mesh;
    w.string(m.name);
    w.u32(m.plants);
    std::vector<float> vertexData;
    vertexData.reserve(mesh.vertices.size() * 8);
    for (const gpu::GpuVertex& v : mesh.vertices)
        for (int i = 0; i < 4; ++i)
            vertexData.push_back(v.positionU[i]);
    for (const gpu::GpuVertex& v : mesh.vertices)
        for (int i = 0; i < 4; ++i)
            vertexData.push_back(v.normalV[i]);
    w.f32s(vertexData);
    w.u32s(mesh.indices);
    w.f32(mesh.boundingRadius);

    const MotionBasis& b = m.motion;
    w.u32(b.frames);
    for (uint32_t modes : b.lodModes)
        w.u32(modes);
    w.u32s(b.vertexBlock);
    w.u32(uint32_t(b.blocks.size()));
    for (const MotionBlock& block : b.blocks) {
        w.u32(block.coordOffset);
        for (uint32_t rank : block.ranks)
            w.u32(rank);
    }
    w.f32s(b.basis);
    w.f32s(b.coords);
    w.f32s(std::vector<float>(b.relativeErrorPerMode.begin(), b.relativeErrorPerMode.end()));

    const MotionGraph& g = m.graph;
    w.u32(g.nodeCount);
    w.u32(g.levelCount);
    w.u32(g.edgeCount);
    w.u32(g.blendFrames);
    w.u8s(g.nodeLevel);
    w.u8s(g.nodeAlive);
    w.u32s(g.naturalNext);
    w.u32s(g.edgeStart);
    w.u32s(g.edgeTarget);
    w.u8s(g.edgeIsTransition);
    w.f32s(g.edgeProbability);
    w.u32s(g.edgeWeight);
    w.f32s(g.futureCost);
    w.u32(g.stronglyConnected ? 1 : 0);
    w.u8s(g.levelStronglyConnected);
    w.u32(g.removedNodes);
    w.u32(g.transitionCount);
    w.u32(g.crossLevelTransitionCount);
    w.f32s(g.levelThresholdScale);
    w.u32s(g.levelLoopFrames);

    w.u32(uint32_t(m.levels.size()));
    for (const LevelStats& s : m.levels) {
        w.f32(s.meanSpeed);
        w.u32(s.frames);
        w.f32(s.maxPenetration);
        w.f32(float(s.maxKineticEnergy));
        w.f32(float(s.kineticEnergyFirstHalf));
        w.f32(float(s.kineticEnergySecondHalf));
        w.f32(float(s.maxAirDivergence));
    }
}

LibraryClump readClump(ByteReader& r, const std::string& where) {
    auto fail = [&](const std::string& what) -> Error { return Error(where + ": " + what); };
    LibraryClump c;
    c.name = r.string();
    c.plants = r.u32();
    std::vector<float> vertexData = r.f32s();
    if (vertexData.size() % 8 != 0)
        throw fail("clump " + c.name + ": vertex data is not a whole number of vertices");
    size_t vertices = vertexData.size() / 8;
    c.mesh.vertices.resize(vertices);
    for (size_t v = 0; v < vertices; ++v)
        for (int i = 0; i < 4; ++i) {
            c.mesh.vertices[v].positionU[i] = vertexData[v * 4 + size_t(i)];
            c.mesh.vertices[v].normalV[i] = vertexData[vertices * 4 + v * 4 + size_t(i)];
        }
    c.mesh.indices = r.u32s();
    c.mesh.boundingRadius = r.f32();
    if (c.mesh.indices.size() % 3 != 0 || !(c.mesh.boundingRadius > 0.0f) || !std::isfinite(c.mesh.boundingRadius))
        throw fail("clump " + c.name + ": inconsistent mesh");
    for (uint32_t index : c.mesh.indices)
        if (index >= vertices)
            throw fail("clump " + c.name + ": a triangle index is out of range");
    for (float f : vertexData)
        if (!std::isfinite(f))
            throw fail("clump " + c.name + ": a vertex holds a non-finite value");

    MotionBasis& b = c.motion;
    b.frames = r.u32();
    for (uint32_t& modes : b.lodModes)
        modes = r.u32();
    b.vertexBlock = r.u32s();
    const uint32_t blockCount = r.u32();
    if (blockCount > r.remaining() / (4 * (1 + kLodCount)))
        throw fail("clump " + c.name + ": motion block count " + std::to_string(blockCount) + " exceeds the section");
    b.blocks.resize(blockCount);
    for (MotionBlock& block : b.blocks) {
        block.coordOffset = r.u32();
        for (uint32_t& rank : block.ranks)
            rank = r.u32();
    }
    b.basis = r.f32s();
    b.coords = r.f32s();
    std::vector<float> errors = r.f32s();
    b.relativeErrorPerMode.assign(errors.begin(), errors.end());
    if (b.vertexBlock.size() != vertices)
        throw fail("clump " + c.name + ": motion blocks for " + std::to_string(b.vertexBlock.size()) +
                   " vertices, mesh has " + std::to_string(vertices));
    b.finish(where + ": clump " + c.name);

    MotionGraph& g = c.graph;
    g.nodeCount = r.u32();
    g.levelCount = r.u32();
    g.edgeCount = r.u32();
    g.blendFrames = r.u32();
    g.nodeLevel = r.u8s();
    g.nodeAlive = r.u8s();
    g.naturalNext = r.u32s();
    g.edgeStart = r.u32s();
    g.edgeTarget = r.u32s();
    g.edgeIsTransition = r.u8s();
    g.edgeProbability = r.f32s();
    g.edgeWeight = r.u32s();
    g.futureCost = r.f32s();
    g.stronglyConnected = r.u32() != 0;
    g.levelStronglyConnected = r.u8s();
    g.removedNodes = r.u32();
    g.transitionCount = r.u32();
    g.crossLevelTransitionCount = r.u32();
    g.levelThresholdScale = r.f32s();
    g.levelLoopFrames = r.u32s();
    const size_t n = g.nodeCount, e = g.edgeCount, l = g.levelCount;
    if (n != c.motion.frames || g.nodeLevel.size() != n || g.nodeAlive.size() != n || g.naturalNext.size() != n ||
        g.edgeStart.size() != n + 1 || g.edgeTarget.size() != e || g.edgeIsTransition.size() != e ||
        g.edgeProbability.size() != e || g.edgeWeight.size() != l * e || g.futureCost.size() != l * n ||
        g.levelStronglyConnected.size() != l || g.levelThresholdScale.size() != l || g.levelLoopFrames.size() != l ||
        g.edgeStart.back() != e)
        throw fail("clump " + c.name + ": motion graph tables have inconsistent sizes");
    for (size_t i = 0; i < n; ++i)
        if (g.edgeStart[i] > g.edgeStart[i + 1])
            throw fail("clump " + c.name + ": motion graph edge offsets are not ordered");
    for (uint32_t target : g.edgeTarget)
        if (target >= n)
            throw fail("clump " + c.name + ": a motion graph edge leads outside the graph");
    // What the run-time step (motion_step.h) indexes with, besides the edges: the level of a node
    // picks a row of weights, and a node's natural successor is played during blends.
    if (l == 0)
        throw fail("clump " + c.name + ": the motion graph has no wind level");
    for (uint8_t level : g.nodeLevel)
        if (level >= l)
            throw fail("clump " + c.name + ": a motion graph node has wind level " + std::to_string(level) + " of " +
                       std::to_string(l));
    for (uint32_t next : g.naturalNext)
        if (next >= n && next != gpu::kMotionNoFrame)
            throw fail("clump " + c.name + ": a motion graph node's natural successor is outside the graph");

    uint32_t levelCount = r.u32();
    if (levelCount != l)
        throw fail("clump " + c.name + ": simulation statistics for " + std::to_string(levelCount) +
                   " levels, graph has " + std::to_string(l));
    for (uint32_t i = 0; i < levelCount; ++i) {
        LevelStats s;
        s.meanSpeed = r.f32();
        s.frames = r.u32();
        s.maxPenetration = r.f32();
        s.maxKineticEnergy = r.f32();
        s.kineticEnergyFirstHalf = r.f32();
        s.kineticEnergySecondHalf = r.f32();
        s.maxAirDivergence = r.f32();
        c.levels.push_back(s);
    }
    return c;
}

} // namespace

void writeClumpSection(ByteWriter& w, const Library& library) {
    w.u32(uint32_t(library.clumps.size()));
    for (const LibraryClump& clump : library.clumps)
        writeClump(w, clump);
}

void readClumpSection(ByteReader& r, const std::string& where, Library& library) {
    uint32_t count = r.u32();
    if (count == 0 || count > 64)
        throw Error(where + " holds " + std::to_string(count) + " clumps");
    for (uint32_t i = 0; i < count; ++i)
        library.clumps.push_back(readClump(r, where));
    r.expectEnd();
}

} // namespace meadow
