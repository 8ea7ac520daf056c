// Triangle/box overlap by the separating axis theorem (Tomas Akenine-Möller, "Fast 3D
// Triangle-Box Overlap Testing", journal of graphics tools 6(1), 2001): the basis of the
// conservative surface voxelization in swept_volume.h.
#pragma once

#include <glm/glm.hpp>

namespace meadow {

// True when the closed triangle (a, b, c) and the closed axis-aligned box centred at `centre`
// with half extents `halfSize` share at least one point. Touching counts as overlap (a triangle
// on a cell's face marks the cells on both sides). Tests the 13 candidate separating axes: the
// box's 3 face normals, the triangle's normal and the 9 cross products of their edges. Degenerate
// triangles (collinear or coincident corners) are handled: their zero normal or zero edge cross
// products separate nothing, and the remaining axes still decide correctly for a segment or point.
// Double precision; callers wanting robustness against rounding grow halfSize by a tiny amount.
bool triangleBoxOverlap(const glm::dvec3& centre, const glm::dvec3& halfSize, const glm::dvec3& a, const glm::dvec3& b,
                        const glm::dvec3& c);

} // namespace meadow
