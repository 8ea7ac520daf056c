#include "lod/triangle_bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace meadow::lod_detail {
namespace {

constexpr uint32_t kLeafTriangles = 4;

glm::vec3 closestOnSegment(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, float& t) {
    const glm::vec3 ab = b - a;
    const float length2 = glm::dot(ab, ab);
    t = length2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / length2, 0.0f, 1.0f) : 0.0f;
    return a + t * ab;
}

float boxDistanceSquared(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi) {
    const glm::vec3 d = glm::max(glm::max(lo - p, p - hi), glm::vec3(0.0f));
    return glm::dot(d, d);
}

} // namespace

glm::vec3 closestPointOnTriangle(const glm::vec3& point, const glm::vec3& a32, const glm::vec3& b32,
                                 const glm::vec3& c32, glm::vec3& barycentric) {
    // In double: the region tests subtract products of edge dot products, which cancel badly in
    // float for the long thin triangles of leaf tips (13 um of error measured on a point lying on
    // its own triangle).
    const glm::dvec3 p(point), a(a32), b(b32), c(c32);
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) {
        barycentric = {1.0f, 0.0f, 0.0f};
        return a32;
    }
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) {
        barycentric = {0.0f, 1.0f, 0.0f};
        return b32;
    }
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0) {
        const double v = d1 / (d1 - d3);
        barycentric = {float(1.0 - v), float(v), 0.0f};
        return glm::vec3(a + v * ab);
    }
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) {
        barycentric = {0.0f, 0.0f, 1.0f};
        return c32;
    }
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0) {
        const double w = d2 / (d2 - d6);
        barycentric = {float(1.0 - w), 0.0f, float(w)};
        return glm::vec3(a + w * ac);
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        barycentric = {0.0f, float(1.0 - w), float(w)};
        return glm::vec3(b + w * (c - b));
    }
    const double sum = va + vb + vc;
    if (sum > 0.0) {
        const double v = vb / sum, w = vc / sum;
        barycentric = {float(1.0 - v - w), float(v), float(w)};
        return glm::vec3(a + ab * v + ac * w);
    }
    // Degenerate triangle: the nearest of its edges.
    float tab, tbc, tca;
    const glm::vec3 qab = closestOnSegment(point, a32, b32, tab), qbc = closestOnSegment(point, b32, c32, tbc),
                    qca = closestOnSegment(point, c32, a32, tca);
    const float dab = glm::dot(point - qab, point - qab), dbc = glm::dot(point - qbc, point - qbc),
                dca = glm::dot(point - qca, point - qca);
    if (dab <= dbc && dab <= dca) {
        barycentric = {1.0f - tab, tab, 0.0f};
        return qab;
    }
    if (dbc <= dca) {
        barycentric = {0.0f, 1.0f - tbc, tbc};
        return qbc;
    }
    barycentric = {tca, 0.0f, 1.0f - tca};
    return qca;
}

TriangleBvh::TriangleBvh(std::span<const glm::vec3> positions, std::span<const uint32_t> indices) {
    const uint32_t count = uint32_t(indices.size() / 3);
    std::vector<glm::vec3> centroid(count);
    std::vector<std::array<glm::vec3, 3>> corners(count);
    for (uint32_t t = 0; t < count; ++t) {
        corners[t] = {positions[indices[3 * t]], positions[indices[3 * t + 1]], positions[indices[3 * t + 2]]};
        centroid[t] = (corners[t][0] + corners[t][1] + corners[t][2]) / 3.0f;
    }
    order_.resize(count);
    for (uint32_t t = 0; t < count; ++t)
        order_[t] = t;

    struct Task {
        uint32_t node, first, count;
    };
    nodes_.reserve(2 * size_t(count) / kLeafTriangles + 2);
    nodes_.push_back({});
    std::vector<Task> stack{{0, 0, count}};
    while (!stack.empty()) {
        const Task task = stack.back();
        stack.pop_back();
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        glm::vec3 clo = lo, chi = hi;
        for (uint32_t i = task.first; i < task.first + task.count; ++i) {
            for (const glm::vec3& corner : corners[order_[i]]) {
                lo = glm::min(lo, corner);
                hi = glm::max(hi, corner);
            }
            clo = glm::min(clo, centroid[order_[i]]);
            chi = glm::max(chi, centroid[order_[i]]);
        }
        nodes_[task.node].lo = lo;
        nodes_[task.node].hi = hi;
        if (task.count <= kLeafTriangles) {
            nodes_[task.node].first = task.first;
            nodes_[task.node].count = task.count;
            continue;
        }
        const glm::vec3 extent = chi - clo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        const uint32_t half = task.count / 2;
        auto begin = order_.begin() + task.first;
        // Ties broken by index: the tree, and so every query's result, is deterministic.
        std::nth_element(begin, begin + half, begin + task.count, [&](uint32_t a, uint32_t b) {
            return centroid[a][axis] != centroid[b][axis] ? centroid[a][axis] < centroid[b][axis] : a < b;
        });
        const uint32_t left = uint32_t(nodes_.size());
        nodes_[task.node].first = left;
        nodes_[task.node].count = 0;
        nodes_.push_back({});
        nodes_.push_back({});
        stack.push_back({left, task.first, half});
        stack.push_back({left + 1, task.first + half, task.count - half});
    }
    corners_.resize(count);
    for (uint32_t i = 0; i < count; ++i)
        corners_[i] = corners[order_[i]];
}

