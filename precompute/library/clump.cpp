#include "library/clump.h"

namespace meadow {

Mesh lodMeshAtFrame(const Mesh& meanPose, const MotionBasis& motion, const ClumpLod& lod, uint32_t lodIndex,
                    uint32_t frame) {
    const Mesh posed = meshAtFrame(meanPose, motion, frame, lodIndex);
    Mesh out;
    out.vertices.reserve(lod.vertices.size());
    for (uint32_t v : lod.vertices)
        out.vertices.push_back(posed.vertices[v]);
    out.indices = lod.indices;
    out.boundingRadius = meanPose.boundingRadius;
    return out;
}

} // namespace meadow
