// The Embree scene wrapper (transfer/ray_scene.h): hits and barycentrics, the analytic ground
// plane, per-frame position updates, watertightness, and rejection of bad meshes.
#include "core/error.h"
#include "transfer/ray_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace meadow::transfer {
namespace {

// Float ray/triangle arithmetic on coordinates of order 1: a few ulps of 1.
constexpr float kHitTolerance = 1e-5f;

const std::vector<glm::vec3> kTrianglePositions = {{0, 1, 0}, {1, 1, 0}, {0, 1, 1}};
const std::vector<uint32_t> kTriangleIndices = {0, 1, 2};

Ray downFrom(glm::vec3 origin) {
    Ray ray;
    ray.origin = origin;
    ray.direction = {0.0f, -1.0f, 0.0f};
    return ray;
}

TEST(RayScene, ReportsTriangleDistanceAndBarycentrics) {
    RayScene scene(false);
    scene.setMesh(kTrianglePositions, kTriangleIndices);
    EXPECT_EQ(scene.triangleCount(), 1u);
    // The point (0.25, 1, 0.5) = 0.25 * (1, 1, 0) + 0.5 * (0, 1, 1) + 0.25 * (0, 1, 0).
    const RayHit hit = scene.intersect(downFrom({0.25f, 3.0f, 0.5f}));
    ASSERT_EQ(hit.triangle, 0u);
    EXPECT_NEAR(hit.t, 2.0f, kHitTolerance);
    EXPECT_NEAR(hit.u, 0.25f, kHitTolerance);
    EXPECT_NEAR(hit.v, 0.5f, kHitTolerance);
    // Beside the triangle, and with tFar short of it: no hit.
    EXPECT_EQ(scene.intersect(downFrom({0.8f, 3.0f, 0.8f})).triangle, kNoHit);
    Ray shortRay = downFrom({0.25f, 3.0f, 0.5f});
    shortRay.tFar = 1.5f;
    EXPECT_EQ(scene.intersect(shortRay).triangle, kNoHit);
    EXPECT_FALSE(scene.occluded(shortRay));
    shortRay.tFar = 2.5f;
    EXPECT_TRUE(scene.occluded(shortRay));
}

TEST(RayScene, GroundPlaneStopsRaysGoingDownOnly) {
    RayScene scene(true);
    scene.setMesh({}, {}); // ground only
    const RayHit down = scene.intersect(downFrom({0.5f, 2.0f, -1.5f}));
    ASSERT_EQ(down.triangle, kGroundHit);
    EXPECT_NEAR(down.t, 2.0f, kHitTolerance);
    EXPECT_NEAR(down.u, 0.5f, kHitTolerance);  // world x of the hit
    EXPECT_NEAR(down.v, -1.5f, kHitTolerance); // world z of the hit

    Ray oblique;
    oblique.origin = {0.0f, 1.0f, 0.0f};
    oblique.direction = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
    const RayHit obliqueHit = scene.intersect(oblique);
    ASSERT_EQ(obliqueHit.triangle, kGroundHit);
    EXPECT_NEAR(obliqueHit.t, std::sqrt(2.0f), kHitTolerance);
    EXPECT_NEAR(obliqueHit.u, 1.0f, kHitTolerance);

    Ray up = downFrom({0.0f, 1.0f, 0.0f});
    up.direction = {0.3f, 1.0f, 0.0f};
    EXPECT_EQ(scene.intersect(up).triangle, kNoHit);
    EXPECT_FALSE(scene.occluded(up));
    // A horizontal ray never meets the plane.
    up.direction = {1.0f, 0.0f, 0.0f};
    EXPECT_EQ(scene.intersect(up).triangle, kNoHit);

    // From below the ground, going down: blocked at once (the ground is a half-space).
    const RayHit below = scene.intersect(downFrom({0.0f, -0.5f, 0.0f}));
    EXPECT_EQ(below.triangle, kGroundHit);
    EXPECT_EQ(below.t, 0.0f);

    RayScene noGround(false);
    noGround.setMesh({}, {});
    EXPECT_EQ(noGround.intersect(downFrom({0.5f, 2.0f, -1.5f})).triangle, kNoHit);
}

TEST(RayScene, NearerTriangleHidesTheGround) {
    RayScene scene(true);
    scene.setMesh(kTrianglePositions, kTriangleIndices);
    EXPECT_EQ(scene.intersect(downFrom({0.25f, 3.0f, 0.5f})).triangle, 0u);
    EXPECT_EQ(scene.intersect(downFrom({0.8f, 3.0f, 0.8f})).triangle, kGroundHit);
    // From between the triangle and the ground, going down: the ground.
    EXPECT_EQ(scene.intersect(downFrom({0.25f, 0.5f, 0.5f})).triangle, kGroundHit);
}

TEST(RayScene, UpdatedPositionsMoveTheHits) {
    RayScene scene(false);
    scene.setMesh(kTrianglePositions, kTriangleIndices);
    const Ray ray = downFrom({0.25f, 3.0f, 0.5f});
    const RayHit first = scene.intersect(ray);
    ASSERT_EQ(first.triangle, 0u);
    // Embree's answer may differ from 2 in the last bit with the CPU's instruction set.
    EXPECT_NEAR(first.t, 2.0f, kHitTolerance);

    std::vector<glm::vec3> moved = kTrianglePositions;
    for (glm::vec3& p : moved)
        p += glm::vec3(5.0f, 0.5f, 0.0f);
    scene.updatePositions(moved);
    EXPECT_EQ(scene.intersect(ray).triangle, kNoHit);
    const RayHit hit = scene.intersect(downFrom({5.25f, 3.0f, 0.5f}));
    ASSERT_EQ(hit.triangle, 0u);
    EXPECT_NEAR(hit.t, 1.5f, kHitTolerance);

    // And back: the first frame's answer again, exactly.
    scene.updatePositions(kTrianglePositions);
    const RayHit again = scene.intersect(ray);
    EXPECT_EQ(again.triangle, 0u);
    EXPECT_EQ(again.t, first.t);
}

TEST(RayScene, ClosedCubeDoesNotLeakThroughEdgesOrCorners) {
    // A unit cube of 12 triangles; rays from its centre aimed exactly at its edges' midpoints and
    // its corners, where two or three triangles meet, must all hit (robust traversal).
    const std::vector<glm::vec3> corners = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                            {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    const std::vector<uint32_t> faces = {0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 4, 5, 0, 5, 1,
                                         3, 2, 6, 3, 6, 7, 0, 3, 7, 0, 7, 4, 1, 5, 6, 1, 6, 2};
    RayScene scene(false);
    scene.setMesh(corners, faces);
    std::vector<Ray> rays;
    for (int x = -1; x <= 1; ++x) {
        for (int y = -1; y <= 1; ++y) {
            for (int z = -1; z <= 1; ++z) {
                if (x == 0 && y == 0 && z == 0)
                    continue;
                Ray ray;
                ray.origin = {0.0f, 0.0f, 0.0f};
                ray.direction = glm::vec3(float(x), float(y), float(z));
                rays.push_back(ray);
            }
        }
    }
    std::vector<RayHit> hits(rays.size());
    scene.intersect(rays, hits);
    for (size_t i = 0; i < rays.size(); ++i) {
        EXPECT_LT(hits[i].triangle, 12u) << "ray " << i << " leaked out of the cube";
        EXPECT_NEAR(hits[i].t, 1.0f, kHitTolerance) << "ray " << i; // t in units of the direction
    }
}

TEST(RayScene, RejectsBadMeshes) {
    RayScene scene(false);
    EXPECT_THROW(scene.setMesh(kTrianglePositions, std::vector<uint32_t>{0, 1}), Error);
    EXPECT_THROW(scene.setMesh(kTrianglePositions, std::vector<uint32_t>{0, 1, 3}), Error);
    std::vector<glm::vec3> bad = kTrianglePositions;
    bad[1].y = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(scene.setMesh(bad, kTriangleIndices), Error);
    scene.setMesh(kTrianglePositions, kTriangleIndices);
    EXPECT_THROW(scene.updatePositions(bad), Error);
    EXPECT_THROW(scene.updatePositions(std::vector<glm::vec3>(2)), Error);
    try {
        scene.updatePositions(std::vector<glm::vec3>(5));
        FAIL() << "a size mismatch was accepted";
    } catch (const Error& error) {
        EXPECT_NE(std::string(error.what()).find("5 positions for a mesh of 3 vertices"), std::string::npos)
            << error.what();
    }
}

} // namespace
} // namespace meadow::transfer
