// What every plant source produces (docs/ARCHITECTURE.md, Plants): a clump of plants as one
// two-sided triangle mesh plus the elastic rods that carry it. The procedural irises (iris.h) and
// the glTF importer (gltf_import.h) both fill these structs; the simulator (precompute/sim) moves
// the rods and skins the mesh with the bindings below.
//
// Units and frames: metres, kilograms, y up; clump space has the clump's rhizomes around the
// origin on the plane y = 0. Everything here is plain data owned by the value that holds it.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace meadow {

enum class RodKind : uint8_t { Leaf, Stem };

// Which part of a plant a vertex belongs to; selects its atlas region (atlas.h) and lets tools
// tell petals from leaves. Imported plants are all Other.
enum class PartKind : uint8_t { Leaf, Stem, Fall, Standard, StyleArm, Other };
inline constexpr uint32_t kPartKindCount = 6;

// An elastic rod: a chain of nodes. Node 0 is anchored at the rhizome (y ≈ 0).
struct Rod {
    RodKind kind = RodKind::Leaf;
    uint32_t plant = 0;               // which plant of the clump
    std::vector<glm::vec3> restNodes; // >= 3 nodes, roughly evenly spaced (6–12 for a leaf or stem)
    std::vector<float> width;         // per node: blade width (leaf) or stem diameter (m); drag area and
                                      // collision radius
    float thickness = 0.0f;           // blade thickness or stem diameter (m), for bending stiffness
    float tipMass = 0.0f;             // kg carried rigidly at the last node (the top flower of a stem)
    // kg carried rigidly at each node besides tipMass (a second flower lower on the stem): one
    // entry per node, or empty when nothing else hangs on the rod.
    std::vector<float> nodeMass;
    // A rod's own material, set by the glTF importer (gltf_import.h); 0 keeps the simulator's
    // defaults for the kind (sim/rod_system.h RodMaterial: a rigidity per kind, a mass from
    // `width`), as for the procedural irises.
    float bendRigidity = 0.0f;  // EI, N m^2
    float linearDensity = 0.0f; // kg/m of the rod itself, besides tipMass and nodeMass
};

// Vertex rest position == mix(rod.restNodes[segment], rod.restNodes[segment + 1], t) + offset.
// A simulator moves the vertex with the rod's frames; vertices of flowers bind to a stem node with
// t = 1 (the top flower to the last segment) so they ride on the stem rigidly.
struct SkinBinding {
    uint32_t rod = 0;
    uint32_t segment = 0; // 0 .. restNodes.size() - 2
    float t = 0.0f;       // 0 .. 1 along the segment
    glm::vec3 offset{0.0f};
};

// One mesh for the whole clump. Thin parts (blades, petals) are single two-sided sheets: the
// renderer must not cull back faces and flips the normal towards the viewer.
struct PlantMesh {
    std::vector<glm::vec3> positions; // rest pose, clump space
    std::vector<glm::vec3> normals;   // unit length, one side of the sheet
    std::vector<glm::vec2> uvs;       // into the one texture atlas (imported plants: the asset's own
                                      // until gltf_import.h paintImportedPlant moves them there)
    std::vector<uint32_t> indices;    // triangle list
    std::vector<SkinBinding> skin;    // one per vertex
    std::vector<PartKind> parts;      // one per vertex

    size_t vertexCount() const { return positions.size(); }
    size_t triangleCount() const { return indices.size() / 3; }
};

struct PlantClump {
    std::string name;
    uint32_t plants = 0; // plants in the clump; Rod::plant is below this
    PlantMesh mesh;
    std::vector<Rod> rods;
};

// The rest position a binding reproduces (see SkinBinding).
glm::vec3 boundRestPosition(const std::vector<Rod>& rods, const SkinBinding& binding);

// Length of a rod's rest polyline (m).
float rodLength(const Rod& rod);

// Checks that a clump is consistent: per-vertex arrays of one size, indices in range, every
// value finite, rods with >= 3 nodes and matching per-node arrays, bindings naming an existing
// rod and segment. Throws meadow::Error starting with `what` (a file or clump name) on the first
// problem found.
void checkPlantClump(const PlantClump& clump, const std::string& what);

} // namespace meadow
