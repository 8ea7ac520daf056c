// Camera and sky parameters turned into the per-frame uniform block (gpu::GpuFrame).
// Projection: Vulkan clip space, reversed Z with an infinite far plane (depth 1 at the near
// plane, 0 at infinity) for precision over a field that reaches the horizon.
#pragma once

#include "gpu_types.h"

#include <array>
#include <glm/glm.hpp>

namespace meadow {

struct Camera {
    glm::vec3 eye{0.0f, 2.0f, -10.0f};
    glm::vec3 target{0.0f, 0.0f, 0.0f};
    float fovYDegrees = 55.0f;
    float nearPlane = 0.05f;
    float farCull = 2000.0f; // instances beyond this distance are culled
};

glm::mat4 viewMatrix(const Camera& camera);
glm::mat4 projectionMatrix(const Camera& camera, float aspect);

// World-space frustum planes (normal pointing inside, normalised): left, right, bottom, top,
// near from the view-projection matrix (Gribb & Hartmann 2001), and a far plane at farCull.
std::array<glm::vec4, 6> frustumPlanes(const Camera& camera, const glm::mat4& viewProj);

// The analytic test sky: sun direction, colour and sky radiance for a local solar hour (0-24).
struct SkyState {
    glm::vec3 sunDirection;
    float sunIntensity;
    glm::vec3 sunColor;
    glm::vec3 zenith;
    glm::vec3 horizon;
    float exposure;
};
SkyState skyForTimeOfDay(float hours);

// The frame's uniform block for a width x height image. The field renderer fills in what it owns
// (its LOD count and parameters: updateFrameUniforms).
gpu::GpuFrame makeFrameUniforms(const Camera& camera, uint32_t width, uint32_t height, const SkyState& sky,
                                uint32_t instanceCount, uint32_t meshCount, uint32_t frameIndex);

} // namespace meadow
