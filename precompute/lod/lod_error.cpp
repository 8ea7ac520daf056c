// The error of a LOD against the full mesh (lod.h), in the spirit of Metro (Cignoni, Rocchini and
// Scopigno 1998): points sampled uniformly by area on each surface, each measured to the nearest
// point of the other surface. Both directions matter: full -> LOD finds what the LOD lost (a
// removed blade tip), LOD -> full finds what it invented (a triangle bridging a gap).
//
// At rest the nearest point also gives each sample its correspondent on the other surface, and
// through it the lighting error (the caller's per-vertex scalar interpolated at both points) and
// the motion error (the displacement of both points in each deformed frame: the LOD's vertices
// are original vertices, so they move exactly as the full mesh's do, but the surface between
// them interpolates fewer of them). In each deformed frame the geometric distance is measured
// afresh on the deformed surfaces, with the same samples carried along (their triangle and
// barycentric weights).
//
// Samples are processed in parallel and reduced in sample order: deterministic for any TBB
// thread count.
#include "lod/lod.h"
#include "lod/triangle_bvh.h"

#include "core/error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace meadow {

using namespace lod_detail;

namespace {

constexpr size_t kGrain = 256;

struct TriangleSurface {
    std::span<const glm::vec3> positions;
    std::span<const uint32_t> indices;
};

template <typename T>
T interpolate(std::span<const T> values, std::span<const uint32_t> indices, uint32_t triangle,
              const glm::vec3& barycentric) {
    return values[indices[3 * triangle]] * barycentric.x + values[indices[3 * triangle + 1]] * barycentric.y +
           values[indices[3 * triangle + 2]] * barycentric.z;
}

// Area-weighted root mean square and maximum of a set of values, one per direction.
struct OneWay {
    double largest = 0.0, sumSquares = 0.0, weight = 0.0;
    void add(const std::vector<float>& values, const std::vector<SurfaceSample>& samples) {
        for (size_t i = 0; i < values.size(); ++i) {
            largest = std::max(largest, double(values[i]));
            sumSquares += double(samples[i].weight) * double(values[i]) * double(values[i]);
            weight += samples[i].weight;
        }
    }
    double rms() const { return weight > 0.0 ? std::sqrt(sumSquares / weight) : 0.0; }
};

// Symmetric figures as Metro's: the larger of the two one-sided ones. Pooling both directions
// into one mean instead would let a LOD look better for having less surface to be wrong on (a
// removed petal takes its own badly lit samples out of the LOD -> full direction).
struct Accumulator {
    OneWay fullToLod, lodToFull;
    SurfaceDistance result() const {
        return {std::max(fullToLod.largest, lodToFull.largest), std::max(fullToLod.rms(), lodToFull.rms())};
    }
};

// For each sample of `from`, the nearest point of `to`.
std::vector<ClosestHit> nearest(const TriangleSurface& from, const std::vector<SurfaceSample>& samples,
                                const TriangleSurface& to) {
    const TriangleBvh bvh(to.positions, to.indices);
    std::vector<ClosestHit> hits(samples.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, samples.size(), kGrain), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const glm::vec3 p = interpolate(from.positions, from.indices, samples[i].triangle, samples[i].barycentric);
            hits[i] = bvh.closest(p);
        }
    });
    return hits;
}

std::vector<float> distances(const std::vector<ClosestHit>& hits) {
    std::vector<float> d(hits.size());
    for (size_t i = 0; i < hits.size(); ++i)
        d[i] = std::sqrt(hits[i].distanceSquared);
    return d;
}

void validate(const LodErrorInput& full, std::span<const uint32_t> lodVertices, std::span<const uint32_t> lodIndices,
              const LodErrorOptions& options) {
    auto fail = [](const std::string& problem) { return Error("LOD error: " + problem); };
    const size_t n = full.positions.size();
    if (n == 0 || full.indices.empty() || full.indices.size() % 3 != 0)
        throw fail("the full mesh needs vertices and a whole number of triangles (" +
                   std::to_string(full.indices.size()) + " indices)");
    for (size_t i = 0; i < full.indices.size(); ++i)
        if (full.indices[i] >= n)
            throw fail("full-mesh index " + std::to_string(i) + " is " + std::to_string(full.indices[i]) +
                       ", the mesh has " + std::to_string(n) + " vertices");
    for (size_t v = 0; v < n; ++v) {
        const glm::vec3& p = full.positions[v];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw fail("the position of vertex " + std::to_string(v) + " is not finite");
    }
    if (lodIndices.empty() || lodIndices.size() % 3 != 0)
        throw fail("the LOD needs a whole, non-zero number of triangles (" + std::to_string(lodIndices.size()) +
                   " indices)");
    for (size_t i = 0; i < lodVertices.size(); ++i)
        if (lodVertices[i] >= n)
            throw fail("LOD vertex " + std::to_string(i) + " is original vertex " + std::to_string(lodVertices[i]) +
                       ", the full mesh has " + std::to_string(n));
    for (size_t i = 0; i < lodIndices.size(); ++i)
        if (lodIndices[i] >= lodVertices.size())
            throw fail("LOD index " + std::to_string(i) + " is " + std::to_string(lodIndices[i]) + ", the LOD has " +
                       std::to_string(lodVertices.size()) + " vertices");
    if (!full.lightScalar.empty()) {
        if (full.lightScalar.size() != n)
            throw fail(std::to_string(full.lightScalar.size()) + " light values for " + std::to_string(n) +
                       " vertices");
        for (size_t v = 0; v < n; ++v)
            if (!std::isfinite(full.lightScalar[v]))
                throw fail("the light value of vertex " + std::to_string(v) + " is not finite");
    }
    for (size_t f = 0; f < full.frames.size(); ++f) {
        if (full.frames[f].size() != n)
            throw fail("frame " + std::to_string(f) + " has " + std::to_string(full.frames[f].size()) +
                       " positions for " + std::to_string(n) + " vertices");
        for (const glm::vec3& p : full.frames[f])
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                throw fail("frame " + std::to_string(f) + " holds a position that is not finite");
    }
    if (!(options.samplesPerSquareMetre > 0.0f) || !std::isfinite(options.samplesPerSquareMetre))
        throw fail("samplesPerSquareMetre must be finite and > 0");
}

} // namespace

