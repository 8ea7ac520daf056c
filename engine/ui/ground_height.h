// The height of the ground as drawn, under any (x, z): walk mode keeps the eye at a person's height
// above it and the fly camera stays above it. Sampled from the terrain mesh the renderer draws
// (FieldScenery::terrain), so the eye follows what is on screen, margins and plain included,
// whatever function made the mesh.
#pragma once

#include "library/mesh.h"

#include <optional>
#include <vector>

namespace meadow {

class GroundHeight {
  public:
    // Indexes the mesh's triangles by their (x, z) bounds. The mesh is world space, y up.
    explicit GroundHeight(const Mesh& terrain);

    // The highest triangle over (x, z), interpolated linearly within it; none outside the mesh.
    std::optional<float> at(float x, float z) const;

  private:
    struct Triangle {
        glm::vec2 a, b, c; // (x, z)
        glm::vec3 heights; // y at a, b, c
        glm::vec2 lo, hi;  // bounds
    };
    std::optional<float> heightIn(const Triangle& t, glm::vec2 p) const;

    std::vector<Triangle> triangles_;
    std::vector<uint32_t> large_; // triangles too large for the grid (the plain's ring)
    glm::vec2 origin_{0.0f};
    float cell_ = 1.0f;
    uint32_t cellsX_ = 0, cellsZ_ = 0;
    std::vector<uint32_t> cellStart_; // cellsX_ * cellsZ_ + 1 offsets into cellTriangles_
    std::vector<uint32_t> cellTriangles_;
};

} // namespace meadow
