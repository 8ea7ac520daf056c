// A user's own plant from glTF 2.0 (docs/ARCHITECTURE.md, Plants), read with tinygltf, so it goes
// through the same simulation and lighting pipeline as the procedural irises.
//
// What is used: the default scene (or scene 0) and its node hierarchy with every node's
// transform; TRIANGLES primitives with POSITION (required), NORMAL (computed from the triangles
// when absent) and TEXCOORD_0 (zero when absent); each primitive's material's base colour
// (pbrMetallicRoughness.baseColorFactor and baseColorTexture, see Colour below) and alphaMode.
// Both .gltf (embedded or external buffers and images) and .glb.
//
// What is refused, with a meadow::Error naming the file and the reason: parse errors, a scene
// without meshes, skins ("uses skinning, which meadow cannot use"), other primitive modes,
// sparse accessors, missing POSITION, accessors that read outside their buffers (counts and
// offsets checked without overflow), out-of-range indices, a node hierarchy that is not a forest
// (a cycle or a node with two parents), implausible sizes: the plant's height must be 0.02–20 m
// (glTF is in metres; a millimetre asset reads as "wrong units? the plant is 1500 m tall"), a
// base-colour texture that cannot be read or decoded (named by image index and name or file) or
// that uses another set than TEXCOORD_0, and something that is not a plant (below).
//
// Not a plant: meadow simulates thin blades and stems on elastic rods, so a closed solid such as
// a box or a boulder is refused. The mesh is welded by position (within 1e-5 of its bounding
// box's diagonal); it is a closed solid when every welded edge is shared by exactly two
// triangles. It is refused when its enclosed volume |V| (divergence theorem) fills more than
// kImportSolidMaxFill of its bounding box and its mean thickness 2|V| / area (a slab's
// thickness, a cylinder's radius, a third of a cube's edge) exceeds kImportSolidMaxThickness of
// its longest extent. The fill alone would refuse a slender closed stem (a cylinder fills 79 % of
// its box) or a closed leaf slab; the thickness alone would refuse nothing that is open. Open
// sheets (blades, petals, crossed cards), double-sided sheets welded at their rims (zero
// volume), and plants that are closed only in parts (a closed stem with open leaves) import.
//
// The imported plant is one plant swaying as one rod: a Stem rod of kImportRodNodes nodes up the
// centre of the bounding box from its lowest to its highest point, every vertex bound to the
// segment at its height. The plant is moved so that axis starts at the origin (clump space, as
// for the irises); it is neither rotated nor scaled. All parts are PartKind::Other; the clump is
// named after the file's stem.
//
// Stiffness and mass: the rod is a stem of diameter d (Rod::thickness) of a herbaceous material
// (Young's modulus kImportStemModulus, so EI = E pi d^4 / 64 in Rod::bendRigidity; an iris stem
// of 7.5 mm gets the simulator's iris stem rigidity) and density kImportStemDensity
// (Rod::linearDensity), carrying the mesh's own foliage: its one-sided area times
// kImportLeafArealDensity, each triangle's share on the node at its height (Rod::nodeMass), and
// catching the wind with half its one-sided area (leaves face it at all angles; Rod::width). The
// scene's plants.stemDiameter sets d; without it d is chosen so that the plant's own weight bends
// its tip by kImportDefaultSag of its height (a uniformly loaded cantilever, sag = q L^4 / 8 EI),
// whatever its size. The simulator caps a rod's bending stiffness where its step would become
// unstable (sim/rod_system.h): a stem stiffer than that moves as a rigid one.
//
// Colour: per primitive, its material's base colour: the base-colour texture (sRGB) times
// baseColorFactor (linear), or the factor alone when there is no texture or the primitive has no
// TEXCOORD_0. A primitive without a material keeps meadow's leaf green (the iris atlas's leaf
// colour; glTF's default white would render an untextured asset as a white plant). Vertex colours
// (COLOR_0), KHR_texture_transform and the other PBR inputs are ignored. paintImportedPlant puts
// the colours into the atlas the renderer samples and points the UVs there:
//   - Each distinct material (per whether its primitives have TEXCOORD_0) gets a cell of the
//     import region (importAtlasCell in atlas.h: the atlas's largest square, where the iris falls
//     sit; a scene of imported plants draws no iris), in a grid when there are several; each cell
//     is painted a few texels beyond its UV rectangle with its edge colours, so bilinear filtering
//     and the first mip levels do not bleed into a neighbour.
//   - UVs: glTF samplers wrap (REPEAT by default), so UVs may lie outside [0, 1]. When all of a
//     material's UVs lie in [0, 1] the texture is painted once over the cell and UVs map directly.
//     Otherwise the texture is baked down: the cell holds the texture over the material's UV
//     bounding box widened to whole periods, [floor(min), ceil(max)], sampled with the sampler's
//     own wrap modes (REPEAT, MIRRORED_REPEAT, CLAMP_TO_EDGE), and UVs map linearly into it. This
//     is exact (no seams, no duplicated vertices); the price is resolution, shared among the
//     periods, and each atlas texel averages the texture over its footprint (up to 8 x 8
//     samples), so many repeats fade towards the texture's mean instead of aliasing.
//   - Alpha: OPAQUE and BLEND are drawn opaque (alpha 255, as the whole atlas; clumps are not
//     blended). MASK is alpha-tested: the atlas alpha is 255 where the filtered texture alpha times
//     the factor's reaches alphaCutoff and 0 elsewhere; the fragment shader discards below 0.5
//     (instance.frag.glsl). The light bake does not see cut-outs: it treats the triangles whole.
#pragma once

