// Conservative surface voxelization of a clump over its frames (swept_volume.h).
#include "core/error.h"
#include "placement/swept_volume.h"
#include "placement/triangle_box.h"
#include "placement/voxel_bit_box.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace meadow {
namespace {

// Gives frame f's positions: either a view of a frame held in memory, or `scratch` filled by the
// caller's FrameSource.
using FrameView = std::function<std::span<const glm::vec3>(uint32_t frame, std::vector<glm::vec3>& scratch)>;

struct FrameBounds {
    glm::dvec3 lo{std::numeric_limits<double>::max()};
    glm::dvec3 hi{std::numeric_limits<double>::lowest()};
    std::string error; // empty when the frame is usable
};

FrameBounds boundsOfFrame(std::span<const uint32_t> indices, std::span<const glm::vec3> positions, uint32_t frame) {
    FrameBounds bounds;
    for (uint32_t index : indices) {
        if (index >= positions.size()) {
            bounds.error = "frame " + std::to_string(frame) + " has " + std::to_string(positions.size()) +
                           " vertices but index " + std::to_string(index) + " names one past them";
            return bounds;
        }
        const glm::vec3 p = positions[index];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            bounds.error = "frame " + std::to_string(frame) + " vertex " + std::to_string(index) + " is not finite";
            return bounds;
        }
        bounds.lo = glm::min(bounds.lo, glm::dvec3(p));
        bounds.hi = glm::max(bounds.hi, glm::dvec3(p));
    }
    return bounds;
}

// Marks every cell whose closed box the triangle touches. Candidate cells are those of the
// triangle's bounding box, counting a cell whose face the box merely touches (ceil - 1 below,
// floor above); each is then decided by Akenine-Möller's separating axis test, unless it is
// already marked (by this frame's other triangles or an earlier frame's: a clump's frames cover
// nearly the same cells, and marking is an OR, so the box is the same).
void markTriangle(VoxelBitBox& box, double cellSize, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
    const glm::ivec3 first(glm::ceil(lo / cellSize) - 1.0), last(glm::floor(hi / cellSize));
    // Half a cell, grown by 5e-6 of a cell so rounding in the test can only add cells, never lose
    // one that the exact triangle touches; instance.h relies on this growth (a ball of that radius
    // around every surface point is covered).
    const glm::dvec3 halfSize(0.5 * cellSize * (1.0 + 1e-5));
    for (int32_t z = first.z; z <= last.z; ++z)
        for (int32_t x = first.x; x <= last.x; ++x)
            for (int32_t y = first.y; y <= last.y; ++y) {
                if (box.test({x, y, z}))
                    continue;
                const glm::dvec3 centre = (glm::dvec3(x, y, z) + 0.5) * cellSize;
                if (triangleBoxOverlap(centre, halfSize, a, b, c))
                    box.set({x, y, z});
            }
}

