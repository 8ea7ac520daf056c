#include "render/camera.h"
#include "render/cull_reference.h"

#include <gtest/gtest.h>

using namespace meadow;

namespace {

gpu::GpuFrame frameFor(const Camera& camera, uint32_t width = 1600, uint32_t height = 900) {
    return makeCameraUniforms(camera, width, height, 1000000);
}

gpu::GpuInstance at(glm::vec3 p, float radius = 0.5f, float scale = 1.0f) {
    gpu::GpuInstance inst{};
    inst.positionScale = glm::vec4(p, scale);
    inst.boundingRadius = radius;
    return inst;
}

} // namespace

TEST(CullReference, PlanesAreNormalisedAndPointInside) {
    Camera c;
    c.eye = {0, 1, 0};
    c.target = {0, 1, 10};
    gpu::GpuFrame f = frameFor(c);
    for (const glm::vec4& p : f.frustumPlanes) {
        EXPECT_NEAR(glm::length(glm::vec3(p)), 1.0f, 1e-5f);
        // A point straight ahead is inside every plane.
        EXPECT_GT(glm::dot(glm::vec3(p), glm::vec3(0, 1, 5)) + p.w, 0.0f);
    }
}

TEST(CullReference, ClassifiesAroundTheCamera) {
    Camera c;
    c.eye = {0, 1, 0};
    c.target = {0, 1, 10};
    c.fovYDegrees = 60.0f;
    c.farCull = 100.0f;
    gpu::GpuFrame f = frameFor(c, 900, 900);
    EXPECT_TRUE(instanceVisible(f, at({0, 0.5f, 10})));    // ahead
    EXPECT_FALSE(instanceVisible(f, at({0, 0.5f, -10})));  // behind
    EXPECT_FALSE(instanceVisible(f, at({30, 0.5f, 10})));  // far to the side
    EXPECT_FALSE(instanceVisible(f, at({0, 0.5f, 150})));  // beyond farCull
    EXPECT_TRUE(instanceVisible(f, at({0, 0.5f, 99.8f}))); // sphere reaches back over farCull
    // Half-angle 30 degrees: at z = 10 the edge is at x = 5.77. A sphere of radius 1 centred
    // just outside still touches the frustum (conservative: kept), one well outside does not.
    EXPECT_TRUE(instanceVisible(f, at({6.2f, 0.5f, 10}, 1.0f)));
    EXPECT_FALSE(instanceVisible(f, at({8.0f, 0.5f, 10}, 1.0f)));
    // Scale grows the sphere: radius 1 x scale 3 reaches back into view.
    EXPECT_TRUE(instanceVisible(f, at({8.0f, -1.0f, 10}, 1.0f, 3.0f)));
}

TEST(CullReference, MarginAgreesWithDecision) {
    Camera c;
    gpu::GpuFrame f = frameFor(c);
    for (int i = 0; i < 2000; ++i) {
        glm::vec3 p(float(i % 50) - 25.0f, 0.0f, float(i / 50) - 20.0f);
        gpu::GpuInstance inst = at(p);
        EXPECT_EQ(instanceVisible(f, inst), visibilityMargin(f, inst) >= 0.0f) << i;
    }
}

TEST(CullReference, RespectsInstanceCount) {
    Camera c;
    c.eye = {0, 1, 0};
    c.target = {0, 1, 10};
    gpu::GpuFrame f = frameFor(c);
    std::vector<gpu::GpuInstance> all(10, at({0, 0, 5}));
    f.counts.x = 4;
    EXPECT_EQ(cullReference(f, all), (std::vector<uint32_t>{0, 1, 2, 3}));
}
