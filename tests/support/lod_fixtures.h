// Meshes for the LOD tests: small analytic shapes whose simplification has a known answer, and
// real procedural iris clumps with a synthetic deformation, light and motion.
#pragma once

#include "lod/lod.h"
#include "plants/plant.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace meadow::test {

struct TestMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;
    std::vector<uint32_t> indices;

    SimplifyInput input() const;
};

// (cellsX + 1) x (cellsY + 1) vertices on the plane z = 0 over [0, sizeX] x [0, sizeY], row-major
// (vertex = y * (cellsX + 1) + x), normals +z, UVs = position / size.
TestMesh makeGrid(uint32_t cellsX, uint32_t cellsY, float sizeX = 1.0f, float sizeY = 1.0f);

// A unit icosphere (closed, 20 x 4^subdivisions triangles), outward normals, no UVs.
TestMesh makeIcosphere(uint32_t subdivisions);

// An open tube of radius 0.05 along y (length 1), `sides` around, `rings` along; the seam column
// is duplicated (u = 0 and u = 1 at one position) like the iris stems.
TestMesh makeTube(uint32_t sides, uint32_t rings);

// A procedural iris clump (irisParamsForPreset(preset)) with the data a LOD build weighs and the
// error report measures.
struct IrisCase {
    PlantClump clump;
    std::vector<uint32_t> groups;               // rodGroups
    std::vector<float> light;                   // irradiance under a test sun, per vertex
    std::vector<std::vector<glm::vec3>> frames; // a synthetic sway, full-mesh positions
    std::vector<float> motion;                  // displacements at 4 of the frames, metres
    static constexpr uint32_t kMotionWidth = 4 * 3;

    SimplifyInput input() const; // normals, UVs, groups, light and motion attributes
    LodErrorInput errorInput() const;
};

// Built once per preset and kept: the clump with the most vertices of the first three of seed 1
// (ci: ~1,800 vertices, ~1,850 triangles; full: ~4,350 vertices, ~6,000 triangles).
const IrisCase& irisCase(const std::string& preset);

// Per vertex: the area-weighted normal of the original faces around its position (vertices at
// bitwise-equal positions share it), computed independently of the simplifier.
std::vector<glm::vec3> surfaceNormals(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices);

// Original-vertex indices of a LOD's triangle list (each index looked up in `vertices`).
std::vector<uint32_t> originalIndices(const std::vector<uint32_t>& vertices, const std::vector<uint32_t>& indices);

// Edges (as sorted vertex-index pairs) used by exactly one triangle.
std::vector<std::pair<uint32_t, uint32_t>> boundaryEdges(const std::vector<uint32_t>& indices);

} // namespace meadow::test
