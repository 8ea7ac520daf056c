#include "render/field_content.h"

#include "core/error.h"

#include <algorithm>

namespace meadow {

float terrainMeshSpacing(const TerrainParams& terrain) {
    const float finest = terrain.wavelength / float(1u << std::min(std::max(terrain.octaves, 1u) - 1u, 12u));
    return std::clamp(finest / 5.0f, 0.5f, 2.0f);
}

FieldScenery fieldScenery(const Library& library, float lodTolerancePixels) {
    if (!(lodTolerancePixels > 0.0f))
        throw Error("fieldScenery: the LOD tolerance must be above 0 px");
    const PlacementStats& stats = library.field.stats;
    const glm::vec2 half = 0.5f * stats.tileSize * glm::vec2(float(stats.tilesX), float(stats.tilesY));
    // 20 m of margin ease the hills into the plain.
    FieldScenery scenery{makeTerrainMesh(library.field.terrain, half, 20.0f, terrainMeshSpacing(library.field.terrain)),
                         library.field.windDirection};
    scenery.sky = library.sky;
    scenery.lodCount = kLodCount;
    gpu::GpuLodParams& p = scenery.lod;
    p.band = 0.1f;
    p.jitter = 0.2f;
    p.hysteresis = 0.05f;
    // A sphere of radius R covering r pixels shows an error e at r e / R pixels: LOD i + 1 may
    // take over below r = tolerance R / e_(i+1), for the clump whose error is largest for its size.
    // 0.3 px of RMS error by default: at 1 px LOD 4's thinner silhouettes (its Hausdorff distance is
    // 5-10x the RMS) showed as a sparser field from ~10 m on, and LODs 2-3 lose some area (15-40 %
    // with the simplifier's area term), so the field darkens where they are drawn (docs/BENCHMARKS.md).
    std::vector<float> radius(library.clumps.size(), 0.0f);
    for (const gpu::GpuInstance& inst : library.field.clumpInstances)
        radius[inst.mesh] = std::max(radius[inst.mesh], inst.boundingRadius);
    for (uint32_t i = 0; i + 1 < kLodCount; ++i) {
        float r = 1e6f;
        for (size_t c = 0; c < library.clumps.size(); ++c) {
            const double e = library.clumps[c].lods[i + 1].error.deformed.rms;
            if (e > 0.0 && radius[c] > 0.0f)
                r = std::min(r, float(lodTolerancePixels * radius[c] / e));
        }
        // Bands must not overlap: each switch lies below the previous one's band.
        if (i > 0)
            r = std::min(r, p.switchRadius[i - 1] * (1.0f - p.band) / (1.0f + p.band) * 0.98f);
        p.switchRadius[i] = r;
    }
    return scenery;
}

std::vector<FieldClump> fieldClumps(const Library& library) {
    std::vector<FieldClump> clumps;
    // Clumps turn by at most the field's yaw jitter; light is projected for 4 yaws in that range.
    const float jitter = library.scene.yawJitter;
    for (const LibraryClump& source : library.clumps) {
        FieldClump clump;
        clump.mesh = source.mesh;
        for (const ClumpLod& lod : source.lods)
            clump.lods.push_back({lod.vertices, lod.indices});
        clump.motion = source.motion;
        clump.graph = source.graph;
        if (source.light.order != 3 || source.light.vertices.valuesPerVertex != 54)
            throw Error("library clump " + source.name + ": its light transfer has SH order " +
                        std::to_string(source.light.order) + "; the renderer draws order 3");
        clump.transfer = source.light.vertices.coefficients;
        clump.yawLow = -jitter;
        clump.yawHigh = jitter;
        clump.yawBins = jitter > 0.0f ? 4 : 1;
        // The ground grid's mean transfer over the motion (its appearance modes, if any, are small:
        // the grid varies less than its bake noise, DESIGN 2.5).
        if (source.light.groundResolution >= 2) {
            clump.groundTransfer = source.light.ground.mean;
            clump.groundResolution = source.light.groundResolution;
            clump.groundSize = source.light.groundSize;
        }
        clump.far = source.far.samples;
        clump.farArea = source.far.area;
        clump.farGain = source.far.gain;
        clumps.push_back(std::move(clump));
    }
    // Rocks: static, lit by their baked transfer (no gradient), turned to any yaw (8 light bins),
    // with the library's five LODs.
    for (const LibraryRock& rock : library.field.rocks) {
        Mesh mesh;
        for (size_t v = 0; v < rock.mesh.positions.size(); ++v)
            mesh.vertices.push_back({glm::vec4(rock.mesh.positions[v], rock.mesh.uvs[v].x),
                                     glm::vec4(rock.mesh.normals[v], rock.mesh.uvs[v].y)});
        mesh.indices = rock.mesh.indices;
        FieldClump clump = staticFieldClump(mesh, kLodCount);
        clump.lods.clear();
        for (const RockLod& lod : rock.lods)
            clump.lods.push_back({lod.vertices, lod.indices});
        if (rock.order != 3 || rock.transfer.size() != rock.mesh.positions.size() * 54)
            throw Error("library rock " + rock.mesh.name + ": its light transfer is not SH order 3 per vertex");
        clump.transfer.reserve(rock.transfer.size() * 4);
        for (float t : rock.transfer)
            clump.transfer.insert(clump.transfer.end(), {t, 0.0f, 0.0f, 0.0f});
        clump.albedo = glm::vec4(kRockAlbedo, 1.0f); // as baked (pipeline/rocks.cpp)
        if (rock.groundResolution >= 2) {
            clump.groundTransfer = rock.groundTransfer;
            clump.groundResolution = rock.groundResolution;
            clump.groundSize = rock.groundSize;
        }
        clump.far = rock.far.samples;
        clump.farArea = rock.far.area;
        clump.farGain = rock.far.gain;
        clump.farClosed = true;
        clumps.push_back(std::move(clump));
    }
    return clumps;
}

std::vector<gpu::GpuInstance> fieldInstances(const Library& library) {
    std::vector<gpu::GpuInstance> instances = library.field.clumpInstances;
    const uint32_t firstRock = uint32_t(library.clumps.size());
    for (gpu::GpuInstance rock : library.field.rockInstances) {
        rock.mesh += firstRock;
        instances.push_back(rock);
    }
    return instances;
}

} // namespace meadow
