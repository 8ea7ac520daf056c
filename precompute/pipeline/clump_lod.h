// A clump's five levels of detail (docs/ARCHITECTURE.md, Levels of detail): its mesh simplified by
// half-edge collapses whose quadrics weigh how each vertex moves and is lit (lod/lod.h), each LOD a
// subset of the original vertices (so motion rows and transfer are the originals'), with its error
// measured against the full mesh at rest and over simulated frames.
#pragma once

#include "library/clump.h"

#include "library/mesh.h"
#include "lod/lod.h"
#include "pipeline/clump_light.h"
#include "pipeline/clump_motion.h"
#include "scene/scene.h"

#include <array>

namespace meadow {

// What the simplifier weighs for a clump (lod/lod.h): the drawn mesh's positions, normals and UVs,
// the rod each vertex follows, its LOD 0 motion rows in metres (weight 1) and its mean light
// transfer (weight 0.01, in units of its spread over the clump). Owns what input() views.
struct ClumpSimplifyData {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> uvs;
    std::vector<uint32_t> indices, groups;
    AttributeValues motionRows, transfer;

    SimplifyInput input() const;
};

// All of it but `transfer`, which the caller sets (meanTransferAttributes of the clump's light).
// `meanPose` as drawn (clumpRenderMesh of `motion`).
ClumpSimplifyData clumpSimplifyData(const ClumpMotion& motion, const Mesh& meanPose);

// `meanPose` as drawn (clumpRenderMesh). Deterministic.
std::array<ClumpLod, kLodCount> buildClumpLods(const ClumpMotion& motion, const ClumpLight& light, const Mesh& meanPose,
                                               const std::vector<float>& testSky, const LodParams& params);

} // namespace meadow
