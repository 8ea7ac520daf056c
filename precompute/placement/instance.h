// Placed instances of swept volumes and the exact test of whether two of them overlap
// (docs/ARCHITECTURE.md, Placement). The same transform places clumps and rocks; the run time
// applies it to meshes.
//
// World frame: metres, y up. An instance maps a clump-space point p to
//     world = position + R(yaw) * M * p
// where M (when mirrored) reflects about the vertical plane through the clump origin that
// contains the wind direction, and R(yaw) turns about +y as the engine's instance.vert.glsl does:
//     x' = cos(yaw) x + sin(yaw) z,   z' = -sin(yaw) x + cos(yaw) z.
// The mirror keeps the wind direction fixed, so a mirrored clump still sways downwind; its meshes
// change handedness (flip the winding, or draw two-sided as the plants already are). Yaw is kept
// to a small jitter for clumps for the same reason: their motion was simulated in one wind
// direction.
#pragma once

#include "placement/swept_volume.h"

#include <glm/glm.hpp>

namespace meadow {

struct InstanceTransform {
    glm::vec3 position{0.0f}; // world position of the clump origin (rhizome)
    float yaw = 0.0f;         // radians about +y, applied after the mirror
    bool mirrored = false;    // reflected about the vertical plane containing the wind direction
};

// The horizontal part R(yaw) * M acting on (x, z) column vectors, in double precision. Throws
// meadow::Error if windDirection (x, z) is zero or not finite; it need not be unit length.
glm::dmat2 horizontalMap(float yaw, bool mirrored, glm::vec2 windDirection);

// world = position + R(yaw) * M * p.
glm::dvec3 instanceToWorld(const InstanceTransform& transform, glm::vec2 windDirection, const glm::vec3& p);

// True when some occupied cell (box) of `a` placed by `ta` and some occupied cell of `b` placed by
// `tb` share interior: the voxel boxes themselves, each turned by its instance's yaw and mirror,
// are tested exactly (separating axes of the two squares in x-z, intervals in y, at any real-valued
// height difference), not a resampling of one grid into the other. Boxes that only touch (a
// shared face, edge or corner) do not overlap.
//
// Never misses a true contact of the surfaces inside the volumes: the voxelizer marks every cell
// whose closed box (grown by 5e-6 of a cell) a triangle touches, both sides of a face it lies on,
// so around a point where two surfaces meet each volume's cells cover a whole ball, and a box of
// each shares interior there. Interiors must overlap by more than 1e-8 of a cell on every axis,
// so that rounding of exact touching (common: tiles put instances on one cell lattice) never reads
// as overlap; the shared interior around a contact is 40 times deeper than that.
//
// Symmetric exactly: overlap(a, ta, b, tb) == overlap(b, tb, a, ta) bit for bit, because each
// box is placed by the same arithmetic relative to the instances' midpoint whichever argument it
// is, and the pair test is symmetric in its arguments. Candidate boxes are found by a
// conservative bounding-box lookup into one volume's column index, so the cost is about
// (columns of the smaller volume) x 4 lookups. Both volumes must share one cell size (meadow::Error
// otherwise).
bool sweptVolumesOverlap(const SweptVolume& a, const InstanceTransform& ta, const SweptVolume& b,
                         const InstanceTransform& tb, glm::vec2 windDirection);

} // namespace meadow
