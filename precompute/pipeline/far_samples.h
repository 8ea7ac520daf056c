// The far field's surface samples of every clump and rock (library/far_samples.h; issue 18):
// points drawn uniformly by area over LOD 0's triangles, those on atlas texels with alpha < 128
// rejected and drawn again, then shuffled (Fisher-Yates) so any prefix is an unbiased subset.
// Deterministic for a seed, whatever the thread count.
#pragma once

#include "library/library.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace meadow {

// What one clump or rock offers to sample.
struct FarSurface {
    std::vector<glm::vec3> positions;      // per vertex, the mean pose
    std::vector<glm::vec3> normals;        // per vertex, unit
    std::vector<glm::vec2> uvs;            // per vertex, atlas UVs (plants/atlas.h); unused without an atlas
    std::vector<uint32_t> indices;         // LOD 0's triangles, into positions
    std::vector<uint32_t> farVertices;     // the last LOD's vertices: the ones a sample may play
    std::vector<uint32_t> vertexBlock;     // per vertex its motion block (rod); empty: one block
    const RgbaImage* atlas = nullptr;      // albedo and alpha test at the UV; null: constantAlbedo, no test
    uint32_t constantAlbedo = 0xff000000u; // RGBA8 (FarSample::albedo) without an atlas
    bool closed = false;                   // a closed surface (a rock): the splat pass hides samples facing away
};

// A clump's LOD 0 (its lods[0] triangles over the mean-pose mesh), its last LOD's vertices and its
// rods, textured by `atlas` (which must outlive the surface).
FarSurface farSurfaceOfClump(const LibraryClump& clump, const RgbaImage& atlas);
// A rock's LOD 0, its last LOD's vertices, one block, kRockAlbedo sRGB-encoded.
FarSurface farSurfaceOfRock(const LibraryRock& rock);

// `count` samples of the surface from `seed`:
// - a triangle picked with probability ∝ its area, a point uniform in it (square-root
//   barycentrics); with an atlas, a point whose texel (nearest: the texel containing the
//   interpolated UV) has alpha < 128 is rejected and drawn again, at most 64 x count + 1024 draws
//   in all (a surface that is almost all cut out keeps fewer samples);
// - the normal: the vertex normals interpolated and normalised (the triangle's geometric normal,
//   turned to the vertex normals' side, where they cancel);
// - the albedo: that texel's rgb (nearest, no filtering), alpha 255;
// - the vertex: of the triangle's vertex nearest the point, its block; the nearest far vertex of
//   that block, or the nearest far vertex of all where the block has none;
// - then a Fisher-Yates shuffle. area = LOD 0's area x accepted / drawn.
FarSamples buildFarSamples(const FarSurface& surface, uint32_t count, uint64_t seed);

// The coverage gains of far.gain (far_splat.h), measured: per size and elevation bin, the surface
// is seen from 32 azimuths, four to each visibility view's cell (each with its own sub-pixel
// offset), orthographically at that size (pixels per metre = size / sqrt(far.area)), and
//   - LOD 0 is rasterised as the mesh pass would, a point is covered where it falls in a triangle
//     whose texel there (nearest, mip 0) has alpha >= 128, at ceil(32 / size) x ceil(32 / size)
//     points per pixel: the pixels it covers on average over where the pixel grid falls;
//   - farSampleCount(...) samples at kFarDefaultDensity, each view a run of them from its own start
//     (a / 32 of the way through the shuffled list; farSampleSlot), those in sight by the bit the
//     splat pass would take there (farVisibilityBitAt), are splatted as the splat pass does
//     (footprint, square side, far side of closed surfaces hidden), each covering with its
//     probability independently, and the expected covered pixels summed;
// and the gain is the factor on every footprint, in [1/4, 8], whose expected coverage equals LOD
// 0's over the 32 views (bisection on the monotone coverage).
std::array<float, gpu::kFarGainSizes * gpu::kFarGainElevations> farCoverageGains(const FarSurface& surface,
                                                                                 const FarSamples& far);

// One cell of that measurement: the gain at `size` px and an eye elevation of `elevationUnits`
// (30 degree units, farEyeElevation's: 0 to kFarGainElevations - 1), also between the table's bins
// (a probe of its interpolation); farCoverageGains holds it at the bins. 1 for no samples.
float farCoverageGainAt(const FarSurface& surface, const FarSamples& far, float size, float elevationUnits);

// The seed of clump `index` (or of rock `index`) of a scene.
uint64_t farSampleSeed(uint64_t sceneSeed, uint32_t index, bool rock);

// Fills clumps[].far and field.rocks[].far (their LODs built), in parallel over clumps and rocks.
void buildLibraryFarSamples(Library& library, uint32_t samplesPerClump, uint64_t sceneSeed);

} // namespace meadow
