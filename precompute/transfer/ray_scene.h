// Ray queries for the transfer bake: one triangle mesh in an Embree 3 scene plus an optional
// ground, the infinite plane y = 0 (docs/ARCHITECTURE.md, Light transfer).
//
// The ground is intersected analytically rather than as a big quad: it is exact at any distance,
// costs nothing in the BVH, and a ray going down from a point at or below y = 0 hits it at t = 0,
// so everything under the ground is occluded. Rays going up never hit it.
//
// Determinism: the BVH is built on one thread (the full iris clump's 7,000 triangles take about two
// milliseconds), so its layout, and with it which of two triangles at exactly the same distance a
// ray reports, never depends on the machine's thread count. Queries are const and thread-safe
// once a mesh is set; each answer depends only on its ray.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <memory>
#include <span>

namespace meadow::transfer {

inline constexpr uint32_t kNoHit = 0xffffffffu;
inline constexpr uint32_t kGroundHit = 0xfffffffeu;
// A scene holds fewer triangles than this: the bake's hit records keep a triangle index in 30 bits
// next to two flag bits, with the largest 30-bit value meaning the ground (bake_detail.h).
inline constexpr uint32_t kMaxTriangles = (1u << 30) - 1;

struct Ray {
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f, 1.0f, 0.0f}; // need not be unit; t is in its units
    float tFar = std::numeric_limits<float>::infinity();
};

struct RayHit {
    uint32_t triangle = kNoHit; // a triangle index, kGroundHit or kNoHit
    // Triangle: barycentrics of its second and third vertex (the first gets 1 - u - v).
    // Ground: the world x and z of the hit point.
    float u = 0.0f;
    float v = 0.0f;
    float t = std::numeric_limits<float>::infinity();
};

class RayScene {
  public:
    // Throws meadow::Error if Embree cannot create a device.
    explicit RayScene(bool groundPlane);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    // New topology: copies positions and indices and builds the BVH. Throws meadow::Error if the
    // index count is not a multiple of 3, an index is out of range, there are kMaxTriangles or
    // more triangles, or a position is not finite. An empty index list is a scene of ground only.
    void setMesh(std::span<const glm::vec3> positions, std::span<const uint32_t> indices);

    // Same topology, moved vertices (the next frame of a deforming clump): refills the vertex
    // buffer and rebuilds the BVH. Throws meadow::Error on a size mismatch or non-finite values.
    void updatePositions(std::span<const glm::vec3> positions);

    // Closest hit along the ray in [0, tFar], ground included.
    RayHit intersect(const Ray& ray) const;

    // Whether anything, ground included, lies along the ray in [0, tFar].
    bool occluded(const Ray& ray) const;

    // A batch of closest hits, hits[i] for rays[i]; sizes must match (asserted). Sequential: the
    // caller parallelises over batches.
    void intersect(std::span<const Ray> rays, std::span<RayHit> hits) const;

    bool hasGroundPlane() const { return groundPlane_; }
    uint32_t vertexCount() const { return vertexCount_; }
    uint32_t triangleCount() const { return triangleCount_; }

  private:
    struct Embree;
    std::unique_ptr<Embree> embree_;
    bool groundPlane_ = false;
    uint32_t vertexCount_ = 0;
    uint32_t triangleCount_ = 0;

    void commit(const char* what);
    // Distance to the ground along the ray, or +infinity if it does not go down onto it.
    float groundDistance(const Ray& ray) const;
};

} // namespace meadow::transfer
