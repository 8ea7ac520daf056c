#include "pipeline/field_placement.h"

#include "placement/field.h"
#include "placement/swept_volume.h"
#include "placement/tile_fill.h"

#include <algorithm>
#include <cmath>
#include <set>

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

PlacedField placeField(const Scene& scene, const std::vector<ClumpMotion>& motions, const std::vector<Mesh>& meshes) {
    const FieldSpec& p = scene.field;
    PlacedField out;
    VoxelizeParams voxels;
    voxels.cellSize = p.cellSize;
    voxels.margin = p.margin;

    // Swept volumes from the simulated frames, half of them from the strongest wind level as
    // Cove & James weight theirs; and, to measure what that sample misses, from every frame.
    std::vector<SweptVolume> clumpVolumes, allFrameVolumes;
    for (size_t c = 0; c < motions.size(); ++c) {
        const ClumpMotion& motion = motions[c];
        std::vector<uint32_t> framesPerLevel;
        for (const MotionClip& clip : motion.clips)
            framesPerLevel.push_back(clip.frameCount);
        const std::vector<uint32_t> frames = selectSweptFrames(framesPerLevel, p.sweptFrames, 0.5f);
        const uint32_t simulated = motion.basis.frames;
        const Mesh& mesh = meshes[c];
        auto framesFrom = [&](const std::vector<uint32_t>* picked) -> FrameSource {
            return [&mesh, &motion, picked](uint32_t i, std::vector<glm::vec3>& positions) {
                const uint32_t frame = picked ? (*picked)[i] : i;
                positions.resize(mesh.vertices.size());
                for (size_t v = 0; v < mesh.vertices.size(); ++v)
                    positions[v] =
                        glm::vec3(mesh.vertices[v].positionU) + motion.basis.displacement(uint32_t(v), frame);
            };
        };
        clumpVolumes.push_back(
            voxelizeSweptSurface(mesh.indices, uint32_t(frames.size()), framesFrom(&frames), voxels));
        allFrameVolumes.push_back(voxelizeSweptSurface(mesh.indices, simulated, framesFrom(nullptr), voxels));
        out.stats.sweptFootprintRadius.push_back(clumpVolumes.back().footprintRadius());
        out.stats.sweptFrames.push_back(uint32_t(frames.size()));
        out.stats.simulatedFrames.push_back(simulated);
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
    const PoissonDiscFill discs = fillWangTilesPoissonDisc(clumpVolumes, fill);
    out.stats.densityVsPoissonDisc = densityVsPoissonDisc(tiles, discs);
    out.stats.poissonClumpsPerTile = discs.clumpsPerTile();
    out.stats.overlapViolationsAllFrames = countTileOverlapViolations(tiles, allFrameVolumes, rockVolumes);

    out.terrain.amplitude = p.terrainAmplitude;
    out.terrain.wavelength = p.terrainWavelength;
    out.terrain.seed = scene.seed ^ 0x7465727261ull; // "terra"
    const Terrain terrain(out.terrain);
    FieldParams tiling;
    tiling.tilesX = p.tilesX;
    tiling.tilesY = p.tilesY;
    tiling.seed = scene.seed ^ 0x6669656c64ull; // "field"
    tiling.tiling = p.tiling == "hash" ? TilingMethod::Hash : TilingMethod::Scanline;
    const Field field = buildField(tiles, clumpVolumes, rockVolumes, terrain, tiling);
    out.stats.tilesX = field.tilesX;
    out.stats.tilesY = field.tilesY;
    out.stats.tileSize = field.tileSize;
    out.stats.overlaps3dFound = field.overlaps3d.pairsFound;
    out.stats.clumpsRemoved3d = field.overlaps3d.clumpsRemoved;
    out.stats.rocksRemoved3d = field.overlaps3d.rocksRemoved;
    out.stats.overlapViolations3d = field.overlaps3d.pairsRemaining;
    out.stats.overlapViolations3dAllFrames = uint32_t(findFieldOverlaps(field, allFrameVolumes, rockVolumes).size());
    out.stats.tiling = p.tiling;
    std::set<uint32_t> used(field.tiling.tiles.begin(), field.tiling.tiles.end());
    out.stats.fieldTiles.assign(used.begin(), used.end());

    for (const PlacedInstance& placed : field.clumps)
        out.clumps.push_back(
            gpuInstance(placed, sweptBoundingRadius(clumpVolumes[placed.index], meshes[placed.index].boundingRadius)));
    for (const PlacedInstance& placed : field.rocks)
        out.rocks.push_back(gpuInstance(placed, sweptBoundingRadius(rockVolumes[placed.index], 0.0f)));
    return out;
}

} // namespace meadow
