// Shadowed diffuse transfer by ray casting (Sloan, Kautz and Snyder 2002, section 4: "T_DS",
// visibility times the clamped cosine, projected on SH), for both sides of every vertex.
//
// One set of rays serves both sides: a direction in front of the normal belongs to the Front
// side's integral, one behind it to the Back side's, so raysPerVertex rays over the sphere give
// each side of a sheet raysPerVertex / 2 samples of its own hemisphere.
//
// Estimator. The unoccluded integral, the clamped cosine C(n), is known in closed form
// (clampedCosineTransfer), so only what the occluders remove is estimated:
//     T_side = C(n_side) - (4 pi / N) * sum over blocked rays in the side's hemisphere of |n . w| y(w).
// This is a control variate with the exact unshadowed transfer: a vertex that sees the whole sky
// gets it exactly, and the Monte-Carlo error scales with the blocked part only. The ray origin is
// moved rayOffset along the side's normal so a vertex never hits the triangles it belongs to.
#include "core/error.h"
#include "light/sh.h"
#include "transfer/bake_detail.h"
#include "transfer/sphere_sampling.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <numbers>
#include <string>

namespace meadow::transfer::detail {

namespace {

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

} // namespace

FrameGeometry prepareFrame(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                           std::span<const uint32_t> indices, uint32_t vertexCount) {
    if (positions.size() != vertexCount || normals.size() != vertexCount) {
        throw Error("transfer bake: the frame has " + std::to_string(positions.size()) + " positions and " +
                    std::to_string(normals.size()) + " normals for a mesh of " + std::to_string(vertexCount) +
                    " vertices");
    }
    FrameGeometry frame;
    frame.positions = positions;
    frame.indices = indices;
    frame.normals.resize(vertexCount);
    for (uint32_t v = 0; v < vertexCount; ++v) {
        if (!finite(positions[v]))
            throw Error("transfer bake: position of vertex " + std::to_string(v) + " is not finite");
        const glm::vec3 n = normals[v];
        const float length = glm::length(n);
        if (!finite(n) || !(length > 1e-6f))
            throw Error("transfer bake: normal of vertex " + std::to_string(v) + " is not finite or has zero length");
        frame.normals[v] = n / length;
    }
    const size_t triangles = indices.size() / 3;
    frame.triangleFronts.resize(triangles);
    for (size_t t = 0; t < triangles; ++t) {
        const uint32_t a = indices[3 * t], b = indices[3 * t + 1], c = indices[3 * t + 2];
        glm::vec3 geometric = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
        if (glm::dot(geometric, frame.normals[a] + frame.normals[b] + frame.normals[c]) < 0.0f)
            geometric = -geometric;
        frame.triangleFronts[t] = geometric;
    }
    return frame;
}

void castVertexRays(const RayScene& scene, const FrameGeometry& frame, const BakeSettings& settings,
                    std::vector<double>& direct, HitRecords& records) {
    const uint32_t vertexCount = uint32_t(frame.positions.size());
    const uint32_t rayCount = settings.raysPerVertex;
    const int order = settings.order;
    const uint32_t n2 = uint32_t(order * order);
    const std::vector<glm::dvec3> lattice = sphericalFibonacci(rayCount);
    const double solidAngle = 4.0 * std::numbers::pi / double(rayCount);

    direct.assign(size_t(vertexCount) * kSideCount * n2, 0.0);
    records.raysPerPoint = rayCount;
    records.hits.resize(size_t(vertexCount) * rayCount);
    records.counts.assign(vertexCount, 0);

    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, vertexCount, 8), [&](const tbb::blocked_range<uint32_t>& range) {
        double basis[sh::kMaxOrder * sh::kMaxOrder];
        for (uint32_t v = range.begin(); v != range.end(); ++v) {
            const glm::dvec3 normal = glm::dvec3(frame.normals[v]);
            const glm::vec3 position = frame.positions[v];
            const glm::vec3 offset = frame.normals[v] * settings.rayOffset;
            double* front = direct.data() + size_t(v) * kSideCount * n2;
            double* back = front + n2;
            clampedCosineTransfer(order, normal, front);
            clampedCosineTransfer(order, -normal, back);

            const glm::dmat3 rotation = randomRotation(settings.seed, v);
            HitRecord* hits = records.hits.data() + size_t(v) * rayCount;
            uint32_t hitCount = 0;
            for (uint32_t k = 0; k < rayCount; ++k) {
                const glm::dvec3 direction = rotation * lattice[k];
                const double cosine = glm::dot(normal, direction);
                if (cosine == 0.0)
                    continue; // in the tangent plane: no weight on either side
                const bool backSide = cosine < 0.0;
                Ray ray;
                ray.origin = backSide ? position - offset : position + offset;
                ray.direction = glm::vec3(direction);
                const RayHit hit = scene.intersect(ray);
                if (hit.triangle == kNoHit)
                    continue;

                const double weight = solidAngle * std::abs(cosine);
                sh::evaluate(order, direction, basis);
                double* side = backSide ? back : front;
                for (uint32_t i = 0; i < n2; ++i)
                    side[i] -= weight * basis[i];

                HitRecord& record = hits[hitCount++];
                record.target = backSide ? kReceiverBackSide : 0u;
                if (hit.triangle == kGroundHit) {
                    record.target |= kGroundTarget;
                } else {
                    record.target |= hit.triangle;
                    if (glm::dot(frame.triangleFronts[hit.triangle], ray.direction) >= 0.0f)
                        record.target |= kHitBackSide;
                }
                record.u = hit.u;
                record.v = hit.v;
                record.weight = float(weight);
            }
            records.counts[v] = hitCount;
        }
    });
}

} // namespace meadow::transfer::detail
