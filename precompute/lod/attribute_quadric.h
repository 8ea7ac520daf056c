// The quadric error metric with attributes of Hoppe 1999 ("New quadric metric for simplifying
// meshes with appearance attributes"), stored in O(m) numbers for m attributes instead of the
// (3 + m)^2 of Garland & Heckbert 1998. Internal to precompute/lod.
//
// For a face f of area a with plane n.p + e = 0, each attribute j is the linear function
// s_j(p) = g_j.p + d_j that interpolates the face's three corner values (g_j in the face's
// plane). The quadric of a set of faces, evaluated at a position p with attribute values s, is
//
//     Q(p, s) = sum_f a_f [ (n.p + e)^2 + sum_j (g_j.p + d_j - s_j)^2 ],
//
// the area-weighted squared distance to the faces' planes plus the squared deviation of s from
// each face's attribute field extended to p. Expanded, with
//     A = sum a (n n^T + sum_j g_j g_j^T), b = sum a (e n + sum_j d_j g_j), c = sum a (e^2 + sum_j d_j^2),
//     W = sum a, G_j = sum a g_j, D_j = sum a d_j:
//
//     Q(p, s) = p^T A p + 2 b.p + c + sum_j s_j (W s_j - 2 (G_j.p + D_j)).
//
// Quadrics add (G&H 1997): the quadric of a vertex is the sum of its faces', and a collapse adds
// the removed vertex's quadric to the kept one's. With half-edge collapses the kept vertex's
// position and attributes are fixed, so Q is only ever evaluated, never minimised.
#pragma once

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <span>

namespace meadow::lod_detail {

// Layout of one quadric in a flat double array: A (xx, xy, xz, yy, yz, zz), b (3), c, W, then
// per attribute (G_j (3), D_j).
inline constexpr size_t kQuadricFixed = 11;
inline size_t quadricStride(uint32_t attributeCount) {
    return kQuadricFixed + 4 * size_t(attributeCount);
}

// Adds the quadric of one face (corners p[0..2], corner attributes s[k][0..m-1]) with weight
// `area` to q. Faces whose attribute system is singular (near-zero area) add their plane only.
void addFaceQuadric(std::span<double> q, const glm::dvec3 p[3], const float* const s[3], uint32_t attributeCount,
                    double area);

// Adds weight * (n.p + e)^2 for the plane through `point` with unit normal `normal` (boundary
// constraint planes: geometry only, W unchanged so attributes stay area-weighted).
void addPlaneQuadric(std::span<double> q, const glm::dvec3& normal, const glm::dvec3& point, double weight);

// q += other.
void addQuadric(std::span<double> q, std::span<const double> other);

// Q(p, s), clamped at 0 (the expanded form can round to slightly below).
double evaluateQuadric(std::span<const double> q, const glm::dvec3& p, const float* s, uint32_t attributeCount);

// W: the face area the quadric stands for.
inline double quadricArea(std::span<const double> q) {
    return q[10];
}

} // namespace meadow::lod_detail
