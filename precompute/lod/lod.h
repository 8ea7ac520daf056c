// Levels of detail for plant clumps (docs/ARCHITECTURE.md, Levels of detail; Cove & James 2004,
// section 2.3: "a quadric-based reduction method, enhanced to appropriately weight the lighting and
// motion data").
//
// Three algorithms, one .cpp each:
//   simplify.cpp    half-edge collapses ordered by an attribute quadric (Garland & Heckbert 1997,
//                   1998; Hoppe 1999). Every surviving vertex is an ORIGINAL vertex, so it keeps
//                   its exact motion rows, rod, light transfer, UV and part.
//   lod_chain.cpp   five LODs from triangle budgets, each ordered for the vertex cache and for
//                   vertex fetch (meshoptimizer; Forsyth's cache model).
//   lod_error.cpp   the error of a LOD against the full mesh: geometric (Hausdorff, RMS) at rest
//                   and over deformed frames, lighting and motion, sampled on both surfaces.
// lod_attributes.cpp turns a clump's motion basis and light transfer into attribute groups.
//
// Conventions: vertex indices are indices of the input mesh ("original vertices"); every output
// vector is owned by the caller. Every function validates its input and throws meadow::Error
// whose message starts with the function's subject ("simplify:", "LOD:", "LOD error:") and says
// what is wrong and where. Everything is deterministic: the same input gives the same bytes, for
// any TBB thread count.
#pragma once

#include "library/clump.h"

