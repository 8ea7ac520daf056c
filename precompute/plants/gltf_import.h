// A user's own plant from glTF 2.0 (docs/ARCHITECTURE.md, Plants), read with tinygltf, so it goes
// through the same simulation and lighting pipeline as the procedural irises.
//
// What is used: the default scene (or scene 0) and its node hierarchy with every node's
// transform; TRIANGLES primitives with POSITION (required), NORMAL (computed from the triangles
// when absent) and TEXCOORD_0 (zero when absent; it refers to the asset's own texture, which is
// not imported). Both .gltf (embedded or external buffers) and .glb.
//
// What is refused, with a meadow::Error naming the file and the reason: parse errors, a scene
// without meshes, skins ("uses skinning, which meadow cannot use"), other primitive modes,
// sparse accessors, missing POSITION, accessors that read outside their buffers (counts and
// offsets checked without overflow), out-of-range indices, a node hierarchy that is not a forest
// (a cycle or a node with two parents), and implausible sizes: the plant's
// height must be 0.02–20 m (glTF is in metres; a millimetre asset reads as "wrong units? the plant
// is 1500 m tall").
//
// The imported plant is one plant swaying as one rod: a Stem rod of kImportRodNodes nodes up the
// centre of the bounding box from its lowest to its highest point, every vertex bound to the
// segment at its height. The plant is moved so that axis starts at the origin (clump space, as
// for the irises); it is neither rotated nor scaled. All parts are PartKind::Other; the clump is
// named after the file's stem.
#pragma once

#include "plant.h"

#include <filesystem>

namespace meadow {

inline constexpr uint32_t kImportRodNodes = 8;
inline constexpr float kImportMinHeight = 0.02f; // m
inline constexpr float kImportMaxHeight = 20.0f; // m

PlantClump importGltfPlant(const std::filesystem::path& path);

} // namespace meadow
