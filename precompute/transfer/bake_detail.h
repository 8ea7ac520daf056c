// Internal to precompute/transfer: the pieces of one frame's bake, shared by its .cpp files.
//
// The bake follows Sloan, Kautz and Snyder 2002 (section 4, "shadowed" and "interreflected"
// diffuse transfer): rays are cast once per frame, every hit is recorded (which triangle, where,
// which of its sides faced the ray, the ray's cosine weight), then each interreflection bounce is
// a pass over the records that gathers only the previous bounce's transfer. No ray is cast twice.
//
// Arrays of transfer use doubles while baking and the layouts of transfer.h: per vertex, side,
// channel, coefficient; scalar (colourless) arrays drop the channel.
#pragma once

#include "transfer/ray_scene.h"
#include "transfer/transfer.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace meadow::transfer::detail {

// HitRecord::target: a triangle index with two flag bits, or kGroundTarget.
inline constexpr uint32_t kHitBackSide = 1u << 31;      // the hit triangle showed its back to the ray
inline constexpr uint32_t kReceiverBackSide = 1u << 30; // the ray left the receiving vertex's back side
inline constexpr uint32_t kTargetMask = (1u << 30) - 1;
inline constexpr uint32_t kGroundTarget = kTargetMask; // with u, v = the ground hit's world x, z

// One ray that hit something. weight = (solid angle per ray) * |cos| to the receiver's normal, so
// that irradiance from radiance B at the hit is weight * B (the Monte-Carlo estimate of
// the integral of B cos over the sphere).
struct HitRecord {
    uint32_t target = 0;
    float u = 0.0f;
    float v = 0.0f;
    float weight = 0.0f;
};

// Hits of every receiving point: point p's hits are hits[p * raysPerPoint ...] for counts[p].
struct HitRecords {
    uint32_t raysPerPoint = 0;
    std::vector<HitRecord> hits;
    std::vector<uint32_t> counts;
};

// One frame's geometry as the bake sees it. normals are unit; triangleFronts[t] is triangle t's
// geometric normal turned to agree with the sum of its vertex normals: a ray with
// dot(triangleFronts[t], direction) < 0 sees the Front side of t.
struct FrameGeometry {
    std::span<const glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::span<const uint32_t> indices;
    std::vector<glm::vec3> triangleFronts;
};

// Checks one frame against the baker's vertex count; normalises normals, orients triangles.
FrameGeometry prepareFrame(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                           std::span<const uint32_t> indices, uint32_t vertexCount);

// Ground grid points, row-major: point r * resolution + c (see GroundTransfer).
glm::vec3 groundPoint(const BakeSettings& settings, uint32_t column, uint32_t row);

// shadowed_transfer.cpp. Casts settings.raysPerVertex rays from every vertex and writes the
// direct, visibility-times-cosine transfer of each side (scalar: vertexCount * 2 * order^2)
// and the hit records of every vertex (raysPerPoint = raysPerVertex).
void castVertexRays(const RayScene& scene, const FrameGeometry& frame, const BakeSettings& settings,
                    std::vector<double>& direct, HitRecords& records);

// ground_transfer.cpp. Direct transfer of every ground grid point (scalar: points * order^2) and
// the hit records of its rays (upper hemisphere only, so none hits the ground).
void castGroundRays(const RayScene& scene, const FrameGeometry& frame, const BakeSettings& settings,
                    std::vector<double>& direct, HitRecords& records);

// ground_transfer.cpp. The ground as a source of light for the clump's first bounce (the ground
// model of transfer.h): its direct transfer at world (x, z) is bilinear in the ground grid's
// direct transfer inside the grid, the unoccluded clamped cosine about +y outside it or when
// there is no grid; it reflects groundAlbedo / pi of it.
struct GroundSource {
    const BakeSettings* settings = nullptr;
    std::span<const double> gridDirect;                   // points * order^2, empty without a grid
    std::vector<double> unoccluded;                       // C(+y), order^2
    void directAt(double x, double z, double* out) const; // writes order^2 values
};
GroundSource makeGroundSource(const BakeSettings& settings, std::span<const double> gridDirect);

// interreflection.cpp. The radiance leaving every vertex side per unit sky, channel by channel:
// exitance[v][side][c] = albedo[v][c] / pi * transfer[v][side][c] (vertexCount * 2 * 3 * order^2).
std::vector<double> vertexExitance(std::span<const double> transfer, std::span<const glm::vec3> albedo, int order);

// interreflection.cpp. Irradiance transfer gathered by point p from its records: the exitance of
// the side of each hit triangle that faced the ray, interpolated with the hit's barycentrics,
// times the ray's weight; ground hits take the ground's exitance when `ground` is given, else
// nothing. out: 2 sides * 3 channels * order^2, added to (each record names the receiving side).
void gatherPoint(const HitRecords& records, uint32_t point, std::span<const uint32_t> indices,
                 std::span<const double> exitance, const GroundSource* ground, int order, double* out);

// interreflection.cpp. The whole interreflected transfer of the clump (Sloan et al. 2002, 4):
// starting from the direct term, `settings.bounces` gathers, each of the previous bounce only,
// with translucency applied to every bounce; returns the sum (vertexCount * 2 * 3 * order^2).
std::vector<double> interreflect(const HitRecords& records, std::span<const double> direct,
                                 std::span<const uint32_t> indices, std::span<const glm::vec3> albedo,
                                 std::span<const float> translucency, const BakeSettings& settings,
                                 const GroundSource& ground);

// interreflection.cpp. T_side += tau T_other side for every vertex (the translucency model of
// transfer.h). raw and out: vertexCount * 2 * 3 * order^2; out is overwritten.
void applyTranslucency(std::span<const double> raw, std::span<const float> translucency, int order,
                       std::span<double> out);

} // namespace meadow::transfer::detail
