// The precomputed radiance transfer bake (docs/ARCHITECTURE.md, Light transfer): per-vertex diffuse
// transfer of a plant clump in spherical harmonics, shadowed by the clump and the ground, with
// light through thin leaves and petals and interreflection between them (Sloan, Kautz and Snyder
// 2002, sections 4–5), baked frame by frame as the clump deforms (James and Fatahalian 2003), plus
// the transfer of a small grid of ground points around the clump so the ground darkens under and
// beside it.
//
// Conventions (every array below follows them):
//   - SH basis, order and polar axis: light/sh.h (world +y up, order n = n^2 coefficients).
//   - L is the sky's radiance in SH, per colour channel c: L_c(w) = sum_i L_c,i y_i(w), w the
//     direction light arrives from.
//   - Transfer T is irradiance transfer: the irradiance reaching one side of a surface point is
//     E_c = sum_i T_c,i L_c,i. The point's own albedo is NOT folded in, so its texture can be
//     applied per fragment; the albedo of everything the light bounced off before is. A renderer
//     computes the radiance leaving that side towards the eye as
//         exit_c = albedo_c / pi * sum_i T_c,i L_c,i            (albedo_c from the atlas, 0..1)
//     and the ground the same with the ground's albedo.
//   - Sides: a vertex's Front is the side its normal points to, Back the other one. Every mesh is
//     treated as two-sided (plants are thin sheets); closed parts such as stems simply get a dark
//     inside.
//   - Translucency tau (per vertex): a thin sheet transmits, diffusely and tinted by its own
//     albedo, tau times what it reflects: the radiance leaving a side is
//     albedo / pi * (E_side + tau * E_otherSide). T therefore already holds
//     T_side = T_own side + tau * T_other side, and the formula above stays the same.
//   - Ground: the plane y = 0 (optional) blocks every ray going down and is a diffuse reflector of
//     albedo groundAlbedo lit by the sky: inside the ground grid by the grid's own shadowed
//     transfer (bilinear), outside it by the unoccluded clamped cosine about +y. It is a source of
//     first-bounce light for the clump only; light the clump sends to the ground and back is
//     dropped (a second-order effect on a dark ground). With the ground on, the sky's SH below the
//     horizon lights nothing (those rays end on the ground); without it, it lights the clump.
//   - Ground grid points: T = visibility x cosine about +y (occluded by the clump), plus, with
//     groundBounce, the clump's light reflected onto them (one bounce off the clump, of its full
//     interreflected transfer), RGB.
//   - Estimator: every side's direct term is the exact unoccluded C(n) minus the Monte-Carlo sum
//     over the blocked rays (shadowed_transfer.cpp), so a side that sees the whole sky is exact
//     and the noise scales with what is blocked.
//   - Units: metres, clump space (plant.h), transfer dimensionless (E in the units of L times sr).
#pragma once

