#include "render/cull_reference.h"

#include <algorithm>
#include <cmath>

namespace meadow {
namespace {

struct Sphere {
    glm::vec3 center;
    float radius;
};

Sphere boundingSphere(const gpu::GpuInstance& inst) {
    float scale = std::abs(inst.positionScale.w); // negative: mirrored, the same sphere
    // Same expression order as cull.comp.glsl.
    glm::vec3 center = glm::vec3(inst.positionScale) + glm::vec3(0.0f, inst.boundingRadius * scale * 0.5f, 0.0f);
    return {center, inst.boundingRadius * scale};
}

float planeDistance(const glm::vec4& plane, const glm::vec3& p) {
    return plane.x * p.x + plane.y * p.y + plane.z * p.z + plane.w;
}

} // namespace

bool instanceVisible(const gpu::GpuFrame& frame, const gpu::GpuInstance& instance) {
    Sphere s = boundingSphere(instance);
    for (int i = 0; i < 6; ++i)
        if (planeDistance(frame.frustumPlanes[i], s.center) < -s.radius)
            return false;
    return true;
}

float visibilityMargin(const gpu::GpuFrame& frame, const gpu::GpuInstance& instance) {
    Sphere s = boundingSphere(instance);
    float margin = 1e30f;
    for (int i = 0; i < 6; ++i)
        margin = std::min(margin, planeDistance(frame.frustumPlanes[i], s.center) + s.radius);
    return margin;
}

std::vector<uint32_t> cullReference(const gpu::GpuFrame& frame, std::span<const gpu::GpuInstance> instances) {
    std::vector<uint32_t> visible;
    uint32_t count = std::min<uint32_t>(frame.counts.x, static_cast<uint32_t>(instances.size()));
    for (uint32_t i = 0; i < count; ++i)
        if (instanceVisible(frame, instances[i]))
            visible.push_back(i);
    return visible;
}

} // namespace meadow
