// The exact voxel-box overlap test between two placed swept volumes (instance.h).
#include "core/error.h"
#include "placement/instance.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace meadow {
namespace {

// Boxes overlap when their interiors do by more than this fraction of a cell on every axis; less
// (touching faces included) is no overlap. Why that is still conservative: the voxelizer marks every
// cell whose box, grown by rho = 5e-6 of a cell, a triangle touches, so around any surface point the
// marked cells cover a ball of radius rho; where two surfaces truly meet, both volumes cover one
// such ball, and cutting it by both grids leaves a ball of radius rho / 12 inside one box of each
// (inscribe an axis-aligned cube in the ball, keep its largest piece of one grid, inscribe a ball,
// repeat for the other grid): an overlap 40 times deeper than this threshold.
constexpr double kPenetration = 1e-8;
// The whole-volume rejections lean the other way, toward testing, by this fraction of a cell.
constexpr double kSlack = 1e-5;

// One instance seen from the midpoint of the pair: column (x, z)'s square has its centre at
// offset + map ((x + 1/2) h, (z + 1/2) h) and half-axes u / 2, v / 2; its cells span
// [y + j h, y + (j + 1) h] in height.
struct Placed {
    const SweptVolume* volume = nullptr;
    glm::dmat2 map{1.0};
    glm::dvec2 offset{0.0};
    double y = 0.0;
    glm::dvec2 u{0.0}, v{0.0};
};

Placed place(const SweptVolume& volume, const InstanceTransform& transform, const glm::dvec2& mid,
             glm::vec2 windDirection) {
    Placed placed;
    placed.volume = &volume;
    placed.map = horizontalMap(transform.yaw, transform.mirrored, windDirection);
    placed.offset = glm::dvec2(transform.position.x, transform.position.z) - mid;
    placed.y = double(transform.position.y);
    const double h = double(volume.cellSize());
    placed.u = placed.map * glm::dvec2(h, 0.0);
    placed.v = placed.map * glm::dvec2(0.0, h);
    return placed;
}

glm::dvec2 columnCentre(const Placed& placed, int32_t x, int32_t z) {
    const double h = double(placed.volume->cellSize());
    return placed.offset + placed.map * glm::dvec2((double(x) + 0.5) * h, (double(z) + 0.5) * h);
}

// Projection radius of a square with half-axes u / 2, v / 2 on `axis`.
double squareRadius(const glm::dvec2& u, const glm::dvec2& v, const glm::dvec2& axis) {
    return 0.5 * (std::abs(glm::dot(u, axis)) + std::abs(glm::dot(v, axis)));
}

// Separating axis test of two squares (2D): the candidate axes are each square's edge directions.
// They overlap when their projections on every axis overlap by more than `depth` (m). Symmetric
// in its two squares to the bit: |(-d).n| == |d.n| and the radii add in either order.
bool squaresSeparated(const glm::dvec2& ca, const glm::dvec2& ua, const glm::dvec2& va, const glm::dvec2& cb,
                      const glm::dvec2& ub, const glm::dvec2& vb, double depth) {
    const glm::dvec2 d = ca - cb;
    for (const glm::dvec2& axis : {ua, va, ub, vb}) {
        const double ra = squareRadius(ua, va, axis), rb = squareRadius(ub, vb, axis);
        if (std::abs(glm::dot(d, axis)) >= ra + rb - depth * glm::length(axis))
            return true;
    }
    return false;
}

bool runsOverlap(std::span<const VoxelRun> a, double ya, std::span<const VoxelRun> b, double yb, double h) {
    const double depth = kPenetration * h;
    for (const VoxelRun& ra : a) {
        const double loA = ya + double(ra.y0) * h, hiA = ya + double(ra.y1 + 1) * h;
        for (const VoxelRun& rb : b) {
            const double loB = yb + double(rb.y0) * h, hiB = yb + double(rb.y1 + 1) * h;
            if (loA < hiB - depth && loB < hiA - depth)
                return true;
        }
    }
    return false;
}

} // namespace

glm::dmat2 horizontalMap(float yaw, bool mirrored, glm::vec2 windDirection) {
    const double length = std::hypot(double(windDirection.x), double(windDirection.y));
    if (!std::isfinite(length) || !(length > 0.0))
        throw Error("placement: wind direction (" + std::to_string(windDirection.x) + ", " +
                    std::to_string(windDirection.y) + ") is not a finite non-zero vector");
    if (!std::isfinite(yaw))
        throw Error("placement: yaw is not finite");
    const double c = std::cos(double(yaw)), s = std::sin(double(yaw));
    const glm::dmat2 rotation(c, -s, s, c); // columns: the images of x and z
    if (!mirrored)
        return rotation;
    // M = I - 2 n n^T with n = (-wz, wx), the horizontal normal of the plane that holds the wind.
    const double wx = double(windDirection.x) / length, wz = double(windDirection.y) / length;
    const glm::dmat2 mirror(1.0 - 2.0 * wz * wz, 2.0 * wx * wz, 2.0 * wx * wz, 1.0 - 2.0 * wx * wx);
    return rotation * mirror;
}

