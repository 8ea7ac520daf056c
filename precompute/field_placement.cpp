#include "field_placement.h"

#include "placement/field.h"
#include "placement/swept_volume.h"
#include "placement/tile_fill.h"

#include <algorithm>
#include <cmath>

namespace meadow {
namespace {

// The cull pass's sphere is centred half its radius above the base (mesh.h). A point at
// horizontal distance rho <= R_f (the footprint) and height 0 <= y <= R lies inside it when
// rho^2 + (y - R/2)^2 <= R^2, which holds for R >= 2 R_f / sqrt 3; below the base the margin's
// cells reach at most a few centimetres.
float sweptBoundingRadius(const SweptVolume& volume, float meanPoseRadius) {
    return std::max(
        {meanPoseRadius, 1.1548f * volume.footprintRadius(), volume.maxY() - std::min(0.0f, volume.minY())});
}

gpu::GpuInstance gpuInstance(const PlacedInstance& placed, float radius) {
    gpu::GpuInstance inst{};
    inst.positionScale = glm::vec4(placed.position, placed.mirrored ? -1.0f : 1.0f);
    inst.yaw = placed.yaw;
    inst.boundingRadius = radius;
    inst.mesh = placed.index;
    return inst;
}

} // namespace

Mesh makeTerrainMesh(const TerrainParams& params, glm::vec2 fieldHalfExtent, float margin, float spacing) {
    const Terrain terrain(params);
    const float plain = -params.amplitude - 0.05f;
    const glm::vec2 half = fieldHalfExtent + glm::vec2(margin);
    const uint32_t nx = uint32_t(std::ceil(2.0f * half.x / spacing)) + 1;
    const uint32_t nz = uint32_t(std::ceil(2.0f * half.y / spacing)) + 1;
    auto heightAt = [&](float x, float z) {
        const float outside = std::max({std::abs(x) - fieldHalfExtent.x, std::abs(z) - fieldHalfExtent.y, 0.0f});
        const float t = margin > 0.0f ? std::clamp(outside / margin, 0.0f, 1.0f) : (outside > 0.0f ? 1.0f : 0.0f);
        const float ease = 1.0f - t * t * (3.0f - 2.0f * t);
        return plain + (terrain.height(x, z) - plain) * ease;
    };
    Mesh mesh;
    std::vector<float> heights(size_t(nx) * nz);
    for (uint32_t j = 0; j < nz; ++j)
        for (uint32_t i = 0; i < nx; ++i) {
            const float x = -half.x + 2.0f * half.x * float(i) / float(nx - 1);
            const float z = -half.y + 2.0f * half.y * float(j) / float(nz - 1);
            heights[size_t(j) * nx + i] = heightAt(x, z);
        }
    const float dx = 2.0f * half.x / float(nx - 1), dz = 2.0f * half.y / float(nz - 1);
    for (uint32_t j = 0; j < nz; ++j)
        for (uint32_t i = 0; i < nx; ++i) {
            const float x = -half.x + dx * float(i), z = -half.y + dz * float(j);
            auto h = [&](uint32_t a, uint32_t b) { return heights[size_t(b) * nx + a]; };
            const float gx = (h(std::min(i + 1, nx - 1), j) - h(i > 0 ? i - 1 : 0, j)) /
                             (dx * float(std::min(i + 1, nx - 1) - (i > 0 ? i - 1 : 0)));
            const float gz = (h(i, std::min(j + 1, nz - 1)) - h(i, j > 0 ? j - 1 : 0)) /
                             (dz * float(std::min(j + 1, nz - 1) - (j > 0 ? j - 1 : 0)));
            mesh.vertices.push_back({glm::vec4(x, heights[size_t(j) * nx + i], z, 0.0f),
                                     glm::vec4(glm::normalize(glm::vec3(-gx, 1.0f, -gz)), 0.0f)});
        }
    for (uint32_t j = 0; j + 1 < nz; ++j)
        for (uint32_t i = 0; i + 1 < nx; ++i) {
            const uint32_t a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
            mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
        }
    // The plain: a ring from the grid's border out to 1 km, at the border's height.
    const uint32_t ring = uint32_t(mesh.vertices.size());
    const float far = 1000.0f;
    const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const glm::vec2& c : corners)
        mesh.vertices.push_back({glm::vec4(c.x * half.x, plain, c.y * half.y, 0.0f), glm::vec4(0, 1, 0, 0)});
    for (const glm::vec2& c : corners)
        mesh.vertices.push_back(
            {glm::vec4(c.x * (half.x + far), plain, c.y * (half.y + far), 0.0f), glm::vec4(0, 1, 0, 0)});
    for (uint32_t k = 0; k < 4; ++k) {
        const uint32_t in0 = ring + k, in1 = ring + (k + 1) % 4, out0 = ring + 4 + k, out1 = ring + 4 + (k + 1) % 4;
        mesh.indices.insert(mesh.indices.end(), {in0, out0, in1, in1, out0, out1});
    }
    return mesh;
}

