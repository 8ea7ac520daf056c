// Ground transfer around a clump (docs/ARCHITECTURE.md, Light transfer; Cove and James 2004 bake
// the ground under each clump so it darkens beneath the plants and follows their motion).
//
// A square grid of points on y = 0 with normal +y, centred on the clump's base. Each point's
// direct transfer is its visibility times the cosine, projected on SH, estimated like a vertex's
// (shadowed_transfer.cpp: the exact unoccluded clamped cosine minus what the clump blocks) but
// over the upper hemisphere only, the ground's own half of the sphere: a hemispherical Fibonacci
// lattice turned about +y by a per-point random angle. Optionally one bounce is added: light
// leaving the clump (its full interreflected transfer, of the side facing the ground point) and
// reaching the point, so the ground picks up the clump's colour faintly.
//
// The grid's direct transfer also lights the clump from below (GroundSource): a leaf above bare
// soil gets more bounce light than one above the shadowed soil under the clump.
#include "light/sh.h"
#include "transfer/bake_detail.h"
#include "transfer/sphere_sampling.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace meadow::transfer {

glm::vec3 GroundTransfer::pointPosition(uint32_t column, uint32_t row) const {
    const float step = resolution > 1 ? size / float(resolution - 1) : 0.0f;
    return {centre.x - 0.5f * size + step * float(column), 0.0f, centre.y - 0.5f * size + step * float(row)};
}

namespace detail {

namespace {

// Streams of the ground points' rotations start far from the vertices' (which use the vertex
// index), so a point never shares a rotation with a vertex.
constexpr uint64_t kGroundStreamBase = 0x67726f756e640000ull; // "ground"

} // namespace

glm::vec3 groundPoint(const BakeSettings& settings, uint32_t column, uint32_t row) {
    GroundTransfer grid;
    grid.resolution = settings.groundGridResolution;
    grid.size = settings.groundGridSize;
    grid.centre = settings.groundCentre;
    return grid.pointPosition(column, row);
}

GroundSource makeGroundSource(const BakeSettings& settings, std::span<const double> gridDirect) {
    GroundSource source;
    source.settings = &settings;
    source.gridDirect = gridDirect;
    source.unoccluded.resize(size_t(settings.order * settings.order));
    clampedCosineTransfer(settings.order, glm::dvec3(0.0, 1.0, 0.0), source.unoccluded.data());
    return source;
}

void GroundSource::directAt(double x, double z, double* out) const {
    const size_t n2 = unoccluded.size();
    const uint32_t resolution = settings->groundGridResolution;
    if (!gridDirect.empty()) {
        const double size = settings->groundGridSize;
        const double cells = double(resolution - 1);
        const double fx = (x - (double(settings->groundCentre.x) - 0.5 * size)) / size * cells;
        const double fz = (z - (double(settings->groundCentre.y) - 0.5 * size)) / size * cells;
        if (fx >= 0.0 && fx <= cells && fz >= 0.0 && fz <= cells) {
            const uint32_t column = std::min(uint32_t(fx), resolution - 2);
            const uint32_t row = std::min(uint32_t(fz), resolution - 2);
            const double tx = fx - double(column), tz = fz - double(row);
            const double* p00 = gridDirect.data() + (size_t(row) * resolution + column) * n2;
            const double* p10 = p00 + n2;
            const double* p01 = p00 + size_t(resolution) * n2;
            const double* p11 = p01 + n2;
            for (size_t i = 0; i < n2; ++i) {
                out[i] = (1.0 - tz) * ((1.0 - tx) * p00[i] + tx * p10[i]) + tz * ((1.0 - tx) * p01[i] + tx * p11[i]);
            }
            return;
        }
    }
    std::copy(unoccluded.begin(), unoccluded.end(), out);
}

void castGroundRays(const RayScene& scene, const FrameGeometry& frame, const BakeSettings& settings,
                    std::vector<double>& direct, HitRecords& records) {
    const uint32_t resolution = settings.groundGridResolution;
    const uint32_t pointCount = resolution * resolution;
    const uint32_t rayCount = settings.groundRaysPerPoint;
    const int order = settings.order;
    const uint32_t n2 = uint32_t(order * order);
    const std::vector<glm::dvec3> lattice = hemisphericalFibonacci(rayCount);
    const double solidAngle = 2.0 * std::numbers::pi / double(rayCount);
    const glm::dvec3 up(0.0, 1.0, 0.0);

    direct.assign(size_t(pointCount) * n2, 0.0);
    records.raysPerPoint = rayCount;
    records.hits.resize(size_t(pointCount) * rayCount);
    records.counts.assign(pointCount, 0);

    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, pointCount, 4), [&](const tbb::blocked_range<uint32_t>& range) {
        double basis[sh::kMaxOrder * sh::kMaxOrder];
        for (uint32_t p = range.begin(); p != range.end(); ++p) {
            double* out = direct.data() + size_t(p) * n2;
            clampedCosineTransfer(order, up, out);
            const glm::dmat3 rotation = randomAzimuthRotation(settings.seed, kGroundStreamBase + p);
            const glm::vec3 origin =
                groundPoint(settings, p % resolution, p / resolution) + glm::vec3(0.0f, settings.rayOffset, 0.0f);
            HitRecord* hits = records.hits.data() + size_t(p) * rayCount;
            uint32_t hitCount = 0;
            for (uint32_t k = 0; k < rayCount; ++k) {
                const glm::dvec3 direction = rotation * lattice[k];
                Ray ray;
                ray.origin = origin;
                ray.direction = glm::vec3(direction);
                const RayHit hit = scene.intersect(ray);
                if (hit.triangle == kNoHit || hit.triangle == kGroundHit)
                    continue; // rays going up cannot meet the ground; kept for safety
                const double weight = solidAngle * direction.y;
                sh::evaluate(order, direction, basis);
                for (uint32_t i = 0; i < n2; ++i)
                    out[i] -= weight * basis[i];
                HitRecord& record = hits[hitCount++];
                record.target = hit.triangle;
                if (glm::dot(frame.triangleFronts[hit.triangle], ray.direction) >= 0.0f)
                    record.target |= kHitBackSide;
                record.u = hit.u;
                record.v = hit.v;
                record.weight = float(weight);
            }
            records.counts[p] = hitCount;
        }
    });
}

} // namespace detail
} // namespace meadow::transfer
