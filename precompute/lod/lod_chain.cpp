// Five levels of detail from triangle budgets (lod.h).
//
// Chaining: every LOD continues the SAME collapse sequence (one MeshSimplifier, decreasing
// targets), so LOD i+1 is simplified from LOD i, but with the quadrics accumulated from the full
// mesh (Garland & Heckbert 1997, section 4: the quadric of a vertex is the sum over every
// original face it stands for). Why:
//   - errors are measured against the original surface, never against an already simplified one
//     (re-simplifying LOD i from scratch would forget what LOD i had already removed and let the
//     error compound);
//   - coarser LODs keep a subset of the finer LODs' vertices, so a dithered cross-fade between two
//     LODs blends two meshes built on the same vertices and their motion and light rows;
//   - all five cost one simplification to the coarsest budget.
// Simplifying each LOD independently from the full mesh would give the same error measure but
// lose the nesting, at five times the cost.
//
// Each LOD is then reordered for the post-transform vertex cache (meshopt_optimizeVertexCache,
// after Forsyth's "Linear-speed vertex cache optimisation") and its vertices for fetch locality
// (meshopt_optimizeVertexFetchRemap: first use order). The fetch order is returned as a list of
// original vertex indices, so the caller gathers its own per-vertex data (motion rows, transfer,
// UV, part) through it.
#include "lod/lod.h"

#include "core/error.h"

#include <meshoptimizer.h>

#include <cmath>
#include <string>

namespace meadow {

namespace {

void validateFractions(const LodOptions& options) {
    for (uint32_t i = 0; i < kLodCount; ++i) {
        const float f = options.triangleFractions[i];
        if (!(f > 0.0f && f <= 1.0f))
            throw Error("LOD: the triangle fraction of LOD " + std::to_string(i) + " is " + std::to_string(f) +
                        ", not in (0, 1]");
        if (i > 0 && f > options.triangleFractions[i - 1])
            throw Error("LOD: the triangle fraction of LOD " + std::to_string(i) + " (" + std::to_string(f) +
                        ") is larger than that of LOD " + std::to_string(i - 1) + " (" +
                        std::to_string(options.triangleFractions[i - 1]) + ")");
    }
}

MeshLod optimiseLod(const SimplifiedMesh& simplified) {
    MeshLod lod;
    lod.targetTriangles = simplified.targetTriangles;
    lod.error = simplified.error;
    lod.stage = simplified.stage;
    lod.removedComponents = simplified.removedComponents;
    const size_t vertexCount = simplified.keptVertices.size();
    const size_t indexCount = simplified.indices.size();

    std::vector<uint32_t> cacheOrder(indexCount);
    meshopt_optimizeVertexCache(cacheOrder.data(), simplified.indices.data(), indexCount, vertexCount);
    // remap[old local index] = new local index, in order of first use by the reordered triangles.
    std::vector<uint32_t> remap(vertexCount);
    const size_t used = meshopt_optimizeVertexFetchRemap(remap.data(), cacheOrder.data(), indexCount, vertexCount);
    // Every kept vertex is used by a triangle (SimplifiedMesh's contract).
    if (used != vertexCount)
        throw Error("LOD: internal error, " + std::to_string(vertexCount - used) + " kept vertices are unused");
    lod.vertices.resize(vertexCount);
    for (size_t old = 0; old < vertexCount; ++old)
        lod.vertices[remap[old]] = simplified.keptVertices[old];
    lod.indices.resize(indexCount);
    meshopt_remapIndexBuffer(lod.indices.data(), cacheOrder.data(), indexCount, remap.data());
    lod.acmr = meshopt_analyzeVertexCache(lod.indices.data(), indexCount, vertexCount, 16, 0, 0).acmr;
    return lod;
}

} // namespace

std::array<MeshLod, kLodCount> buildLods(const SimplifyInput& input, const LodOptions& options) {
    validateFractions(options);
    MeshSimplifier simplifier(input, options.simplify);
    const double fullTriangles = double(input.indices.size() / 3);
    std::array<MeshLod, kLodCount> lods;
    for (uint32_t i = 0; i < kLodCount; ++i) {
        const uint32_t target =
            uint32_t(std::max(1.0, std::round(double(options.triangleFractions[i]) * fullTriangles)));
        lods[i] = optimiseLod(simplifier.simplifyTo(target));
    }
    return lods;
}

} // namespace meadow
