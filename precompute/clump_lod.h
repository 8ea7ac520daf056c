// A clump's five levels of detail (DESIGN.md 2.8): its mesh simplified by half-edge collapses
// whose quadrics weigh how each vertex moves and is lit (lod/lod.h), each LOD a subset of the
// original vertices (so motion rows and transfer are the originals'), with its error measured
// against the full mesh at rest and over simulated frames.
#pragma once

#include "clump_light.h"
#include "clump_motion.h"
#include "lod/lod.h"
#include "mesh.h"
#include "scene.h"

#include <array>

namespace meadow {

struct ClumpLod {
    std::vector<uint32_t> vertices; // original vertex indices, in vertex-fetch order
    std::vector<uint32_t> indices;  // triangles into `vertices`
    LodError error;                 // against LOD 0 (the full mesh)
};

// `meanPose` as drawn (clumpRenderMesh). Deterministic.
std::array<ClumpLod, kLodCount> buildClumpLods(const ClumpMotion& motion, const ClumpLight& light, const Mesh& meanPose,
                                               const std::vector<float>& testSky, const LodParams& params);

// The LOD's mesh at a motion frame: the gathered vertices of meshAtFrame with the LOD's modes.
Mesh lodMeshAtFrame(const Mesh& meanPose, const MotionBasis& motion, const ClumpLod& lod, uint32_t lodIndex,
                    uint32_t frame);

} // namespace meadow