#include "library/motion_basis.h" // kLodCount

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace meadow {

struct VertexAppearance;
struct PlantMesh;

// ---------------------------------------------------------------------------------------------
// Simplification

// Per-vertex values the simplifier should keep faithful, e.g. a vertex's mean light transfer or
// its motion basis rows. `values` holds vertexCount x width floats, vertex-major. `weight` is in
// metres per attribute unit: an attribute that is off by 1/weight costs as much as a surface that
// is off by one metre (Hoppe 1999 adds attribute and geometric deviations in one quadric, so they
// need a common unit).
struct AttributeGroup {
    std::string name; // for error messages
    std::span<const float> values;
    uint32_t width = 0;
    float weight = 1.0f;
};

struct SimplifyInput {
    std::span<const glm::vec3> positions;
    std::span<const glm::vec3> normals; // one per vertex; enter the quadric as an attribute
    std::span<const glm::vec2> uvs;     // one per vertex; idem. A UV seam is two vertices at one position
    std::span<const uint32_t> indices;  // triangle list
    std::vector<AttributeGroup> attributes;
    // Optional, one per vertex (e.g. the rod a vertex follows, rodGroups()). With
    // SimplifyOptions::separateGroups, no vertex is ever collapsed onto a vertex of another group.
    std::span<const uint32_t> collapseGroups;
};

struct SimplifyOptions {
    // Defaults chosen on the iris clumps of tests/precompute/lod: heavier normal or UV weights (0.02, 0.5)
    // raised the geometric RMS error of LOD 1 by half for no gain in lighting error.
    float normalWeight = 0.01f;  // metres per unit of normal difference
    float uvWeight = 0.1f;       // metres per UV unit: a 1 % texture shift costs like 1 mm
    float boundaryWeight = 4.0f; // weight of the planes through boundary edges, perpendicular to
                                 // their face, relative to the faces' own (G&H 1997, section 6.1)
    bool separateGroups = true;  // never collapse across collapse groups (see SimplifyInput)
    float minNormalDot = 0.2f;   // a collapse may turn a triangle's normal by at most acos(this)
    bool allowFallback = true;   // see SimplifyStage
    // A collapse that changes the surface's area by dA (m^2) costs areaWeight x dA^2 (m^4, the
    // quadric's unit) on top of its quadric error. Without it a blade or petal loses its tip at no
    // cost: its border vertex slides along the outline, on the boundary planes. At 300 the iris
    // clumps' LODs 1-3 keep 97, 84 and 60 % of LOD 0's area instead of 91, 75 and 49 %, and their
    // RMS distance over the motion is lower too (docs/BENCHMARKS.md, "LODs that keep their area").
    float areaWeight = 300.0f;
};

// How far the simplifier had to go to meet a target. The constrained stage keeps every rule
// above. When no collapse is left and the target is not met, with allowFallback it first ignores
// the collapse groups, then removes whole connected components, those that stand for the least
// original surface area per triangle first (a far LOD of a clump may have fewer triangles than
// the clump has leaves, petals and stems: an iris clump cannot go below ~200 triangles without).
// Without allowFallback the result simply stops above the target (check triangleCount()). The
// rules never relaxed: no flip, no degenerate triangle, manifold, borders and seams kept.
enum class SimplifyStage : uint8_t { Constrained, GroupsRelaxed, ComponentsRemoved };

inline constexpr uint32_t kRemovedVertex = 0xffffffffu;

struct SimplifiedMesh {
    uint32_t targetTriangles = 0;
    std::vector<uint32_t> keptVertices; // original indices, ascending, each used by a triangle
    std::vector<uint32_t> indices;      // triangle list into keptVertices
    // Per original vertex: the kept vertex it was collapsed into (itself when kept), or
    // kRemovedVertex when its component was removed by the fallback (or no triangle used it).
    std::vector<uint32_t> representative;
    // The largest collapse error so far: the root mean square, over the original surface a
    // collapse stands for, of its distance plus weighted attribute deviation (metres).
    float error = 0.0f;
    SimplifyStage stage = SimplifyStage::Constrained;
    uint32_t removedComponents = 0;

    uint32_t triangleCount() const { return uint32_t(indices.size() / 3); }
};

// Simplifies step by step: each simplifyTo() continues from the previous result, with quadrics
// accumulated from the full mesh, so a sequence of decreasing targets gives nested LODs whose
// errors are measured against the original surface (see lod_chain.cpp). The constructor
// validates the input and copies what it needs: the spans need not outlive it.
class MeshSimplifier {
  public:
    MeshSimplifier(const SimplifyInput& input, const SimplifyOptions& options = {});
    ~MeshSimplifier();
    MeshSimplifier(const MeshSimplifier&) = delete;
    MeshSimplifier& operator=(const MeshSimplifier&) = delete;

    // Collapses until at most `targetTriangles` remain (> 0), or nothing more is allowed.
    SimplifiedMesh simplifyTo(uint32_t targetTriangles);

  private:
    struct State;
    std::unique_ptr<State> state_;
};

// One-shot: MeshSimplifier(input, options).simplifyTo(targetTriangles).
SimplifiedMesh simplifyMesh(const SimplifyInput& input, uint32_t targetTriangles, const SimplifyOptions& options = {});

// ---------------------------------------------------------------------------------------------
// Five levels of detail

struct LodOptions {
    // Triangle budget of each LOD as a fraction of the full mesh, non-increasing, in (0, 1].
    std::array<float, kLodCount> triangleFractions{1.0f, 1.0f / 3.0f, 1.0f / 10.0f, 1.0f / 40.0f, 1.0f / 150.0f};
    SimplifyOptions simplify;
};

struct MeshLod {
    uint32_t targetTriangles = 0;
    // Original vertex indices in the order the LOD's vertex buffer should hold them (vertex-fetch
    // order): gather every per-vertex array (motion rows, transfer, UV, ...) through this list.
    std::vector<uint32_t> vertices;
    std::vector<uint32_t> indices; // triangle list into `vertices`, in vertex-cache order
    float error = 0.0f;            // SimplifiedMesh::error
    SimplifyStage stage = SimplifyStage::Constrained;
    uint32_t removedComponents = 0;
    float acmr = 0.0f; // average cache miss ratio (16-entry FIFO) after optimisation

    uint32_t triangleCount() const { return uint32_t(indices.size() / 3); }
};

// LOD i has at most max(1, round(fraction_i x input triangles)) triangles (fewer only when the
// fallback removed a component). LOD 0 with fraction 1 is the input mesh itself, reordered (less
// any triangle with two corners at one position, which has no area).
// Coarser LODs' vertices are subsets of finer LODs' vertices.
std::array<MeshLod, kLodCount> buildLods(const SimplifyInput& input, const LodOptions& options = {});

// ---------------------------------------------------------------------------------------------
// Error report

struct LodErrorInput {
    std::span<const glm::vec3> positions; // the full mesh at rest
    std::span<const uint32_t> indices;
    // Optional: a per-vertex scalar to compare, e.g. irradiance under a test sky.
    std::span<const float> lightScalar;
    // Optional: deformed frames, each the positions of every full-mesh vertex. A LOD's vertices
    // are original vertices, so in each frame they sit where the full mesh's do.
    std::span<const std::vector<glm::vec3>> frames;
};

struct LodErrorOptions {
    // Sample points per square metre of each surface (uniform by area, stratified inside each
    // triangle), and at least one per triangle. 20,000 / m^2 is a point every ~7 mm: ~18,000 on
    // a full iris clump (0.9 m^2 of surface).
    float samplesPerSquareMetre = 20000.0f;
};

// `lodVertices`: original indices (MeshLod::vertices or SimplifiedMesh::keptVertices);
// `lodIndices`: triangles into lodVertices.
LodError measureLodError(const LodErrorInput& full, std::span<const uint32_t> lodVertices,
                         std::span<const uint32_t> lodIndices, const LodErrorOptions& options = {});

// measureLodError for each of buildLods' LODs.
std::array<LodError, kLodCount> measureLodErrors(const LodErrorInput& full, const std::array<MeshLod, kLodCount>& lods,
                                                 const LodErrorOptions& options = {});

// ---------------------------------------------------------------------------------------------
// Attribute groups from a clump's data (lod_attributes.cpp)

struct AttributeValues {
    std::vector<float> values; // vertexCount x width
    uint32_t width = 0;
};

// The rod each vertex follows (SkinBinding::rod): vertices of different rods move independently.
std::vector<uint32_t> rodGroups(const PlantMesh& mesh);

// Each vertex's basis rows of the modes used at `lod`, mode k scaled by the RMS of its coordinate
// over all frames, zero-padded to the widest block. Metres: because PCA coordinates of one block
// are uncorrelated, the squared distance between two vertices' rows of one block is their mean
// squared displacement difference over the frames. Weight 1 then weighs motion like geometry.
AttributeValues motionAttributes(const MotionBasis& motion, uint32_t lod);

// Each vertex's mean transfer T̄ (all values), divided by the RMS deviation of T̄ over the
// vertices, so that weight w costs a typical transfer difference like w metres of distance.
AttributeValues meanTransferAttributes(const VertexAppearance& appearance);

} // namespace meadow
