#include "render/cull_reference.h"

#include "near_raster.h"

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

int nearRasterReference(const gpu::GpuFrame& frame, const gpu::GpuInstance& instance) {
    if ((frame.motion.w & gpu::kFrameNearRaster) == 0u)
        return 0;
    Sphere s = boundingSphere(instance);
    const glm::vec3 d = s.center - glm::vec3(frame.cameraPosition);
    const float dist = std::max(std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z), 1e-3f);
    const float screenRadius = s.radius * frame.lodScreen.x / dist;
    const bool taken =
        screenRadius <= gpu::kNearMaxRadius && planeDistance(frame.frustumPlanes[4], s.center) > s.radius;
    return taken ? gpu::nearSubpixelFor(screenRadius) : 0;
}

gpu::GpuLodChoice lodReference(const gpu::GpuFrame& frame, const gpu::GpuInstance& instance, uint32_t index,
                               float previousX) {
    Sphere s = boundingSphere(instance);
    const glm::vec3 d = s.center - glm::vec3(frame.cameraPosition);
    const float dist = std::max(std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z), 1e-3f);
    const float screenRadius = s.radius * frame.lodScreen.x / dist;
    gpu::GpuLodParams p{};
    for (int i = 0; i < 4; ++i)
        p.switchRadius[i] = frame.lodSwitchRadius[i];
    p.band = frame.lodBand.x;
    p.jitter = frame.lodBand.y;
    p.hysteresis = frame.lodBand.z;
    p.farRadius = frame.lodBand.w;
    return gpu::lodSelect(p, screenRadius, gpu::lodInstanceRandom(index), previousX);
}

std::vector<std::vector<uint32_t>> cullReferenceBuckets(const gpu::GpuFrame& frame,
                                                        std::span<const gpu::GpuInstance> instances,
                                                        std::vector<float>& lodX) {
    const uint32_t lodCount = std::max(frame.counts.w, 1u);
    std::vector<std::vector<uint32_t>> buckets(frame.counts.y);
    for (uint32_t i : cullReference(frame, instances)) {
        const uint32_t first = instances[i].mesh * lodCount;
        if (lodCount == 1) {
            buckets[first].push_back(i);
            continue;
        }
        const gpu::GpuLodChoice c = lodReference(frame, instances[i], i, lodX[i]);
        lodX[i] = c.x;
        // As cull.comp: the far field's instances go to its list, not to a bucket.
        const bool far = c.lod == gpu::kLodFar, farFade = c.fadeLod == gpu::kLodFar && !far;
        const uint32_t lod = std::min(c.lod, lodCount - 1), fadeLod = std::min(c.fadeLod, lodCount - 1);
        if (!far)
            buckets[first + lod].push_back(i);
        if (fadeLod != lod && !farFade)
            buckets[first + fadeLod].push_back(i | gpu::kLodFadeEntryBit);
    }
    for (std::vector<uint32_t>& b : buckets)
        std::sort(b.begin(), b.end());
    return buckets;
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