#include "light/sh.h"
#include "plants/plant.h"

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace meadow::transfer {

enum class Side : uint32_t { Front = 0, Back = 1 };
inline constexpr uint32_t kSideCount = 2;
inline constexpr uint32_t kChannelCount = 3; // linear RGB

struct BakeSettings {
    int order = sh::kDefaultOrder; // SH order, 1 .. sh::kMaxOrder
    uint32_t raysPerVertex = 256;  // directions over the whole sphere per vertex; each side of a
                                   // sheet uses the half in front of it (>= 8)
    uint32_t bounces = 2;          // interreflection bounces after the direct (shadowed) term
    float rayOffset = 1e-4f;       // m: rays leave a vertex this far along the side's normal
    uint64_t seed = 1;             // picks each vertex's rotation of the direction set
    // Translucency tau per PartKind (Leaf, Stem, Fall, Standard, StyleArm, Other), used by
    // translucencyForParts: leaf blades pass about a quarter of what they reflect, thin petals
    // more, stems (closed tubes) nothing.
    std::array<float, kPartKindCount> translucency{0.25f, 0.0f, 0.45f, 0.45f, 0.35f, 0.2f};

    bool groundPlane = true;                    // the plane y = 0 occludes and reflects
    glm::vec3 groundAlbedo{0.2f, 0.16f, 0.12f}; // linear RGB of the soil, for light it sends up
    glm::vec2 groundCentre{0.0f};               // (x, z) of the grid's centre: the clump's base
    float groundGridSize = 2.0f;                // m, side of the square grid
    uint32_t groundGridResolution = 16;         // points per side (>= 2), or 0 for no ground grid;
                                                // baked with or without groundPlane (it sees only
                                                // the upper hemisphere)
    uint32_t groundRaysPerPoint = 256;          // directions over the upper hemisphere (>= 8)
    bool groundBounce = true;                   // add light reflected by the clump onto the ground
};

// "ci" (seconds for a library) or "full" (the default fidelity). Throws meadow::Error otherwise.
BakeSettings bakeSettingsForPreset(const std::string& preset);

// Throws meadow::Error naming the first field out of range.
void checkBakeSettings(const BakeSettings& settings);

// Per-vertex translucency from each vertex's PartKind and settings.translucency.
std::vector<float> translucencyForParts(std::span<const PartKind> parts, const BakeSettings& settings);

// One frame of a mesh to bake. Views only: the caller owns the arrays for the call.
struct TransferMesh {
    std::span<const glm::vec3> positions; // clump space
    std::span<const glm::vec3> normals;   // the Front side's normal per vertex (normalised here)
    std::span<const uint32_t> indices;    // triangle list
    std::span<const glm::vec3> albedo;    // linear RGB per vertex, each in [0, 1]
    std::span<const float> translucency;  // tau per vertex, in [0, 1]
};

// Transfer of every vertex and side: coefficients[offset(v, side, c) + i] is T_c,i of vertex v.
struct VertexTransfer {
    int order = 0;
    uint32_t vertexCount = 0;
    std::vector<float> coefficients; // vertexCount * 2 sides * 3 channels * order^2

    uint32_t coefficientCount() const { return uint32_t(order * order); }
    size_t offset(uint32_t vertex, Side side, uint32_t channel) const {
        return ((size_t(vertex) * kSideCount + uint32_t(side)) * kChannelCount + channel) * coefficientCount();
    }
    const float* at(uint32_t vertex, Side side, uint32_t channel) const {
        return coefficients.data() + offset(vertex, side, channel);
    }
};

// Transfer of a square grid of ground points (normal +y) around the clump. Point (column, row)
// sits at centre + (-size/2 + size * column / (resolution - 1), 0, -size/2 + size * row / (resolution - 1)).
struct GroundTransfer {
    int order = 0;
    uint32_t resolution = 0; // 0: no grid was baked
    float size = 0.0f;
    glm::vec2 centre{0.0f};
    std::vector<float> coefficients; // resolution^2 points (row-major, row along z) * 3 channels * order^2

    uint32_t coefficientCount() const { return uint32_t(order * order); }
    uint32_t pointCount() const { return resolution * resolution; }
    glm::vec3 pointPosition(uint32_t column, uint32_t row) const;
    const float* at(uint32_t point, uint32_t channel) const {
        return coefficients.data() + (size_t(point) * kChannelCount + channel) * coefficientCount();
    }
};

// What a frame cost; for benchmarks and progress, never part of the result's identity.
struct BakeStats {
    uint64_t vertexRays = 0;    // rays cast from vertices
    uint64_t groundRays = 0;    // rays cast from ground points
    double buildSeconds = 0.0;  // Embree scene build
    double castSeconds = 0.0;   // vertex rays: visibility and hit records
    double bounceSeconds = 0.0; // interreflection gathers
    double groundSeconds = 0.0; // ground grid rays and gathers
    double totalSeconds = 0.0;
};

struct ClumpTransfer {
    VertexTransfer vertices;
    GroundTransfer ground; // resolution 0 when settings.groundGridResolution is 0
    BakeStats stats;
};

// Bakes many frames of one clump: topology and materials are fixed, positions and normals change
// per frame. Keeps one Embree scene whose vertex buffer is refilled and whose BVH is rebuilt per
// frame (about 2 ms for the full iris clump, far below the rays). Results depend
// only on the inputs and settings, never on the thread count. Not thread-safe: bake one frame at a
// time per baker (each bake is parallel inside).
class TransferBaker {
  public:
    // Throws meadow::Error for bad settings, indices out of range or not a multiple of 3, albedo
    // or translucency arrays of another length than the vertex count, or values out of range.
    TransferBaker(std::span<const uint32_t> indices, std::span<const glm::vec3> albedo,
                  std::span<const float> translucency, const BakeSettings& settings);
    ~TransferBaker();
    TransferBaker(TransferBaker&&) noexcept;
    TransferBaker& operator=(TransferBaker&&) noexcept;

    // One frame. Throws meadow::Error if the arrays' sizes differ from the vertex count, a value
    // is not finite, or a normal has (near) zero length.
    ClumpTransfer bake(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals);

    uint32_t vertexCount() const;

  private:
    struct State;
    std::unique_ptr<State> state_;
};

// One frame in one call (a TransferBaker used once).
ClumpTransfer bakeTransfer(const TransferMesh& mesh, const BakeSettings& settings);

// The analytic unshadowed transfer, no rays: T_side = C(n_side) + tau C(n_other side), C the
// clamped cosine below, the same in the three channels. Checks its input as bakeTransfer does.
VertexTransfer unshadowedTransfer(const TransferMesh& mesh, const BakeSettings& settings);

// C(n): SH projection of max(n . w, 0), the clamped cosine lobe rotated to the unit normal n:
// c_lm = A_l Y_lm(n) with A_l the Lambertian convolution weights (pi, 2 pi / 3, pi / 4, 0, ...;
// Ramamoorthi and Hanrahan 2001), i.e. sqrt(4 pi / (2l + 1)) z_l Y_lm(n) with z_l the clamped
// cosine's zonal coefficients (0.886227, 1.023327, 0.495416, ...). Writes order^2 values.
void clampedCosineTransfer(int order, const glm::dvec3& normal, double* out);

} // namespace meadow::transfer
