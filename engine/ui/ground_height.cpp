#include "ui/ground_height.h"

#include <algorithm>
#include <cmath>

namespace meadow {

GroundHeight::GroundHeight(const Mesh& terrain) {
    for (size_t i = 0; i + 2 < terrain.indices.size(); i += 3) {
        Triangle t;
        const glm::vec4 p[3] = {terrain.vertices[terrain.indices[i]].positionU,
                                terrain.vertices[terrain.indices[i + 1]].positionU,
                                terrain.vertices[terrain.indices[i + 2]].positionU};
        t.a = {p[0].x, p[0].z};
        t.b = {p[1].x, p[1].z};
        t.c = {p[2].x, p[2].z};
        t.heights = {p[0].y, p[1].y, p[2].y};
        t.lo = glm::min(t.a, glm::min(t.b, t.c));
        t.hi = glm::max(t.a, glm::max(t.b, t.c));
        triangles_.push_back(t);
    }
    if (triangles_.empty())
        return;

    // Cells the size of a typical triangle; triangles much larger than that (the plain's ring
    // reaching to the horizon) are few and are tested one by one.
    std::vector<float> extents;
    for (const Triangle& t : triangles_)
        extents.push_back(std::max(t.hi.x - t.lo.x, t.hi.y - t.lo.y));
    std::vector<float> sorted = extents;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    cell_ = std::max(sorted[sorted.size() / 2], 1e-3f);
    const float largeExtent = 8.0f * cell_;

    glm::vec2 lo(1e30f), hi(-1e30f);
    for (size_t i = 0; i < triangles_.size(); ++i)
        if (extents[i] <= largeExtent) {
            lo = glm::min(lo, triangles_[i].lo);
            hi = glm::max(hi, triangles_[i].hi);
        } else {
            large_.push_back(uint32_t(i));
        }
    if (lo.x > hi.x)
        return; // only large triangles
    origin_ = lo;
    cellsX_ = std::max(1u, uint32_t(std::ceil((hi.x - lo.x) / cell_)));
    cellsZ_ = std::max(1u, uint32_t(std::ceil((hi.y - lo.y) / cell_)));
    auto cellRange = [&](const Triangle& t, uint32_t& x0, uint32_t& x1, uint32_t& z0, uint32_t& z1) {
        x0 = uint32_t(std::clamp(std::floor((t.lo.x - origin_.x) / cell_), 0.0f, float(cellsX_ - 1)));
        x1 = uint32_t(std::clamp(std::floor((t.hi.x - origin_.x) / cell_), 0.0f, float(cellsX_ - 1)));
        z0 = uint32_t(std::clamp(std::floor((t.lo.y - origin_.y) / cell_), 0.0f, float(cellsZ_ - 1)));
        z1 = uint32_t(std::clamp(std::floor((t.hi.y - origin_.y) / cell_), 0.0f, float(cellsZ_ - 1)));
    };
    // Two passes: count per cell, then fill (a compact list per cell).
    cellStart_.assign(size_t(cellsX_) * cellsZ_ + 1, 0);
    for (size_t i = 0; i < triangles_.size(); ++i) {
        if (extents[i] > largeExtent)
            continue;
        uint32_t x0, x1, z0, z1;
        cellRange(triangles_[i], x0, x1, z0, z1);
        for (uint32_t z = z0; z <= z1; ++z)
            for (uint32_t x = x0; x <= x1; ++x)
                ++cellStart_[size_t(z) * cellsX_ + x + 1];
    }
    for (size_t c = 1; c < cellStart_.size(); ++c)
        cellStart_[c] += cellStart_[c - 1];
    cellTriangles_.resize(cellStart_.back());
    std::vector<uint32_t> fill(cellStart_.begin(), cellStart_.end() - 1);
    for (size_t i = 0; i < triangles_.size(); ++i) {
        if (extents[i] > largeExtent)
            continue;
        uint32_t x0, x1, z0, z1;
        cellRange(triangles_[i], x0, x1, z0, z1);
        for (uint32_t z = z0; z <= z1; ++z)
            for (uint32_t x = x0; x <= x1; ++x)
                cellTriangles_[fill[size_t(z) * cellsX_ + x]++] = uint32_t(i);
    }
}

std::optional<float> GroundHeight::heightIn(const Triangle& t, glm::vec2 p) const {
    if (p.x < t.lo.x || p.x > t.hi.x || p.y < t.lo.y || p.y > t.hi.y)
        return std::nullopt;
    auto cross = [](glm::vec2 u, glm::vec2 v) { return u.x * v.y - u.y * v.x; };
    const float area = cross(t.b - t.a, t.c - t.a);
    if (std::abs(area) < 1e-12f)
        return std::nullopt; // seen edge-on from above: the neighbours carry the height
    const float wb = cross(p - t.a, t.c - t.a) / area;
    const float wc = cross(t.b - t.a, p - t.a) / area;
    const float wa = 1.0f - wb - wc;
    const float eps = -1e-5f; // points on a shared edge belong to both triangles
    if (wa < eps || wb < eps || wc < eps)
        return std::nullopt;
    return wa * t.heights.x + wb * t.heights.y + wc * t.heights.z;
}

std::optional<float> GroundHeight::at(float x, float z) const {
    const glm::vec2 p(x, z);
    std::optional<float> best;
    auto consider = [&](uint32_t i) {
        if (auto h = heightIn(triangles_[i], p))
            best = best ? std::max(*best, *h) : *h;
    };
    if (cellsX_ > 0) {
        // A point on the far border belongs to the last cell.
        const float cx = std::min(std::floor((x - origin_.x) / cell_), float(cellsX_ - 1));
        const float cz = std::min(std::floor((z - origin_.y) / cell_), float(cellsZ_ - 1));
        const float fx = (x - origin_.x) / cell_, fz = (z - origin_.y) / cell_;
        if (fx >= 0.0f && fz >= 0.0f && fx <= float(cellsX_) && fz <= float(cellsZ_)) {
            const size_t cell = size_t(cz) * cellsX_ + size_t(cx);
            for (uint32_t k = cellStart_[cell]; k < cellStart_[cell + 1]; ++k)
                consider(cellTriangles_[k]);
        }
    }
    for (uint32_t i : large_)
        consider(i);
    return best;
}

} // namespace meadow