LodError measureLodError(const LodErrorInput& full, std::span<const uint32_t> lodVertices,
                         std::span<const uint32_t> lodIndices, const LodErrorOptions& options) {
    validate(full, lodVertices, lodIndices, options);
    std::vector<glm::vec3> lodRest(lodVertices.size());
    for (size_t i = 0; i < lodVertices.size(); ++i)
        lodRest[i] = full.positions[lodVertices[i]];
    const TriangleSurface fullMesh{full.positions, full.indices}, lodMesh{lodRest, lodIndices};

    const std::vector<SurfaceSample> fullSamples =
        sampleSurface(full.positions, full.indices, options.samplesPerSquareMetre);
    const std::vector<SurfaceSample> lodSamples = sampleSurface(lodRest, lodIndices, options.samplesPerSquareMetre);
    LodError error;
    error.fullSamples = uint32_t(fullSamples.size());
    error.lodSamples = uint32_t(lodSamples.size());

    // Rest: distances and correspondences.
    const std::vector<ClosestHit> fullToLod = nearest(fullMesh, fullSamples, lodMesh);
    const std::vector<ClosestHit> lodToFull = nearest(lodMesh, lodSamples, fullMesh);
    Accumulator rest;
    rest.fullToLod.add(distances(fullToLod), fullSamples);
    rest.lodToFull.add(distances(lodToFull), lodSamples);
    error.rest = rest.result();

    if (!full.lightScalar.empty()) {
        std::vector<float> lodLight(lodVertices.size());
        for (size_t i = 0; i < lodVertices.size(); ++i)
            lodLight[i] = full.lightScalar[lodVertices[i]];
        const std::span<const float> fullValues = full.lightScalar, lodValues = lodLight;
        auto difference = [](std::span<const float> fromValues, std::span<const uint32_t> fromIndices,
                             const std::vector<SurfaceSample>& samples, std::span<const float> toValues,
                             std::span<const uint32_t> toIndices, const std::vector<ClosestHit>& hits) {
            std::vector<float> d(samples.size());
            for (size_t i = 0; i < samples.size(); ++i)
                d[i] = std::abs(interpolate(fromValues, fromIndices, samples[i].triangle, samples[i].barycentric) -
                                interpolate(toValues, toIndices, hits[i].triangle, hits[i].barycentric));
            return d;
        };
        Accumulator light;
        light.fullToLod.add(difference(fullValues, full.indices, fullSamples, lodValues, lodIndices, fullToLod),
                            fullSamples);
        light.lodToFull.add(difference(lodValues, lodIndices, lodSamples, fullValues, full.indices, lodToFull),
                            lodSamples);
        error.light = light.result();
    }

    Accumulator deformed, motion;
    std::vector<glm::vec3> lodFrame(lodVertices.size()), fullDisplacement(full.positions.size()),
        lodDisplacement(lodVertices.size());
    for (const std::vector<glm::vec3>& frame : full.frames) {
        for (size_t i = 0; i < lodVertices.size(); ++i)
            lodFrame[i] = frame[lodVertices[i]];
        const TriangleSurface fullNow{frame, full.indices}, lodNow{lodFrame, lodIndices};
        deformed.fullToLod.add(distances(nearest(fullNow, fullSamples, lodNow)), fullSamples);
        deformed.lodToFull.add(distances(nearest(lodNow, lodSamples, fullNow)), lodSamples);

        for (size_t v = 0; v < frame.size(); ++v)
            fullDisplacement[v] = frame[v] - full.positions[v];
        for (size_t i = 0; i < lodVertices.size(); ++i)
            lodDisplacement[i] = fullDisplacement[lodVertices[i]];
        const std::span<const glm::vec3> fullD = fullDisplacement, lodD = lodDisplacement;
        auto difference = [](std::span<const glm::vec3> fromD, std::span<const uint32_t> fromIndices,
                             const std::vector<SurfaceSample>& samples, std::span<const glm::vec3> toD,
                             std::span<const uint32_t> toIndices, const std::vector<ClosestHit>& hits) {
            std::vector<float> d(samples.size());
            for (size_t i = 0; i < samples.size(); ++i)
                d[i] = glm::length(interpolate(fromD, fromIndices, samples[i].triangle, samples[i].barycentric) -
                                   interpolate(toD, toIndices, hits[i].triangle, hits[i].barycentric));
            return d;
        };
        motion.fullToLod.add(difference(fullD, full.indices, fullSamples, lodD, lodIndices, fullToLod), fullSamples);
        motion.lodToFull.add(difference(lodD, lodIndices, lodSamples, fullD, full.indices, lodToFull), lodSamples);
    }
    error.deformed = deformed.result();
    error.motion = motion.result();
    return error;
}

std::array<LodError, kLodCount> measureLodErrors(const LodErrorInput& full, const std::array<MeshLod, kLodCount>& lods,
                                                 const LodErrorOptions& options) {
    std::array<LodError, kLodCount> errors;
    for (uint32_t i = 0; i < kLodCount; ++i)
        errors[i] = measureLodError(full, lods[i].vertices, lods[i].indices, options);
    return errors;
}

} // namespace meadow
