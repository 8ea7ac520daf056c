#include "pipeline/rocks.h"

#include <algorithm>
#include <meshoptimizer.h>

namespace meadow {

std::array<RockLod, kLodCount> buildRockLods(const RockMesh& mesh) {
    const float fractions[kLodCount] = {1.0f, 1.0f / 3.0f, 1.0f / 10.0f, 1.0f / 20.0f, 1.0f / 30.0f};
    const size_t vertexCount = mesh.positions.size();
    std::array<RockLod, kLodCount> lods;
    std::vector<uint32_t> previous = mesh.indices;
    for (uint32_t l = 0; l < kLodCount; ++l) {
        std::vector<uint32_t> indices = previous;
        if (l > 0) {
            const size_t target = std::max<size_t>(3, size_t(float(mesh.indices.size() / 3) * fractions[l]) * 3);
            indices.resize(previous.size());
            indices.resize(meshopt_simplify(indices.data(), previous.data(), previous.size(), &mesh.positions[0].x,
                                            vertexCount, sizeof(glm::vec3), target, 0.05f, meshopt_SimplifyLockBorder,
                                            nullptr));
            if (indices.empty())
                indices = previous;
        }
        previous = indices;
        meshopt_optimizeVertexCache(indices.data(), indices.data(), indices.size(), vertexCount);
        // The LOD's own vertices in first-use order, and its triangles over them.
        RockLod& lod = lods[l];
        std::vector<uint32_t> local(vertexCount, UINT32_MAX);
        for (uint32_t i : indices) {
            if (local[i] == UINT32_MAX) {
                local[i] = uint32_t(lod.vertices.size());
                lod.vertices.push_back(i);
            }
            lod.indices.push_back(local[i]);
        }
    }
    return lods;
}

std::vector<LibraryRock> buildRocks(const std::vector<RockMesh>& meshes, const transfer::BakeSettings& bake) {
    std::vector<LibraryRock> rocks;
    for (const RockMesh& mesh : meshes) {
        LibraryRock rock;
        rock.mesh = mesh;
        rock.lods = buildRockLods(mesh);
        transfer::BakeSettings settings = bake;
        settings.groundGridSize = 2.0f * mesh.size;
        const std::vector<glm::vec3> albedo(mesh.positions.size(), kRockAlbedo);
        const std::vector<float> translucency(mesh.positions.size(), 0.0f);
        const transfer::ClumpTransfer t =
            transfer::bakeTransfer({mesh.positions, mesh.normals, mesh.indices, albedo, translucency}, settings);
        rock.order = t.vertices.order;
        rock.transfer = t.vertices.coefficients;
        rock.groundResolution = t.ground.resolution;
        rock.groundSize = t.ground.size;
        rock.groundTransfer = t.ground.coefficients;
        rocks.push_back(std::move(rock));
    }
    return rocks;
}

} // namespace meadow
