// The camera turned into its part of the per-frame uniform block (gpu::GpuFrame).
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

// The camera's part of the frame's uniform block for a width x height image (matrices, frustum,
// eye, LOD scale) with counts.x = instanceCount; the field renderer fills in the rest
// (field_renderer.h: frameUniforms).
gpu::GpuFrame makeCameraUniforms(const Camera& camera, uint32_t width, uint32_t height, uint32_t instanceCount);

} // namespace meadow