glm::dvec3 instanceToWorld(const InstanceTransform& transform, glm::vec2 windDirection, const glm::vec3& p) {
    const glm::dvec2 xz = horizontalMap(transform.yaw, transform.mirrored, windDirection) * glm::dvec2(p.x, p.z);
    return glm::dvec3(transform.position) + glm::dvec3(xz.x, double(p.y), xz.y);
}

bool sweptVolumesOverlap(const SweptVolume& a, const InstanceTransform& ta, const SweptVolume& b,
                         const InstanceTransform& tb, glm::vec2 windDirection) {
    if (a.cellSize() != b.cellSize())
        throw Error("placement: swept volumes of cell sizes " + std::to_string(a.cellSize()) + " and " +
                    std::to_string(b.cellSize()) + " m cannot be compared");
    if (a.empty() || b.empty())
        return false;
    const double h = double(a.cellSize());

    // Whole-volume rejections: the axis-centred cylinders do not meet.
    const glm::dvec2 pa(ta.position.x, ta.position.z), pb(tb.position.x, tb.position.z);
    const glm::dvec2 d = pa - pb;
    const double reach = double(a.footprintRadius()) + double(b.footprintRadius()) + kSlack * h;
    if (glm::dot(d, d) > reach * reach)
        return false;
    if (double(ta.position.y) + double(a.minY()) > double(tb.position.y) + double(b.maxY()) + kSlack * h ||
        double(tb.position.y) + double(b.minY()) > double(ta.position.y) + double(a.maxY()) + kSlack * h)
        return false;

    const glm::dvec2 mid = (pa + pb) * 0.5;
    const Placed placedA = place(a, ta, mid, windDirection), placedB = place(b, tb, mid, windDirection);
    // Walk the volume with fewer columns; look candidates up in the other's column index. Which
    // one walks changes the work, not the answer: the answer is the OR of the symmetric box test
    // over every pair the lookup can produce, and the lookup is a superset of the touching pairs.
    const bool walkA = a.columns().size() < b.columns().size();
    const Placed& walk = walkA ? placedA : placedB;
    const Placed& look = walkA ? placedB : placedA;
    const SweptVolume& lookVolume = *look.volume;
    const glm::ivec3 lookMin = lookVolume.minCell(), lookMax = lookVolume.maxCell();

    // The walked squares' half extents along the looked-up volume's own axes (map^T = map^-1).
    const glm::dmat2 toLook = glm::transpose(look.map);
    const glm::dvec2 uLocal = toLook * walk.u, vLocal = toLook * walk.v;
    const glm::dvec2 extent = 0.5 * (glm::abs(uLocal) + glm::abs(vLocal)) + glm::dvec2(1e-4 * h);

    const std::span<const VoxelRun> walkRuns = walk.volume->runs();
    for (const VoxelColumn& column : walk.volume->columns()) {
        const glm::dvec2 centre = columnCentre(walk, column.x, column.z);
        const glm::dvec2 local = toLook * (centre - look.offset);
        // Columns c with [c h, (c + 1) h] meeting [local - extent, local + extent].
        const int32_t x0 = std::max(lookMin.x, int32_t(std::ceil((local.x - extent.x) / h - 1.0)));
        const int32_t x1 = std::min(lookMax.x, int32_t(std::floor((local.x + extent.x) / h)));
        const int32_t z0 = std::max(lookMin.z, int32_t(std::ceil((local.y - extent.y) / h - 1.0)));
        const int32_t z1 = std::min(lookMax.z, int32_t(std::floor((local.y + extent.y) / h)));
        if (x0 > x1 || z0 > z1)
            continue;
        const std::span<const VoxelRun> runs = walkRuns.subspan(column.firstRun, column.runCount);
        for (int32_t z = z0; z <= z1; ++z)
            for (int32_t x = x0; x <= x1; ++x) {
                const std::span<const VoxelRun> lookRuns = lookVolume.columnRuns(x, z);
                if (lookRuns.empty() || !runsOverlap(runs, walk.y, lookRuns, look.y, h))
                    continue;
                if (!squaresSeparated(centre, walk.u, walk.v, columnCentre(look, x, z), look.u, look.v,
                                      kPenetration * h))
                    return true;
            }
    }
    return false;
}

} // namespace meadow
