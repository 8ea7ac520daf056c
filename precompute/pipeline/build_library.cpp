#include "pipeline/build_library.h"

#include "core/error.h"
#include "core/random.h"
#include "library/library_file.h"
#include "pipeline/clump_light.h"
#include "pipeline/clump_lod.h"
#include "pipeline/clump_motion.h"
#include "pipeline/far_samples.h"
#include "pipeline/field_placement.h"
#include "pipeline/rocks.h"
#include "plants/atlas.h"
#include "plants/gltf_import.h"
#include "plants/iris.h"
#include "sky/environment_map.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <tbb/parallel_for.h>

namespace meadow {
namespace {

// The clumps and the one atlas every clump is drawn with: the iris atlas, with an imported
// plant's base colours painted into its import region and the plant's UVs moved there
// (plants/gltf_import.h).
std::vector<PlantClump> makePlants(const Scene& scene, TextureAtlas& atlas) {
    atlas = makeIrisAtlas(irisParamsForPreset(scene.preset).atlasSize, scene.seed);
    if (scene.plants.source == "gltf") {
        GltfImportOptions options;
        options.stemDiameter = scene.plants.stemDiameter;
        ImportedPlant plant = importGltfPlantWithMaterials(scene.plants.gltf, options);
        paintImportedPlant(plant, atlas);
        return {std::move(plant.clump)};
    }
    return makeIrisClumps(scene.seed, scene.plants.clumps, irisParamsForPreset(scene.preset));
}

// Progress lines on stderr, each with the seconds since the run began.
struct Progress {
    bool quiet = false;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();

