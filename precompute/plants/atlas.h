// The iris texture atlas (Cove & James 2004, section 2.4: one texture for every iris so the whole
// field draws without texture switches). Each PartKind owns one rectangle; its texture is
// generated procedurally: leaf gradient with parallel veins, stem, violet falls with darker veins
// and the yellow-orange beard, lighter standards, style arms, and a plain green for Other.
//
// Pixels: RGBA, 8 bits, sRGB-encoded colour, row 0 first. Texel (x, y) covers UV
// [x / width, (x + 1) / width] × [y / height, (y + 1) / height], so UV (0, 0) is the first byte
// (Vulkan's convention for an image uploaded row 0 first). Alpha is 255 everywhere: petal and leaf
// outlines come from the geometry, not from cutouts.
#pragma once

#include "library/mesh.h"
#include "plant.h"

#include <array>
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <vector>

namespace meadow {

// A rectangle in UV space. Part textures are painted a few texels beyond it, so bilinear
// filtering at its border does not pick up a neighbour's colour.
struct AtlasRegion {
    glm::vec2 min{0.0f};
    glm::vec2 max{0.0f};

    // Maps a part's local coordinates (u across, v along, each 0..1) into the region.
    glm::vec2 map(glm::vec2 local) const { return min + (max - min) * local; }
    bool contains(glm::vec2 uv) const { return uv.x >= min.x && uv.x <= max.x && uv.y >= min.y && uv.y <= max.y; }
};

// Where each part sits in the iris atlas; independent of the atlas size, so meshes can be built
// before (or without) the atlas.
AtlasRegion irisAtlasRegion(PartKind part);

// Texels [x0, x1) x [y0, y1) of an atlas.
struct AtlasCell {
    uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// Where an imported plant's materials are painted (gltf_import.h, paintImportedPlant): the
// atlas's largest square cell, the one the iris falls use (a scene of imported plants draws no
// iris), in texels of an atlas `size` texels wide.
AtlasCell importAtlasCell(uint32_t size);

struct TextureAtlas {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba; // width * height * 4 bytes, see the header comment

    AtlasRegion region(PartKind part) const { return irisAtlasRegion(part); }
};

// Generates the atlas; `size` (a power of two, 64 .. 8192) is its width and height. The same
// size and seed give the same bytes.
TextureAtlas makeIrisAtlas(uint32_t size, uint64_t seed);

// Writes the atlas as an image through OpenImageIO (the extension picks the format; PNG keeps
// the 8-bit sRGB bytes exactly). The file appears whole or not at all: pixels go to a temporary
// file in the same folder, which is renamed over `path`. Throws meadow::Error naming the path.
void writeAtlas(const std::filesystem::path& path, const TextureAtlas& atlas);

} // namespace meadow
