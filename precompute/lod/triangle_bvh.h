// Nearest points on a triangle mesh and area-uniform sample points on it, for the LOD error report
// (lod_error.cpp). Internal to precompute/lod.
//
// The bounding volume hierarchy is the plain kind (median split of triangle centroids along the
// longest axis, up to four triangles per leaf); the query descends the nearer child first and
// prunes boxes farther than the best hit so far. The closest point on a triangle follows Ericson,
// "Real-Time Collision Detection" (2005), section 5.1.5, by Voronoi regions.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace meadow::lod_detail {

struct ClosestHit {
    uint32_t triangle = 0;        // index into the mesh's triangle list
    glm::vec3 barycentric{0.0f};  // weights of the triangle's corners 0, 1, 2
    float distanceSquared = 0.0f; // to the query point
};

// The closest point of triangle abc to p, and its barycentric coordinates. Degenerate triangles
// (zero area) fall back to the closest point of their three edges.
glm::vec3 closestPointOnTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                                 glm::vec3& barycentric);

class TriangleBvh {
  public:
    // Copies the triangles' corners; indices must be in range (checked by the caller).
    TriangleBvh(std::span<const glm::vec3> positions, std::span<const uint32_t> indices);
    // Requires at least one triangle.
    ClosestHit closest(const glm::vec3& p) const;

  private:
    struct Node {
        glm::vec3 lo, hi;
        uint32_t first = 0; // leaf: first triangle in order_; inner: left child (right is first + 1)
        uint32_t count = 0; // triangles in a leaf; 0 for an inner node
    };
    std::vector<Node> nodes_;
    std::vector<uint32_t> order_;                   // triangle indices, leaves' ranges
    std::vector<std::array<glm::vec3, 3>> corners_; // by position in order_
};

// A point on a mesh: a triangle, barycentric weights, and the area it stands for.
struct SurfaceSample {
    uint32_t triangle = 0;
    glm::vec3 barycentric{0.0f};
    float weight = 0.0f; // m^2: the triangle's area divided by its number of samples
};

// max(1, round(area x density)) samples per triangle, placed by the R2 low-discrepancy sequence
// (Roberts 2018) folded into the triangle: stratified, deterministic, no random generator.
std::vector<SurfaceSample> sampleSurface(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                                         float samplesPerSquareMetre);

} // namespace meadow::lod_detail