ClosestHit TriangleBvh::closest(const glm::vec3& p) const {
    ClosestHit best;
    best.distanceSquared = std::numeric_limits<float>::max();
    uint32_t stack[64];
    uint32_t depth = 0;
    stack[depth++] = 0;
    while (depth > 0) {
        const Node& node = nodes_[stack[--depth]];
        if (boxDistanceSquared(p, node.lo, node.hi) >= best.distanceSquared)
            continue;
        if (node.count > 0) {
            for (uint32_t i = node.first; i < node.first + node.count; ++i) {
                glm::vec3 barycentric;
                const glm::vec3 q =
                    closestPointOnTriangle(p, corners_[i][0], corners_[i][1], corners_[i][2], barycentric);
                const float d = glm::dot(p - q, p - q);
                // Equal distances keep the lower triangle index: the result does not depend on the
                // traversal order.
                if (d < best.distanceSquared || (d == best.distanceSquared && order_[i] < best.triangle)) {
                    best = {order_[i], barycentric, d};
                }
            }
            continue;
        }
        const float dl = boxDistanceSquared(p, nodes_[node.first].lo, nodes_[node.first].hi);
        const float dr = boxDistanceSquared(p, nodes_[node.first + 1].lo, nodes_[node.first + 1].hi);
        // Push the farther child first so the nearer one is searched first.
        if (dl <= dr) {
            stack[depth++] = node.first + 1;
            stack[depth++] = node.first;
        } else {
            stack[depth++] = node.first;
            stack[depth++] = node.first + 1;
        }
    }
    return best;
}

std::vector<SurfaceSample> sampleSurface(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                                         float samplesPerSquareMetre) {
    // R2 sequence: the generalised golden ratio in two dimensions.
    constexpr double kPlastic = 1.32471795724474602596;
    constexpr double kAlpha1 = 1.0 / kPlastic, kAlpha2 = 1.0 / (kPlastic * kPlastic);
    std::vector<SurfaceSample> samples;
    const uint32_t count = uint32_t(indices.size() / 3);
    for (uint32_t t = 0; t < count; ++t) {
        const glm::vec3 a = positions[indices[3 * t]], b = positions[indices[3 * t + 1]],
                        c = positions[indices[3 * t + 2]];
        const float area = 0.5f * glm::length(glm::cross(b - a, c - a));
        const uint32_t n = uint32_t(std::max(1.0, std::round(double(area) * double(samplesPerSquareMetre))));
        for (uint32_t i = 0; i < n; ++i) {
            double u = std::fmod(0.5 + double(i) * kAlpha1, 1.0), v = std::fmod(0.5 + double(i) * kAlpha2, 1.0);
            if (u + v > 1.0) {
                u = 1.0 - u;
                v = 1.0 - v;
            }
            samples.push_back({t, glm::vec3(float(1.0 - u - v), float(u), float(v)), area / float(n)});
        }
    }
    return samples;
}

} // namespace meadow::lod_detail
