// The 3D overlap check of a finished field (field.h): a world hash grid over all instances for the
// candidate pairs, the exact voxel-box test for each.
#include "core/error.h"
#include "placement/field.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace meadow {

std::vector<std::pair<uint32_t, uint32_t>> findFieldOverlaps(const Field& field, std::span<const SweptVolume> clumps,
                                                             std::span<const SweptVolume> rocks,
                                                             uint64_t* candidatePairs) {
    struct Item {
        const SweptVolume* volume;
        InstanceTransform transform;
    };
    std::vector<Item> items;
    items.reserve(field.clumps.size() + field.rocks.size());
    float maxRadius = 0.0f;
    auto add = [&](const PlacedInstance& instance, std::span<const SweptVolume> volumes, const char* kind) {
        if (instance.index >= volumes.size())
            throw Error(std::string("field overlap check: ") + kind + " index " + std::to_string(instance.index) +
                        " is out of range (" + std::to_string(volumes.size()) + " volumes)");
        items.push_back({&volumes[instance.index], instance.transform()});
        maxRadius = std::max(maxRadius, volumes[instance.index].footprintRadius());
    };
    for (const PlacedInstance& instance : field.clumps)
        add(instance, clumps, "clump");
    for (const PlacedInstance& instance : field.rocks)
        add(instance, rocks, "rock");
    if (candidatePairs)
        *candidatePairs = 0;
    if (items.empty())
        return {};

    // Buckets two radii wide: instances whose bounding cylinders meet lie in neighbouring buckets.
    const double bucket = std::max(2.0 * double(maxRadius), 1e-3);
    glm::dvec2 lo(items[0].transform.position.x, items[0].transform.position.z), hi = lo;
    for (const Item& item : items) {
        lo = glm::min(lo, glm::dvec2(item.transform.position.x, item.transform.position.z));
        hi = glm::max(hi, glm::dvec2(item.transform.position.x, item.transform.position.z));
    }
    const glm::ivec2 buckets = glm::ivec2(glm::floor((hi - lo) / bucket)) + glm::ivec2(1);
    if (double(buckets.x) * double(buckets.y) > 1e8)
        throw Error("field overlap check: the field spans too many buckets (" + std::to_string(buckets.x) + " x " +
                    std::to_string(buckets.y) + ")");
    auto bucketOf = [&](const Item& item) {
        const glm::dvec2 p(item.transform.position.x, item.transform.position.z);
        return glm::min(glm::ivec2(glm::floor((p - lo) / bucket)), buckets - glm::ivec2(1));
    };
    // Counting sort of the items by bucket (stable: ascending item order inside a bucket).
    std::vector<uint32_t> start(size_t(buckets.x) * size_t(buckets.y) + 1, 0), order(items.size());
    std::vector<glm::ivec2> cell(items.size());
    for (size_t i = 0; i < items.size(); ++i) {
        cell[i] = bucketOf(items[i]);
        ++start[size_t(cell[i].y) * size_t(buckets.x) + size_t(cell[i].x) + 1];
    }
    for (size_t b = 1; b < start.size(); ++b)
        start[b] += start[b - 1];
    std::vector<uint32_t> fillAt(start.begin(), start.end() - 1);
    for (size_t i = 0; i < items.size(); ++i)
        order[fillAt[size_t(cell[i].y) * size_t(buckets.x) + size_t(cell[i].x)]++] = uint32_t(i);

    std::vector<std::vector<uint32_t>> partners(items.size());
    std::vector<uint64_t> candidates(items.size(), 0);
    tbb::parallel_for(size_t(0), items.size(), [&](size_t i) {
        const Item& a = items[i];
        for (int32_t bz = std::max(0, cell[i].y - 1); bz <= std::min(buckets.y - 1, cell[i].y + 1); ++bz)
            for (int32_t bx = std::max(0, cell[i].x - 1); bx <= std::min(buckets.x - 1, cell[i].x + 1); ++bx) {
                const size_t b = size_t(bz) * size_t(buckets.x) + size_t(bx);
                for (uint32_t k = start[b]; k < start[b + 1]; ++k) {
                    const uint32_t j = order[k];
                    if (j <= i)
                        continue;
                    const Item& other = items[j];
                    const glm::vec2 d(a.transform.position.x - other.transform.position.x,
                                      a.transform.position.z - other.transform.position.z);
                    const float reach = a.volume->footprintRadius() + other.volume->footprintRadius();
                    if (glm::dot(d, d) > reach * reach * 1.0001f)
                        continue;
                    ++candidates[i];
                    if (sweptVolumesOverlap(*a.volume, a.transform, *other.volume, other.transform,
                                            field.windDirection))
                        partners[i].push_back(j);
                }
            }
        std::sort(partners[i].begin(), partners[i].end());
    });
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
    for (size_t i = 0; i < items.size(); ++i) {
        for (uint32_t j : partners[i])
            pairs.emplace_back(uint32_t(i), j);
        if (candidatePairs)
            *candidatePairs += candidates[i];
    }
    return pairs;
}

} // namespace meadow
