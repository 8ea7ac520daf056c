// The field's ground (docs/ARCHITECTURE.md, Placement): a low-frequency heightmap, a few octaves of
// smooth 2D gradient noise (Perlin's, with the quintic fade so heights have continuous second
// derivatives) drawn from the seed. Cove & James 2004 displace their clumps by a bilinearly
// interpolated low-frequency heightmap; here the noise is evaluated directly, with exact
// derivatives for the normal.
//
// Units: metres, world x and z, height along +y. Pure functions of (x, z): any order, any thread.
#pragma once

#include "library/mesh.h"

#include <cstdint>
#include <glm/glm.hpp>

namespace meadow {

struct TerrainParams {
    float amplitude = 1.0f;   // m: heights lie within [-amplitude, amplitude]; 0 is a flat plane at y = 0
    float wavelength = 40.0f; // m: the period of the first octave's lattice; octave o has wavelength / 2^o
    uint32_t octaves = 3;     // 1 .. 12, each half the amplitude of the one before
    uint64_t seed = 0;
};

class Terrain {
  public:
    // Throws meadow::Error for a negative or non-finite amplitude, a wavelength that is not a
    // positive finite number, or an octave count outside 1 .. 12.
    explicit Terrain(const TerrainParams& params);

    const TerrainParams& params() const { return params_; }
    float height(float x, float z) const;
    // (dh/dx, dh/dz), exact derivatives of height().
    glm::vec2 gradient(float x, float z) const;
    // Unit upward normal: normalize(-dh/dx, 1, -dh/dz).
    glm::vec3 normal(float x, float z) const;

  private:
    // Height and gradient in double precision.
    glm::dvec3 evaluate(double x, double z) const;

    TerrainParams params_;
    double scale_; // amplitude over the largest value the octave sum can reach
};

// The ground as drawn: the terrain over the field (tilesX x tilesY tiles of tileSize, centred on
// the origin) plus `margin` metres, sampled every `spacing` metres, exact at the grid points
// inside the field; over the margin it eases down to a flat plain at y = -amplitude - 5 cm, which
// a ring of four large quads carries out to the horizon. Normals from the drawn heights; UVs unused.
Mesh makeTerrainMesh(const TerrainParams& terrain, glm::vec2 fieldHalfExtent, float margin, float spacing);

} // namespace meadow
