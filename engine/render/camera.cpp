#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace meadow {

glm::mat4 viewMatrix(const Camera& c) {
    return glm::lookAtRH(c.eye, c.target, glm::vec3(0.0f, 1.0f, 0.0f));
}

glm::mat4 projectionMatrix(const Camera& c, float aspect) {
    float f = 1.0f / std::tan(glm::radians(c.fovYDegrees) * 0.5f);
    glm::mat4 p(0.0f);
    p[0][0] = f / aspect;
    p[1][1] = -f;          // Vulkan's y points down
    p[2][3] = -1.0f;       // w_clip = -z_view
    p[3][2] = c.nearPlane; // z_clip = near: depth = near / distance (reversed, infinite)
    return p;
}

std::array<glm::vec4, 6> frustumPlanes(const Camera& c, const glm::mat4& m) {
    // Rows of the (column-major) matrix.
    glm::vec4 r0(m[0][0], m[1][0], m[2][0], m[3][0]);
    glm::vec4 r1(m[0][1], m[1][1], m[2][1], m[3][1]);
    glm::vec4 r2(m[0][2], m[1][2], m[2][2], m[3][2]);
    glm::vec4 r3(m[0][3], m[1][3], m[2][3], m[3][3]);
    std::array<glm::vec4, 6> planes = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r3 - r2, glm::vec4(0.0f)};
    for (int i = 0; i < 5; ++i)
        planes[i] /= glm::length(glm::vec3(planes[i]));
    glm::vec3 forward = glm::normalize(c.target - c.eye);
    planes[5] = glm::vec4(-forward, glm::dot(forward, c.eye) + c.farCull);
    return planes;
}

gpu::GpuFrame makeCameraUniforms(const Camera& camera, uint32_t width, uint32_t height, uint32_t instanceCount) {
    gpu::GpuFrame f{};
    const glm::mat4 projection = projectionMatrix(camera, float(width) / float(height));
    f.viewProj = projection * viewMatrix(camera);
    // A sphere of radius R at distance d covers R * lodScreen.x / d pixels vertically.
    f.lodScreen = glm::vec4(0.5f * float(height) * std::abs(projection[1][1]), 0.0f, 0.0f, 0.0f);
    f.inverseViewProj = glm::inverse(f.viewProj);
    std::array<glm::vec4, 6> planes = frustumPlanes(camera, f.viewProj);
    for (int i = 0; i < 6; ++i)
        f.frustumPlanes[i] = planes[i];
    f.cameraPosition = glm::vec4(camera.eye, 1.0f);
    f.counts = glm::uvec4(instanceCount, 0u, 0u, 0u);
    return f;
}

} // namespace meadow