PlacedField placeField(const Scene& scene, const std::vector<ClumpMotion>& motions, const std::vector<Mesh>& meshes) {
    const FieldSpec& p = scene.field;
    PlacedField out;
    VoxelizeParams voxels;
    voxels.cellSize = p.cellSize;
    voxels.margin = p.margin;

    // Swept volumes from the simulated frames, half of them from the strongest wind level as
    // Cove & James weight theirs.
    std::vector<SweptVolume> clumpVolumes;
    for (size_t c = 0; c < motions.size(); ++c) {
        const ClumpMotion& motion = motions[c];
        std::vector<uint32_t> framesPerLevel;
        for (const MotionClip& clip : motion.clips)
            framesPerLevel.push_back(clip.frameCount);
        const std::vector<uint32_t> frames = selectSweptFrames(framesPerLevel, p.sweptFrames, 0.5f);
        const Mesh& mesh = meshes[c];
        FrameSource frameAt = [&](uint32_t i, std::vector<glm::vec3>& positions) {
            positions.resize(mesh.vertices.size());
            for (size_t v = 0; v < mesh.vertices.size(); ++v)
                positions[v] =
                    glm::vec3(mesh.vertices[v].positionU) + motion.basis.displacement(uint32_t(v), frames[i]);
        };
        clumpVolumes.push_back(voxelizeSweptSurface(mesh.indices, uint32_t(frames.size()), frameAt, voxels));
        out.stats.sweptFootprintRadius.push_back(clumpVolumes.back().footprintRadius());
    }

    // Rocks: static, and nothing may be placed inside one.
    out.rockMeshes = makeRocks(scene.seed ^ 0x726f636bull, p.rockVariants, rockParamsForPreset(scene.preset));
    std::vector<SweptVolume> rockVolumes;
    VoxelizeParams rockVoxels = voxels;
    rockVoxels.fillEnclosed = true;
    for (const RockMesh& rock : out.rockMeshes)
        rockVolumes.push_back(
            voxelizeSweptSurface(rock.indices, std::vector<std::vector<glm::vec3>>{rock.positions}, rockVoxels));

    TileFillParams fill;
    fill.tileSize = p.tileSize;
    fill.windDirection = glm::vec2(scene.wind.direction.x, scene.wind.direction.z);
    fill.clumpYawJitter = p.yawJitter;
    fill.maxRocksPerTile = p.rocksPerTile;
    fill.seed = scene.seed ^ 0x74696c6573ull; // "tiles"
    const WangTileFill tiles =
        fillWangTiles(clumpVolumes, p.rocksPerTile > 0 ? rockVolumes : std::vector<SweptVolume>{}, fill);
    out.stats.tiles = uint32_t(tiles.tiles.size());
    out.stats.clumpsPerTile = tiles.clumpsPerTile();
    out.stats.rocksPerTile = tiles.rocksPerTile();
    out.stats.overlapViolations = countTileOverlapViolations(tiles, clumpVolumes, rockVolumes);
    out.stats.densityVsPoissonDisc = densityVsPoissonDisc(tiles, fillWangTilesPoissonDisc(clumpVolumes, fill));

    out.terrain.amplitude = p.terrainAmplitude;
    out.terrain.wavelength = p.terrainWavelength;
    out.terrain.seed = scene.seed ^ 0x7465727261ull; // "terra"
    const Terrain terrain(out.terrain);
    FieldParams tiling;
    tiling.tilesX = p.tilesX;
    tiling.tilesY = p.tilesY;
    tiling.seed = scene.seed ^ 0x6669656c64ull; // "field"
    const Field field = buildField(tiles, clumpVolumes, rockVolumes, terrain, tiling);
    out.stats.tilesX = field.tilesX;
    out.stats.tilesY = field.tilesY;
    out.stats.tileSize = field.tileSize;
    out.stats.overlaps3dFound = field.overlaps3d.pairsFound;
    out.stats.clumpsRemoved3d = field.overlaps3d.clumpsRemoved;
    out.stats.rocksRemoved3d = field.overlaps3d.rocksRemoved;
    out.stats.overlapViolations3d = field.overlaps3d.pairsRemaining;

    for (const PlacedInstance& placed : field.clumps)
        out.clumps.push_back(
            gpuInstance(placed, sweptBoundingRadius(clumpVolumes[placed.index], meshes[placed.index].boundingRadius)));
    for (const PlacedInstance& placed : field.rocks)
        out.rocks.push_back(gpuInstance(placed, sweptBoundingRadius(rockVolumes[placed.index], 0.0f)));
    return out;
}

} // namespace meadow