#include "atlas.h"
#include "plant.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace meadow {

inline constexpr uint32_t kImportRodNodes = 8;
inline constexpr float kImportMinHeight = 0.02f;         // m
inline constexpr float kImportMaxHeight = 20.0f;         // m
inline constexpr float kImportSolidMaxFill = 0.1f;       // of the bounding box's volume
inline constexpr float kImportSolidMaxThickness = 0.05f; // of the longest extent
inline constexpr float kImportStemModulus = 2.0e8f;      // Pa, Young's modulus of a herbaceous stem
inline constexpr float kImportStemDensity = 700.0f;      // kg/m^3, as RodMaterial::stemDensity
inline constexpr float kImportLeafArealDensity = 0.35f;  // kg/m^2, as RodMaterial::leafArealDensity
inline constexpr float kImportDefaultSag = 0.1f;         // of the height, under the plant's own weight

struct GltfImportOptions {
    std::optional<float> stemDiameter; // m (the scene's plants.stemDiameter); none: see the header comment
};

// One material of an imported plant, as painted into the atlas (see Colour above).
struct ImportedMaterial {
    std::string name;            // the material's name or "material N", for messages and tools
    bool leafGreen = false;      // no material: meadow's leaf green, nothing else here is used
    glm::vec4 factor{1.0f};      // baseColorFactor, linear RGBA
    uint32_t width = 0;          // the texture's size; 0: no texture, the factor alone
    uint32_t height = 0;         //
    std::vector<uint8_t> texels; // width * height RGBA, 8 bits, sRGB colour, row 0 first (v = 0)
    int wrapS = 10497;           // the sampler's wrap modes (GL enums): REPEAT, MIRRORED_REPEAT 33648,
    int wrapT = 10497;           // CLAMP_TO_EDGE 33071
    bool mask = false;           // alphaMode MASK
    float alphaCutoff = 0.5f;
};

struct ImportedPlant {
    PlantClump clump; // uvs: the asset's TEXCOORD_0 until paintImportedPlant
    std::vector<ImportedMaterial> materials;
    std::vector<uint32_t> vertexMaterial; // per vertex, into materials
};

ImportedPlant importGltfPlantWithMaterials(const std::filesystem::path& path, const GltfImportOptions& options = {});

// The plant alone (its UVs the asset's own).
PlantClump importGltfPlant(const std::filesystem::path& path, const GltfImportOptions& options = {});

// Paints the plant's materials into the atlas's import region and moves every vertex's UV to its
// material's cell (leaf-green vertices to the centre of the leaf region). Only the import region
// of the atlas changes. Deterministic.
void paintImportedPlant(ImportedPlant& plant, TextureAtlas& atlas);

} // namespace meadow
