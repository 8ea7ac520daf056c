#include "library/mesh.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>

namespace meadow {

Mesh makeTuftMesh(uint32_t blades, uint32_t segments) {
    Mesh mesh;
    for (uint32_t b = 0; b < blades; ++b) {
        // Blades fan out around the base with a golden-angle spread, each leaning outwards.
        float angle = static_cast<float>(b) * 2.39996f;
        float height = 0.55f + 0.35f * std::fmod(static_cast<float>(b) * 0.618f, 1.0f);
        float lean = 0.25f + 0.2f * std::fmod(static_cast<float>(b) * 0.371f, 1.0f);
        float width = 0.045f;
        glm::vec3 out(std::cos(angle), 0.0f, std::sin(angle));
        glm::vec3 side(-out.z, 0.0f, out.x);
        uint32_t base = static_cast<uint32_t>(mesh.vertices.size());
        for (uint32_t s = 0; s <= segments; ++s) {
            float t = static_cast<float>(s) / static_cast<float>(segments);
            // A blade bends outwards more towards its tip (quadratic), and tapers to a point.
            glm::vec3 spine = out * (lean * t * t * height) + glm::vec3(0.0f, height * t, 0.0f) + out * 0.03f;
            glm::vec3 tangent = glm::normalize(out * (2.0f * lean * t * height) + glm::vec3(0.0f, height, 0.0f));
            glm::vec3 normal = glm::normalize(glm::cross(side, tangent));
            float halfWidth = width * (1.0f - t * 0.92f);
            for (int e = -1; e <= 1; e += 2) {
                glm::vec3 p = spine + side * (halfWidth * static_cast<float>(e));
                mesh.vertices.push_back({glm::vec4(p, e < 0 ? 0.0f : 1.0f), glm::vec4(normal, t)});
            }
            if (s > 0) {
                uint32_t a = base + (s - 1) * 2;
                mesh.indices.insert(mesh.indices.end(), {a, a + 1, a + 2, a + 1, a + 3, a + 2});
            }
        }
    }
    mesh.fitBoundingSphere();
    return mesh;
}

void Mesh::fitBoundingSphere() {
    // The cull pass centres the sphere at half the radius above the base (the mesh grows up from
    // y = 0); grow the radius until that sphere contains every vertex.
    float r = 1e-3f;
    for (const gpu::GpuVertex& v : vertices)
        r = std::max(r, glm::length(glm::vec3(v.positionU)));
    for (;;) {
        glm::vec3 c(0.0f, r * 0.5f, 0.0f);
        bool inside = std::all_of(vertices.begin(), vertices.end(), [&](const gpu::GpuVertex& v) {
            return glm::length(glm::vec3(v.positionU) - c) <= r;
        });
        if (inside)
            break;
        r *= 1.02f;
    }
    boundingRadius = r;
}

Mesh meshAtFrame(const Mesh& meanPose, const MotionBasis& motion, uint32_t frame, uint32_t lod) {
    Mesh mesh = meanPose;
    const size_t vertices = mesh.vertices.size();
    std::vector<glm::vec3> p(vertices);
    for (size_t v = 0; v < vertices; ++v)
        p[v] = glm::vec3(mesh.vertices[v].positionU) + motion.displacement(uint32_t(v), frame, lod);
    std::vector<glm::vec3> n(vertices, glm::vec3(0.0f));
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        glm::vec3 face = glm::cross(p[b] - p[a], p[c] - p[a]);
        n[a] += face;
        n[b] += face;
        n[c] += face;
    }
    for (size_t v = 0; v < vertices; ++v) {
        glm::vec3 mean = glm::vec3(mesh.vertices[v].normalV);
        glm::vec3 normal = glm::length(n[v]) > 1e-12f ? glm::normalize(n[v]) : mean;
        if (glm::dot(normal, mean) < 0.0f)
            normal = -normal;
        mesh.vertices[v].positionU = glm::vec4(p[v], mesh.vertices[v].positionU.w);
        mesh.vertices[v].normalV = glm::vec4(normal, mesh.vertices[v].normalV.w);
    }
    return mesh;
}

float srgbToLinear(uint8_t value) {
    const float c = static_cast<float>(value) / 255.0f;
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

uint8_t linearToSrgb(float linear) {
    float c = std::clamp(linear, 0.0f, 1.0f);
    float e = c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return static_cast<uint8_t>(std::lround(e * 255.0f));
}

} // namespace meadow
