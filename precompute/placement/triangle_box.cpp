#include "placement/triangle_box.h"

#include <algorithm>
#include <cmath>

namespace meadow {
namespace {

// Projects the triangle (box-centred corners) and the box on `axis`; true when the intervals are
// disjoint. Strict comparisons: touching intervals do not separate (closed sets). A zero axis
// (parallel edges) projects everything to 0 and separates nothing, as it must.
bool separatedOnAxis(const glm::dvec3& axis, const glm::dvec3& halfSize, const glm::dvec3& v0, const glm::dvec3& v1,
                     const glm::dvec3& v2) {
    const double p0 = glm::dot(axis, v0), p1 = glm::dot(axis, v1), p2 = glm::dot(axis, v2);
    const double radius = halfSize.x * std::abs(axis.x) + halfSize.y * std::abs(axis.y) + halfSize.z * std::abs(axis.z);
    return std::min({p0, p1, p2}) > radius || std::max({p0, p1, p2}) < -radius;
}

} // namespace

bool triangleBoxOverlap(const glm::dvec3& centre, const glm::dvec3& halfSize, const glm::dvec3& a, const glm::dvec3& b,
                        const glm::dvec3& c) {
    // Akenine-Möller 2001: move the box to the origin, then try the axes cheapest first.
    const glm::dvec3 v0 = a - centre, v1 = b - centre, v2 = c - centre;

    // The box's face normals: the triangle's bounding box against the box.
    for (int axis = 0; axis < 3; ++axis) {
        if (std::min({v0[axis], v1[axis], v2[axis]}) > halfSize[axis] ||
            std::max({v0[axis], v1[axis], v2[axis]}) < -halfSize[axis])
            return false;
    }

    // The nine cross products of the triangle's edges with the box's axes.
    const glm::dvec3 edges[3] = {v1 - v0, v2 - v1, v0 - v2};
    for (const glm::dvec3& e : edges) {
        const glm::dvec3 axes[3] = {{0.0, -e.z, e.y}, {e.z, 0.0, -e.x}, {-e.y, e.x, 0.0}}; // x, y, z cross e
        for (const glm::dvec3& axis : axes)
            if (separatedOnAxis(axis, halfSize, v0, v1, v2))
                return false;
    }

    // The triangle's plane against the box: the box's projection radius on the normal versus the
    // plane's distance from the box centre.
    const glm::dvec3 normal = glm::cross(edges[0], edges[1]);
    const double distance = glm::dot(normal, v0);
    const double radius =
        halfSize.x * std::abs(normal.x) + halfSize.y * std::abs(normal.y) + halfSize.z * std::abs(normal.z);
    return std::abs(distance) <= radius;
}

} // namespace meadow
