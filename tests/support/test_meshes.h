// Small meshes with known answers for the transfer bake's tests, and the helpers they share.
#pragma once

#include "light/sh.h"
#include "plants/iris.h"
#include "transfer/transfer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/glm.hpp>
#include <numbers>
#include <vector>

namespace meadow::transfer::test {

// A mesh that owns its arrays; view() hands them to the bake.
struct OwnedMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<uint32_t> indices;
    std::vector<glm::vec3> albedo;
    std::vector<float> translucency;

    TransferMesh view() const { return {positions, normals, indices, albedo, translucency}; }

    // Appends another mesh, shifting its indices.
    void append(const OwnedMesh& other) {
        const uint32_t base = uint32_t(positions.size());
        positions.insert(positions.end(), other.positions.begin(), other.positions.end());
        normals.insert(normals.end(), other.normals.begin(), other.normals.end());
        albedo.insert(albedo.end(), other.albedo.begin(), other.albedo.end());
        translucency.insert(translucency.end(), other.translucency.begin(), other.translucency.end());
        for (uint32_t i : other.indices)
            indices.push_back(base + i);
    }
};

// One triangle of side ~`size` around `centre`, lying in the plane with normal `normal` (its Front).
inline OwnedMesh triangle(glm::vec3 centre, glm::vec3 normal, float size, float translucency = 0.0f) {
    normal = glm::normalize(normal);
    const glm::vec3 helper = std::abs(normal.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 e1 = glm::normalize(glm::cross(helper, normal));
    const glm::vec3 e2 = glm::cross(normal, e1);
    OwnedMesh mesh;
    mesh.positions = {centre, centre + size * e1, centre + size * e2};
    mesh.normals.assign(3, normal);
    mesh.indices = {0, 1, 2};
    mesh.albedo.assign(3, glm::vec3(0.5f));
    mesh.translucency.assign(3, translucency);
    return mesh;
}

// A horizontal square of side `size` centred at `centre`, Front facing `up` (+y) or down.
inline OwnedMesh horizontalQuad(glm::vec3 centre, float size, bool up, glm::vec3 albedo = glm::vec3(0.5f)) {
    const float h = 0.5f * size;
    OwnedMesh mesh;
    mesh.positions = {centre + glm::vec3(-h, 0, -h), centre + glm::vec3(h, 0, -h), centre + glm::vec3(h, 0, h),
                      centre + glm::vec3(-h, 0, h)};
    mesh.normals.assign(4, glm::vec3(0, up ? 1.0f : -1.0f, 0));
    mesh.indices = {0, 1, 2, 0, 2, 3};
    mesh.albedo.assign(4, albedo);
    mesh.translucency.assign(4, 0.0f);
    return mesh;
}

// The lower half of the sphere of radius `radius` about the origin (a bowl open to the sky at
// y = 0), Front facing inward. Vertex 0 is the bottom (0, -radius, 0); rings of `segments`
// vertices rise from it to the rim.
inline OwnedMesh hemisphereBowl(float radius, uint32_t rings, uint32_t segments, glm::vec3 albedo) {
    OwnedMesh mesh;
    mesh.positions.push_back({0.0f, -radius, 0.0f});
    for (uint32_t r = 1; r <= rings; ++r) {
        const double polar = 0.5 * std::numbers::pi * double(r) / double(rings); // from the bottom
        for (uint32_t s = 0; s < segments; ++s) {
            const double azimuth = 2.0 * std::numbers::pi * double(s) / double(segments);
            mesh.positions.push_back(glm::vec3(
                glm::dvec3(std::sin(polar) * std::cos(azimuth), -std::cos(polar), std::sin(polar) * std::sin(azimuth)) *
                double(radius)));
        }
    }
    for (const glm::vec3& p : mesh.positions)
        mesh.normals.push_back(-glm::normalize(p));
    auto ringVertex = [&](uint32_t r, uint32_t s) { return 1 + (r - 1) * segments + s % segments; };
    for (uint32_t s = 0; s < segments; ++s)
        mesh.indices.insert(mesh.indices.end(), {0, ringVertex(1, s), ringVertex(1, s + 1)});
    for (uint32_t r = 1; r < rings; ++r) {
        for (uint32_t s = 0; s < segments; ++s) {
            mesh.indices.insert(mesh.indices.end(), {ringVertex(r, s), ringVertex(r + 1, s), ringVertex(r + 1, s + 1)});
            mesh.indices.insert(mesh.indices.end(), {ringVertex(r, s), ringVertex(r + 1, s + 1), ringVertex(r, s + 1)});
        }
    }
    mesh.albedo.assign(mesh.positions.size(), albedo);
    mesh.translucency.assign(mesh.positions.size(), 0.0f);
    return mesh;
}

// A procedural iris clump (plants/iris.h) with a plausible albedo per part and the default
// translucency per part.
inline OwnedMesh irisClumpMesh(const std::string& preset, uint64_t seed = 20040807) {
    const PlantClump clump = makeIrisClumps(seed, 1, irisParamsForPreset(preset)).front();
    OwnedMesh mesh;
    mesh.positions = clump.mesh.positions;
    mesh.normals = clump.mesh.normals;
    mesh.indices = clump.mesh.indices;
    const glm::vec3 partAlbedo[kPartKindCount] = {
        {0.10f, 0.30f, 0.08f}, // Leaf
        {0.12f, 0.32f, 0.10f}, // Stem
        {0.30f, 0.12f, 0.55f}, // Fall
        {0.45f, 0.30f, 0.70f}, // Standard
        {0.50f, 0.40f, 0.70f}, // StyleArm
        {0.20f, 0.30f, 0.15f}, // Other
    };
    for (PartKind part : clump.mesh.parts)
        mesh.albedo.push_back(partAlbedo[uint32_t(part)]);
    mesh.translucency = translucencyForParts(clump.mesh.parts, BakeSettings{});
    return mesh;
}

// C(n) as the brief states the oracle: c_lm = sqrt(4 pi / (2l + 1)) z_l Y_lm(n) with the clamped
// cosine's zonal coefficients z = (0.886227, 1.023327, 0.495416); order 3.
inline std::vector<double> clampedCosineOracle(const glm::dvec3& normal) {
    const double z[3] = {0.886227, 1.023327, 0.495416};
    std::vector<double> y(9);
    sh::evaluate(3, glm::normalize(normal), y.data());
    for (int l = 0; l < 3; ++l) {
        for (int m = -l; m <= l; ++m)
            y[size_t(sh::index(l, m))] *= std::sqrt(4.0 * std::numbers::pi / double(2 * l + 1)) * z[l];
    }
    return y;
}

// Settings for isolated test geometry: no ground, no grid, no bounces unless a test asks.
inline BakeSettings isolatedSettings(uint32_t rays = 256) {
    BakeSettings settings;
    settings.raysPerVertex = rays;
    settings.bounces = 0;
    settings.groundPlane = false;
    settings.groundGridResolution = 0;
    return settings;
}

// Every channel of one vertex side equals `expected` (9 values) within `tolerance`.
inline void expectSideNear(const VertexTransfer& transfer, uint32_t vertex, Side side,
                           const std::vector<double>& expected, double tolerance, const char* what) {
    for (uint32_t c = 0; c < kChannelCount; ++c) {
        const float* t = transfer.at(vertex, side, c);
        for (size_t i = 0; i < expected.size(); ++i) {
            EXPECT_NEAR(t[i], expected[i], tolerance)
                << what << ": vertex " << vertex << (side == Side::Front ? " front" : " back") << " channel " << c
                << " coefficient " << i;
        }
    }
}

inline std::vector<double> scaled(std::vector<double> v, double s) {
    for (double& x : v)
        x *= s;
    return v;
}

inline std::vector<double> sum(std::vector<double> a, const std::vector<double>& b) {
    for (size_t i = 0; i < a.size(); ++i)
        a[i] += b[i];
    return a;
}

} // namespace meadow::transfer::test