    template <typename... Args> void operator()(const char* fmt, Args... args) const {
        if (quiet)
            return;
        double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::fprintf(stderr, "meadow: [%6.1f s] ", t);
        std::fprintf(stderr, fmt, args...);
        std::fprintf(stderr, "\n");
    }
};

} // namespace

Library buildLibrary(const Scene& scene, bool quiet) {
    const Progress say{quiet};
    say("precompute %s (preset %s, seed %llu)", scene.name.c_str(), scene.preset.c_str(),
        static_cast<unsigned long long>(scene.seed));
    Library library;
    library.scene = parseLibraryScene(scene.resolved.dump(2), "scene " + scene.name);

    library.skyFromMaps = !scene.sky.maps.empty();
    library.sky = library.skyFromMaps ? sky::buildEnvironmentDay(scene.sky.maps, scene.sky.params)
                                      : sky::buildSkyDay(scene.sky.params);
    say("sky: %zu frames (%s), SH order %d", library.sky.frames.size(),
        library.skyFromMaps ? "panoramas" : "analytic daylight", library.sky.shOrder);

    TextureAtlas atlas;
    std::vector<PlantClump> plants = makePlants(scene, atlas);
    say("plants: %zu clumps (%s)", plants.size(), scene.plants.source.c_str());
    library.atlas = RgbaImage{atlas.width, atlas.height, atlas.rgba};

    say("motion: simulating %zu clumps x %zu wind levels, %.1f s each", plants.size(), scene.wind.levelSpeeds.size(),
        double(scene.motion.recordSeconds));
    std::vector<ClumpMotion> motions(plants.size());
    tbb::parallel_for(size_t(0), plants.size(),
                      [&](size_t i) { motions[i] = buildClumpMotion(plants[i], scene, scene.seed * 1000003ull + i); });
    // Every later stage works on the clumps as drawn.
    std::vector<Mesh> meshes;
    for (const ClumpMotion& m : motions)
        meshes.push_back(clumpRenderMesh(m));
    library.clumps.resize(motions.size());
    for (size_t i = 0; i < motions.size(); ++i) {
        const ClumpMotion& m = motions[i];
        say("clump %s: %zu vertices, %zu triangles, %u frames, LOD0 %u modes (%.2f%% error), graph %u nodes %u edges, "
            "max penetration %.1f mm (simulate %.1f s, PCA %.1f s, graph %.1f s)",
            m.clump.name.c_str(), m.clump.mesh.positions.size(), m.clump.mesh.indices.size() / 3, m.basis.frames,
            m.basis.lodModes[0], m.basis.relativeErrorPerMode[m.basis.lodModes[0]] * 100.0, m.graph.nodeCount,
            m.graph.edgeCount,
            double(std::max_element(m.levels.begin(), m.levels.end(),
                                    [](auto& a, auto& b) { return a.maxPenetration < b.maxPenetration; })
                       ->maxPenetration *
                   1000.0f),
            m.simulateSeconds, m.pcaSeconds, m.graphSeconds);
        for (uint32_t l = 0; l < m.graph.levelCount; ++l)
            if (m.graph.levelThresholdScale[l] != 1.0f || m.graph.levelLoopFrames[l] > 0)
                say("clump %s wind level %u: too few transitions to keep its frames; threshold raised %gx%s",
                    m.clump.name.c_str(), l, double(m.graph.levelThresholdScale[l]),
                    m.graph.levelLoopFrames[l] > 0
                        ? (", looped over " + std::to_string(m.graph.levelLoopFrames[l]) + " frames").c_str()
                        : "");
        const WindResponse wind = measureWindResponse(m.graph);
        say("clump %s wind response (the walk reaching the new level's frames; median, p95): calm to strongest %.2f "
            "s, %.2f s; back %.2f s, %.2f s",
            m.clump.name.c_str(), wind.upMedianSeconds, wind.upP95Seconds, wind.downMedianSeconds, wind.downP95Seconds);
        LibraryClump& clump = library.clumps[i];
        clump.name = m.clump.name;
        clump.plants = m.clump.plants;
        clump.mesh = meshes[i];
        clump.motion = m.basis;
        clump.graph = m.graph;
        clump.levels = m.levels;
    }

    say("light: baking %u frames per wind level of each clump, %u rays per vertex, %u bounces",
        scene.light.framesPerLevel, scene.light.bake.raysPerVertex, scene.light.bake.bounces);
    // The error figures are measured under a clear noon sky of the scene's own latitude and day.
    const std::vector<float> testSky = sky::buildSkyFrame(scene.sky.params, 12.0).sh;
    std::vector<ClumpLight> lights(motions.size());
    tbb::parallel_for(size_t(0), motions.size(), [&](size_t i) {
        lights[i] =
            buildClumpLight(motions[i], meshes[i], vertexAlbedo(meshes[i], library.atlas), scene.light, testSky);
    });
    for (size_t i = 0; i < lights.size(); ++i) {
        const ClumpLight& l = lights[i];
        say("clump %s light: %zu frames baked (noise %.2f%%); noon irradiance at held-out frames within %.2f%% "
            "(mean alone %.2f%%, noise %.2f%%); ground (its mean) within %.2f%% (noise %.2f%%) (bake %.1f s, fit "
            "%.1f s)",
            motions[i].clump.name.c_str(), l.bakedFrames.size(), l.vertexNoise * 100.0, l.vertexHeldOutError * 100.0,
            l.vertexMeanOnlyError * 100.0, l.vertexIrradianceNoise * 100.0, l.groundHeldOutError * 100.0,
            l.groundIrradianceNoise * 100.0, l.bakeSeconds, l.reduceSeconds);
        library.clumps[i].light = libraryLight(l);
    }

    say("levels of detail: %u per clump", kLodCount);
    std::vector<std::array<ClumpLod, kLodCount>> lods(motions.size());
    tbb::parallel_for(size_t(0), motions.size(), [&](size_t i) {
        lods[i] = buildClumpLods(motions[i], lights[i], meshes[i], testSky, scene.lod);
    });
    for (size_t i = 0; i < lods.size(); ++i) {
        std::string line;
        for (const ClumpLod& lod : lods[i]) {
            char part[96];
            std::snprintf(part, sizeof(part), " %zu (%.1f mm)", lod.indices.size() / 3,
                          lod.error.deformed.rms * 1000.0);
            line += part;
        }
        say("clump %s LOD triangles (RMS distance over frames):%s", motions[i].clump.name.c_str(), line.c_str());
        library.clumps[i].lods = lods[i];
    }

    PlacedField placed = placeField(scene, motions, meshes);
    const PlacementStats& fs = placed.stats;
    say("field: %u x %u tiles of %.1f m, %zu clumps and %zu rocks; %.2fx the density of Poisson discs; %u pairs met "
        "on the terrain and were resolved (%u clumps, %u rocks removed), %u left",
        fs.tilesX, fs.tilesY, double(fs.tileSize), placed.clumps.size(), placed.rocks.size(), fs.densityVsPoissonDisc,
        fs.overlaps3dFound, fs.clumpsRemoved3d, fs.rocksRemoved3d, fs.overlapViolations3d);
    library.field.clumpInstances = placed.clumps;
    // Rocks are static: one bake each, with the ground around them, and five LODs.
    library.field.rocks = buildRocks(placed.rockMeshes, scene.light.bake);
    library.field.rockInstances = placed.rocks;
    library.field.terrain = placed.terrain;
    library.field.windDirection = glm::normalize(glm::vec2(scene.wind.direction.x, scene.wind.direction.z));
    library.field.stats = placed.stats;

    // The far field's surface samples of every clump and rock, over LOD 0, playing the last LOD.
    const auto farStart = std::chrono::steady_clock::now();
    buildLibraryFarSamples(library, scene.far.samplesPerClump, scene.seed);
    size_t farSamples = 0;
    for (const LibraryClump& clump : library.clumps)
        farSamples += clump.far.samples.size();
    for (const LibraryRock& rock : library.field.rocks)
        farSamples += rock.far.samples.size();
    say("far field: %u surface samples per clump and rock, %zu in all over %zu clumps and %zu rocks (%.1f ms)",
        scene.far.samplesPerClump, farSamples, library.clumps.size(), library.field.rocks.size(),
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - farStart).count());
    return library;
}

void buildLibrary(const Scene& scene, const std::filesystem::path& path, bool quiet) {
    const Progress say{quiet};
    const Library library = buildLibrary(scene, quiet);
    std::error_code ec;
    if (!path.parent_path().empty())
        std::filesystem::create_directories(path.parent_path(), ec);
    writeLibrary(path, library, libraryInputHash(scene));
    say("wrote %s", path.string().c_str());
}

Library ensureLibrary(const Scene& scene, bool quiet) {
    std::filesystem::path path = cachedLibraryPath(scene);
    uint64_t hash = 0;
    if (peekLibraryInputHash(path, hash) && hash == libraryInputHash(scene)) {
        try {
            return loadLibrary(path);
        } catch (const Error& e) {
            std::fprintf(stderr, "meadow: cached library is unusable, rebuilding: %s\n", e.what());
        }
    } else if (std::filesystem::exists(path)) {
        std::fprintf(stderr, "meadow: cached library %s is stale or corrupt, rebuilding\n", path.string().c_str());
    }
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);
    if (ec)
        throw Error("cannot create the library cache folder " + path.parent_path().string() + ": " + ec.message() +
                    " (set MEADOW_CACHE_DIR)");
    buildLibrary(scene, path, quiet);
    return loadLibrary(path);
}

} // namespace meadow
