#include "lod/attribute_quadric.h"

#include <algorithm>
#include <cmath>

namespace meadow::lod_detail {
namespace {

void addOuter(std::span<double> q, const glm::dvec3& v, double weight) {
    q[0] += weight * v.x * v.x;
    q[1] += weight * v.x * v.y;
    q[2] += weight * v.x * v.z;
    q[3] += weight * v.y * v.y;
    q[4] += weight * v.y * v.z;
    q[5] += weight * v.z * v.z;
}

} // namespace

void addFaceQuadric(std::span<double> q, const glm::dvec3 p[3], const float* const s[3], uint32_t attributeCount,
                    double area) {
    const glm::dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    const glm::dvec3 cross = glm::cross(e1, e2);
    const double length = glm::length(cross);
    if (!(length > 0.0) || !(area > 0.0))
        return;
    const glm::dvec3 n = cross / length;
    const double e = -glm::dot(n, p[0]);
    addOuter(q, n, area);
    q[6] += area * e * n.x;
    q[7] += area * e * n.y;
    q[8] += area * e * n.z;
    q[9] += area * e * e;
    q[10] += area;
    if (attributeCount == 0)
        return;

    // Hoppe 1999, section 4: the gradient g solves [p0 - p2; p1 - p2; n] g = [s0 - s2; s1 - s2; 0].
    const glm::dvec3 r0 = p[0] - p[2], r1 = p[1] - p[2];
    // Inverse of the matrix with rows r0, r1, n: columns (r1 x n, n x r0, r0 x r1) / det.
    const glm::dvec3 c0 = glm::cross(r1, n), c1 = glm::cross(n, r0);
    const double det = glm::dot(r0, c0);
    // det is twice the area times |n| = 1: relative to the edge lengths it vanishes only for a
    // sliver whose attribute field would be meaningless; such a face keeps its plane only.
    const double scale = std::max(glm::dot(r0, r0), glm::dot(r1, r1));
    if (!(std::abs(det) > 1e-12 * scale))
        return;
    for (uint32_t j = 0; j < attributeCount; ++j) {
        const double s0 = s[0][j], s1 = s[1][j], s2 = s[2][j];
        const glm::dvec3 g = (c0 * (s0 - s2) + c1 * (s1 - s2)) / det;
        const double d = s2 - glm::dot(g, p[2]);
        addOuter(q, g, area);
        q[6] += area * d * g.x;
        q[7] += area * d * g.y;
        q[8] += area * d * g.z;
        q[9] += area * d * d;
        double* attribute = &q[kQuadricFixed + 4 * size_t(j)];
        attribute[0] += area * g.x;
        attribute[1] += area * g.y;
        attribute[2] += area * g.z;
        attribute[3] += area * d;
    }
}

void addPlaneQuadric(std::span<double> q, const glm::dvec3& normal, const glm::dvec3& point, double weight) {
    const double e = -glm::dot(normal, point);
    addOuter(q, normal, weight);
    q[6] += weight * e * normal.x;
    q[7] += weight * e * normal.y;
    q[8] += weight * e * normal.z;
    q[9] += weight * e * e;
}

void addQuadric(std::span<double> q, std::span<const double> other) {
    for (size_t i = 0; i < q.size(); ++i)
        q[i] += other[i];
}

double evaluateQuadric(std::span<const double> q, const glm::dvec3& p, const float* s, uint32_t attributeCount) {
    const double x = p.x, y = p.y, z = p.z;
    double result = q[0] * x * x + q[3] * y * y + q[5] * z * z + 2.0 * (q[1] * x * y + q[2] * x * z + q[4] * y * z) +
                    2.0 * (q[6] * x + q[7] * y + q[8] * z) + q[9];
    const double w = q[10];
    for (uint32_t j = 0; j < attributeCount; ++j) {
        const double* attribute = &q[kQuadricFixed + 4 * size_t(j)];
        const double value = s[j];
        result += value * (w * value - 2.0 * (attribute[0] * x + attribute[1] * y + attribute[2] * z + attribute[3]));
    }
    return std::max(result, 0.0);
}

} // namespace meadow::lod_detail