SweptVolume voxelize(std::span<const uint32_t> indices, uint32_t frameCount, const FrameView& frameAt,
                     const VoxelizeParams& params) {
    const std::string what = "swept volume voxelization: ";
    if (!(params.cellSize > 0.0f) || !std::isfinite(params.cellSize))
        throw Error(what + "cell size " + std::to_string(params.cellSize) + " m is not a positive finite number");
    if (!(params.margin >= 0.0f) || !std::isfinite(params.margin))
        throw Error(what + "margin " + std::to_string(params.margin) + " m is not a finite number >= 0");
    if (indices.empty() || indices.size() % 3 != 0)
        throw Error(what + std::to_string(indices.size()) + " indices do not make a non-empty triangle list");
    if (frameCount == 0)
        throw Error(what + "no frames");

    // Pass 1: the bounds of every frame (min and max reduce to the same values in any order).
    std::vector<FrameBounds> bounds(frameCount);
    tbb::parallel_for(uint32_t(0), frameCount, [&](uint32_t f) {
        std::vector<glm::vec3> scratch;
        bounds[f] = boundsOfFrame(indices, frameAt(f, scratch), f);
    });
    glm::dvec3 lo{std::numeric_limits<double>::max()}, hi{std::numeric_limits<double>::lowest()};
    for (const FrameBounds& b : bounds) { // the first bad frame is the one reported, whatever ran first
        if (!b.error.empty())
            throw Error(what + b.error);
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    const double h = double(params.cellSize);
    const int32_t k = int32_t(std::ceil(double(params.margin) / h - 1e-4));
    // Candidate cells of every triangle, plus k cells for the dilation and one free layer so the
    // enclosed-space fill can flood around the outside.
    const int32_t pad = std::max(k, 0) + 1;
    const glm::ivec3 first = glm::ivec3(glm::ceil(lo / h) - 1.0) - pad;
    const glm::ivec3 last = glm::ivec3(glm::floor(hi / h)) + pad;
    const glm::ivec3 size = last - first + glm::ivec3(1);
    if (double(size.x) * double(size.y) * double(size.z) > 2e9)
        throw Error(what + "the clump spans " + std::to_string(size.x) + " x " + std::to_string(size.y) + " x " +
                    std::to_string(size.z) + " cells of " + std::to_string(params.cellSize) +
                    " m; the cell size is too small for its size");

    // Pass 2: each thread marks its frames into its own box; OR of the boxes is order-independent.
    tbb::enumerable_thread_specific<std::optional<VoxelBitBox>> partial;
    tbb::parallel_for(uint32_t(0), frameCount, [&](uint32_t f) {
        std::optional<VoxelBitBox>& local = partial.local();
        if (!local)
            local.emplace(first, size);
        std::vector<glm::vec3> scratch;
        const std::span<const glm::vec3> positions = frameAt(f, scratch);
        for (size_t t = 0; t < indices.size(); t += 3)
            markTriangle(*local, h, glm::dvec3(positions[indices[t]]), glm::dvec3(positions[indices[t + 1]]),
                         glm::dvec3(positions[indices[t + 2]]));
    });
    VoxelBitBox box(first, size);
    for (const std::optional<VoxelBitBox>& local : partial)
        if (local)
            box.orWith(*local);
    if (params.fillEnclosed)
        box.fillEnclosedAboveGround();
    box.dilate(k);
    return box.toVolume(params.cellSize);
}

} // namespace

SweptVolume voxelizeSweptSurface(std::span<const uint32_t> indices, uint32_t frameCount, const FrameSource& frameAt,
                                 const VoxelizeParams& params) {
    return voxelize(
        indices, frameCount,
        [&](uint32_t frame, std::vector<glm::vec3>& scratch) -> std::span<const glm::vec3> {
            frameAt(frame, scratch);
            return scratch;
        },
        params);
}

SweptVolume voxelizeSweptSurface(std::span<const uint32_t> indices, std::span<const std::vector<glm::vec3>> frames,
                                 const VoxelizeParams& params) {
    return voxelize(
        indices, uint32_t(frames.size()),
        [&](uint32_t frame, std::vector<glm::vec3>&) -> std::span<const glm::vec3> { return frames[frame]; }, params);
}

std::vector<uint32_t> selectSweptFrames(std::span<const uint32_t> framesPerLevel, uint32_t budget,
                                        float strongestShare) {
    if (framesPerLevel.empty())
        throw Error("swept frame selection: no wind level");
    for (size_t level = 0; level < framesPerLevel.size(); ++level)
        if (framesPerLevel[level] == 0)
            throw Error("swept frame selection: wind level " + std::to_string(level) + " has no frame");
    if (!(strongestShare >= 0.0f && strongestShare <= 1.0f))
        throw Error("swept frame selection: strongest-level share " + std::to_string(strongestShare) +
                    " is outside [0, 1]");
    const uint32_t strongest = framesPerLevel.back();
    uint32_t others = 0;
    for (size_t level = 0; level + 1 < framesPerLevel.size(); ++level)
        others += framesPerLevel[level];
    const uint32_t strongestWanted =
        others == 0 ? budget : uint32_t(std::lround(double(budget) * double(strongestShare)));
    const uint32_t strongestCount = std::min(strongest, strongestWanted);
    const uint32_t otherCount = std::min(others, budget - std::min(budget, strongestCount));

    // m evenly spaced picks among n frames, starting at `base`: frame base + floor((i + 1/2) n / m),
    // distinct because m <= n.
    std::vector<uint32_t> picked;
    auto spread = [&](uint32_t base, uint32_t n, uint32_t m) {
        for (uint32_t i = 0; i < m; ++i)
            picked.push_back(base + uint32_t((uint64_t(2 * i + 1) * n) / (2 * uint64_t(m))));
    };
    spread(0, others, otherCount);
    spread(others, strongest, strongestCount);
    return picked;
}

} // namespace meadow
