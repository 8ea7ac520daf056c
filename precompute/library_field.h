// The library's field sections (internal to library.cpp): "ROCK" the rocks' meshes, their static
// light transfer and their instances; "PLCE" the terrain, the tiling and the placement figures.
#pragma once

#include "core/library_file.h"
#include "field_placement.h"
#include "light/vertex_appearance.h"

#include <string>
#include <vector>

namespace meadow {

// A rock as the library keeps it: the mesh, and its transfer (static: one bake, no gradient) and
// that of the ground around it, in transfer/transfer.h's layouts.
struct LibraryRock {
    RockMesh mesh;
    int order = 0;
    std::vector<float> transfer; // vertices x 2 sides x 3 channels x order^2
    uint32_t groundResolution = 0;
    float groundSize = 0.0f;
    std::vector<float> groundTransfer; // resolution^2 points x 3 channels x order^2
};

struct LibraryField {
    TerrainParams terrain;
    glm::vec2 windDirection{1.0f, 0.0f}; // (x, z) unit: mirrored instances reflect about its vertical plane
    PlacementStats stats;
    std::vector<LibraryRock> rocks;
    std::vector<gpu::GpuInstance> rockInstances; // mesh names the rock
};

void writeRocks(ByteWriter& w, const std::vector<LibraryRock>& rocks, const std::vector<gpu::GpuInstance>& instances);
void readRocks(ByteReader& r, const std::string& where, LibraryField& field);
void writePlacement(ByteWriter& w, const TerrainParams& terrain, glm::vec2 windDirection, const PlacementStats& stats);
void readPlacement(ByteReader& r, const std::string& where, LibraryField& field);

// Per instance: position and scale (w, -1 when mirrored), yaw, bounding radius, tint, mesh.
void writeInstances(ByteWriter& w, const std::vector<gpu::GpuInstance>& instances);
// Checks every value is finite, |scale| is 1 and mesh < meshCount.
std::vector<gpu::GpuInstance> readInstances(ByteReader& r, const std::string& where, uint32_t meshCount);

} // namespace meadow
