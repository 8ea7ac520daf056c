// meadow precompute / meadow inspect.
#include "app/commands.h"
#include "app/session.h"
#include "core/error.h"
#include "library/library_file.h"

#include <cstdio>
#include <fstream>

namespace meadow {
namespace {

const char* kPrecomputeHelp = R"(usage: meadow precompute SCENE [--preset ci|full] [--seed S] [--out LIB] [--force]

Builds the library of SCENE (a scene JSON file) and writes it to LIB, by default to the
library cache ($MEADOW_CACHE_DIR, else ~/.cache/meadow). Prints the library's path. A library
already there that was built from the same scene, preset and seed is kept (--force rebuilds).
)";

const char* kInspectHelp = R"(usage: meadow inspect LIB --json

Checks a library file and prints facts about it as JSON on stdout.
)";

// What the motion-graph build adapted, in words: per wind level, a raised threshold and a loop.
nlohmann::json graphAdaptations(const MotionGraph& g) {
    nlohmann::json said = nlohmann::json::array();
    for (uint32_t l = 0; l < g.levelCount; ++l) {
        char line[160];
        if (g.levelThresholdScale[l] != 1.0f) {
            std::snprintf(line, sizeof line, "wind level %u: transition threshold raised %gx", l,
                          double(g.levelThresholdScale[l]));
            said.push_back(line);
        }
        if (g.levelLoopFrames[l] > 0) {
            std::snprintf(line, sizeof line,
                          "wind level %u: looped over %u frames (the clip ends with a blended jump back into its "
                          "first half)",
                          l, g.levelLoopFrames[l]);
            said.push_back(line);
        }
    }
    return said;
}

// The far field's surface samples of a clump or rock (library/far_samples.h): how many, the
// area they cover (m^2, one side), their coverage gains (rows of sizes, columns of elevations:
// far_splat.h), the share of them that their own clump leaves in sight from each elevation (over
// its views' azimuths) and their bytes in the FARS section.
nlohmann::json farSamplesJson(const FarSamples& far) {
    nlohmann::json visible = nlohmann::json::array();
    for (uint32_t elevation = 0; elevation < gpu::kFarGainElevations; ++elevation) {
        const uint32_t azimuths = elevation + 1 < gpu::kFarGainElevations ? gpu::kFarVisibilityAzimuths : 1u;
        size_t seen = 0;
        for (const FarSample& s : far.samples)
            for (uint32_t a = 0; a < azimuths; ++a)
                seen += s.visibility >> gpu::farVisibilityBit(a, elevation) & 1u;
        visible.push_back(far.samples.empty() ? 0.0 : double(seen) / double(far.samples.size() * azimuths));
    }
    nlohmann::json gain = nlohmann::json::array();
    for (uint32_t size = 0; size < gpu::kFarGainSizes; ++size) {
        nlohmann::json row = nlohmann::json::array();
        for (uint32_t elevation = 0; elevation < gpu::kFarGainElevations; ++elevation)
            row.push_back(far.gain[size * gpu::kFarGainElevations + elevation]);
        gain.push_back(row);
    }
    return {{"samples", far.samples.size()},
            {"area", far.area},
            {"coverageGain", gain},
            {"visibleShare", visible},
            {"bytes", 8 + far.gain.size() * 4 + far.samples.size() * size_t(kFarSampleBytes)}};
}

} // namespace

int runPrecompute(const Args& argv) {
    if (printHelpIfAsked(argv, kPrecomputeHelp))
        return 0;
    CommandSpec spec{"precompute", {"SCENE"}, {"--out"}, {"--force"}};
    addSceneOptions(spec);
    ParsedArgs args = parseArgs(spec, argv);
    Scene scene = sceneFromArgs(args);
    std::filesystem::path out = args.value("--out").value_or(cachedLibraryPath(scene).string());
    std::error_code ec;
    if (out.has_parent_path() && !std::filesystem::is_directory(out.parent_path(), ec)) {
        if (args.has("--out"))
            throw Error("meadow precompute: --out " + out.string() + ": folder " + out.parent_path().string() +
                        " does not exist");
        std::filesystem::create_directories(out.parent_path(), ec);
        if (ec)
            throw Error("cannot create the library cache folder " + out.parent_path().string() + ": " + ec.message());
    }
    // An unchanged scene's library is reused: same inputs, and it reads back whole.
    uint64_t hash = 0;
    if (!args.has("--force") && peekLibraryInputHash(out, hash) && hash == libraryInputHash(scene)) {
        try {
            loadLibrary(out);
            std::fprintf(stderr, "meadow: %s is up to date\n", out.string().c_str());
            std::printf("%s\n", out.string().c_str());
            return 0;
        } catch (const Error& e) {
            std::fprintf(stderr, "meadow: rebuilding: %s\n", e.what());
        }
    }
    buildLibrary(scene, out);
    loadLibrary(out); // what was written must read back
    std::printf("%s\n", out.string().c_str());
    return 0;
}

int runInspect(const Args& argv) {
    if (printHelpIfAsked(argv, kInspectHelp))
        return 0;
    CommandSpec spec{"inspect", {"LIB"}, {}, {"--json"}};
    ParsedArgs args = parseArgs(spec, argv);
    if (!args.has("--json"))
        throw Error("meadow inspect: only JSON output exists; pass --json");
    Library lib = loadLibrary(args.positionals[0]);

    nlohmann::json j;
    j["formatVersion"] = lib.formatVersion;
    j["inputHash"] = lib.inputHash;
    j["bytes"] = lib.fileBytes;
    j["sections"] = lib.sections;
    j["scene"] = {{"name", lib.scene.name}, {"seed", lib.scene.seed}};
    j["clumps"] = nlohmann::json::array();
    for (const LibraryClump& c : lib.clumps) {
        nlohmann::json clump;
        clump["name"] = c.name;
        clump["plants"] = c.plants;
        // The five levels of detail (precompute/lod): LOD 0 the whole mesh, then ever fewer triangles,
        // each with the motion modes it plays and its error against LOD 0 at rest and over the motion.
        clump["lods"] = nlohmann::json::array();
        // Each LOD's triangle area in the mean pose: what a coarser LOD loses besides its silhouette.
        std::array<double, kLodCount> area{};
        for (uint32_t l = 0; l < kLodCount; ++l)
            for (size_t t = 0; t + 2 < c.lods[l].indices.size(); t += 3) {
                glm::dvec3 p[3];
                for (int k = 0; k < 3; ++k)
                    p[k] = glm::dvec3(c.mesh.vertices[c.lods[l].vertices[c.lods[l].indices[t + size_t(k)]]].positionU);
                area[l] += 0.5 * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
            }
        for (uint32_t l = 0; l < kLodCount; ++l) {
            const LodError& e = c.lods[l].error;
            clump["lods"].push_back({{"vertices", c.lods[l].vertices.size()},
                                     {"triangles", c.lods[l].indices.size() / 3},
                                     {"motionModes", c.motion.lodModes[l]},
                                     {"areaFraction", area[0] > 0.0 ? area[l] / area[0] : 0.0},
                                     {"maxModesPerVertex", c.motion.maxBlockRank(l)},
                                     // Per-vertex first-order transfer (mean and displacement gradient), no modes.
                                     {"appearanceModes", 0},
                                     {"error",
                                      {{"hausdorffRest", e.rest.hausdorff},
                                       {"rmsRest", e.rest.rms},
                                       {"hausdorffDeformed", e.deformed.hausdorff},
                                       {"rmsDeformed", e.deformed.rms},
                                       {"lightRms", e.light.rms},
                                       {"motionRms", e.motion.rms},
                                       {"motionPcaRelError", c.motion.relativeErrorPerMode[c.motion.lodModes[l]]}}}});
        }
        const MotionGraph& g = c.graph;
        uint32_t levelsConnected = 0;
        for (uint8_t connected : g.levelStronglyConnected)
            levelsConnected += connected ? 1 : 0;
        std::vector<uint32_t> levelLiveFrames(g.levelCount, 0);
        for (uint32_t i = 0; i < g.nodeCount; ++i)
            levelLiveFrames[g.nodeLevel[i]] += g.nodeAlive[i] ? 1 : 0;
        nlohmann::json levels = nlohmann::json::array();
        for (const LevelStats& s : c.levels)
            levels.push_back({{"meanSpeed", s.meanSpeed},
                              {"frames", s.frames},
                              {"maxPenetration", s.maxPenetration},
                              {"maxKineticEnergy", s.maxKineticEnergy},
                              {"kineticEnergyFirstHalf", s.kineticEnergyFirstHalf},
                              {"kineticEnergySecondHalf", s.kineticEnergySecondHalf},
                              {"maxAirDivergence", s.maxAirDivergence}});
        std::array<uint32_t, kLodCount> maxModesPerVertex{};
        for (uint32_t lod = 0; lod < kLodCount; ++lod)
            maxModesPerVertex[lod] = c.motion.maxBlockRank(lod);
        clump["motion"] = {{"frames", c.motion.frames},
                           {"windLevels", g.levelCount},
                           {"pcaRelError", c.motion.relativeErrorPerMode},
                           {"motionModesPerLod", c.motion.lodModes},
                           {"motionBlocks", c.motion.blocks.size()},
                           {"maxModesPerVertexPerLod", maxModesPerVertex},
                           {"graph",
                            {{"nodes", g.nodeCount - g.removedNodes},
                             {"edges", g.edgeCount},
                             {"transitions", g.transitionCount},
                             {"crossLevelTransitions", g.crossLevelTransitionCount},
                             {"removedNodes", g.removedNodes},
                             {"stronglyConnected", g.stronglyConnected},
                             {"levelsStronglyConnected", levelsConnected == g.levelCount},
                             {"levelLiveFrames", levelLiveFrames},
                             {"levelThresholdScale", g.levelThresholdScale},
                             {"levelLoopFrames", g.levelLoopFrames},
                             {"adaptations", graphAdaptations(g)}}},
                           {"levels", levels}};
        // The ≤ 1 s target: seconds from a step in the wind level to playing the new level's
        // frames, over 1000 walks with the run time's own step (library/motion_graph.h).
        const WindResponse wind = measureWindResponse(g);
        clump["motion"]["windResponse"] = {
            {"medianSeconds", {{"up", wind.upMedianSeconds}, {"down", wind.downMedianSeconds}}},
            {"p95Seconds", {{"up", wind.upP95Seconds}, {"down", wind.downP95Seconds}}},
            {"walks", wind.instances},
            {"unreached", wind.unreached}};
        const LibraryLight& light = c.light;
        clump["light"] = {{"shOrder", light.order},
                          {"bakedFrames", light.bakedFrames.size()},
                          {"model", "mean + displacement gradient"},
                          {"bakeNoise", light.vertexNoise},
                          {"heldOutIrradianceRelError", light.vertexHeldOutError},
                          {"meanOnlyIrradianceRelError", light.vertexMeanOnlyError},
                          {"irradianceNoise", light.vertexIrradianceNoise},
                          {"ground",
                           {{"resolution", light.groundResolution},
                            {"size", light.groundSize},
                            {"model", "mean over the baked frames"},
                            {"appearanceRelError", light.ground.relativeErrorPerMode},
                            {"bakeNoise", light.groundNoise},
                            {"heldOutIrradianceRelError", light.groundHeldOutError},
                            {"irradianceNoise", light.groundIrradianceNoise}}}};
        clump["far"] = farSamplesJson(c.far);
        j["clumps"].push_back(clump);
    }
    // Rocks carry far-field samples too; they are listed only for those.
    j["rocks"] = nlohmann::json::array();
    for (const LibraryRock& rock : lib.field.rocks)
        j["rocks"].push_back({{"name", rock.mesh.name}, {"far", farSamplesJson(rock.far)}});
    uint32_t plants = 0;
    for (const gpu::GpuInstance& inst : lib.field.clumpInstances)
        plants += lib.clumps[inst.mesh].plants;
    const PlacementStats& ps = lib.field.stats;
    // The tiles the field's tiling uses, and their figures; the complete set's under completeSet.
    // overlapViolations checks every tile of the set against every neighbour it may have.
    std::vector<uint32_t> clumpsUsed, rocksUsed;
    uint64_t voxelClumps = 0, discClumps = 0;
    for (uint32_t t : ps.fieldTiles) {
        clumpsUsed.push_back(ps.clumpsPerTile[t]);
        rocksUsed.push_back(ps.rocksPerTile[t]);
        voxelClumps += ps.clumpsPerTile[t];
        discClumps += ps.poissonClumpsPerTile[t];
    }
    j["tiles"] = {{"count", ps.fieldTiles.size()},
                  {"indices", ps.fieldTiles},
                  {"size", ps.tileSize},
                  {"clumpsPerTile", clumpsUsed},
                  {"rocksPerTile", rocksUsed},
                  {"densityVsPoissonDisc", discClumps ? double(voxelClumps) / double(discClumps) : 0.0},
                  {"overlapViolations", ps.overlapViolations},
                  {"overlapViolationsAllFrames", ps.overlapViolationsAllFrames},
                  {"sweptFootprintRadius", ps.sweptFootprintRadius},
                  {"sweptFrames", ps.sweptFrames},
                  {"simulatedFrames", ps.simulatedFrames},
                  {"completeSet",
                   {{"count", ps.tiles},
                    {"clumpsPerTile", ps.clumpsPerTile},
                    {"rocksPerTile", ps.rocksPerTile},
                    {"densityVsPoissonDisc", ps.densityVsPoissonDisc}}}};
    j["field"] = {
        {"tilesX", ps.tilesX},
        {"tilesY", ps.tilesY},
        {"clumps", lib.field.clumpInstances.size()},
        {"plants", plants},
        {"rocks", lib.field.rockInstances.size()},
        {"rockVariants", lib.field.rocks.size()},
        {"overlapsFound3d", ps.overlaps3dFound},
        {"clumpsRemoved3d", ps.clumpsRemoved3d},
        {"rocksRemoved3d", ps.rocksRemoved3d},
        {"overlapViolations3d", ps.overlapViolations3d},
        {"overlapViolations3dAllFrames", ps.overlapViolations3dAllFrames},
        {"tiling", ps.tiling},
        {"wangTiles", ps.fieldTiles.size()},
        {"terrain", {{"amplitude", lib.field.terrain.amplitude}, {"wavelength", lib.field.terrain.wavelength}}}};
    j["atlas"] = {{"width", lib.atlas.width}, {"height", lib.atlas.height}};
    j["sky"] = {{"frames", lib.sky.frames.size()},
                {"source", lib.skyFromMaps ? "panoramas" : "analytic"},
                {"shOrder", lib.sky.shOrder},
                {"imageWidth", lib.sky.imageWidth},
                {"imageHeight", lib.sky.imageHeight}};
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
}

} // namespace meadow
