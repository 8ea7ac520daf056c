#include "pipeline/clump_motion.h"

#include "core/error.h"
#include "sim/clump_sim.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <tbb/parallel_for.h>

namespace meadow {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The most modes PCA keeps per rod. A rod's motion lives in the span of its ~10 nodes' positions
// and frames; 1 % error of a clump takes ~10–20 modes for the busiest rods.
constexpr uint32_t kMaxModesPerRod = 48;

// How far a level's transition threshold is raised before the level is looped instead: beyond 8x
// the level's statistic (a low quantile of its distances) jumps stop resembling the motion.
constexpr float kMaxLevelThresholdScale = 8.0f;

} // namespace

std::array<float, kLodCount> lodErrorBounds(float lod0MaxError) {
    std::array<float, kLodCount> bounds = {lod0MaxError, 0.03f, 0.06f, 0.12f, 0.25f};
    for (uint32_t i = 1; i < kLodCount; ++i)
        bounds[i] = std::max(bounds[i], bounds[i - 1]);
    return bounds;
}

ClumpMotion buildClumpMotion(const PlantClump& clump, const Scene& scene, uint64_t seed) {
    ClumpMotion out;
    out.clump = clump;
    const uint32_t levels = uint32_t(scene.wind.levelSpeeds.size());

    ClumpSimSettings settings;
    settings.frameRate = scene.motion.frameRate;
    settings.substeps = scene.motion.substeps;
    settings.settleSeconds = scene.motion.settleSeconds;
    settings.recordSeconds = scene.motion.recordSeconds;
    settings.windDirection = scene.wind.direction;
    settings.gustPeriod = scene.wind.gustPeriod;

    // The levels are independent simulations: run them side by side.
    auto start = std::chrono::steady_clock::now();
    std::vector<LevelSimulation> runs(levels);
    tbb::parallel_for(uint32_t(0), levels, [&](uint32_t level) {
        WindLevelSpec wind{scene.wind.levelSpeeds[level], scene.wind.turbulence};
        runs[level] = simulateClumpLevel(clump, wind, level, settings, seed * 31 + level);
    });
    out.simulateSeconds = secondsSince(start);

    // Skin every recorded frame; stack the vertex positions as the columns of the PCA input.
    start = std::chrono::steady_clock::now();
    const size_t vertexCount = clump.mesh.positions.size();
    uint32_t totalFrames = 0;
    for (const LevelSimulation& run : runs) {
        out.clips.push_back({run.level, totalFrames, run.frames});
        totalFrames += run.frames;
    }
    Eigen::MatrixXf samples(Eigen::Index(vertexCount * 3), Eigen::Index(totalFrames));
    std::vector<glm::dvec3> normalSum(vertexCount, glm::dvec3(0.0));
    {
        RodSystem rods(clump.rods, settings.material);
        std::vector<glm::vec3> positions, normals;
        uint32_t column = 0;
        for (const LevelSimulation& run : runs) {
            for (uint32_t f = 0; f < run.frames; ++f, ++column) {
                rods.setPositions(&run.nodeFrames[size_t(f) * run.nodesPerFrame]);
                skinPlantMesh(clump.mesh, clump.rods, rods, positions, &normals);
                for (size_t v = 0; v < vertexCount; ++v) {
                    samples(Eigen::Index(3 * v + 0), column) = positions[v].x;
                    samples(Eigen::Index(3 * v + 1), column) = positions[v].y;
                    samples(Eigen::Index(3 * v + 2), column) = positions[v].z;
                    normalSum[v] += glm::dvec3(normals[v]);
                }
            }
        }
    }
    if (!samples.allFinite())
        throw Error("clump " + clump.name + ": skinning produced non-finite vertex positions");
    std::vector<uint32_t> vertexRod(vertexCount);
    for (size_t v = 0; v < vertexCount; ++v)
        vertexRod[v] = clump.mesh.skin[v].rod;
    out.pca = computeBlockPca(samples, vertexRod, uint32_t(clump.rods.size()), kMaxModesPerRod);
    if (out.pca.modeOrder.empty())
        throw Error("clump " + clump.name + ": the simulation recorded no motion to reduce");
    out.meanPositions.resize(vertexCount);
    out.meanNormals.resize(vertexCount);
    for (size_t v = 0; v < vertexCount; ++v) {
        out.meanPositions[v] = {out.pca.mean(Eigen::Index(3 * v)), out.pca.mean(Eigen::Index(3 * v + 1)),
                                out.pca.mean(Eigen::Index(3 * v + 2))};
        glm::dvec3 n = normalSum[v];
        out.meanNormals[v] = glm::length(n) > 1e-12 ? glm::vec3(glm::normalize(n)) : clump.mesh.normals[v];
    }
    std::array<float, kLodCount> bounds = lodErrorBounds(scene.motion.lod0MaxError);
    std::array<uint32_t, kLodCount> lodModes{};
    for (uint32_t lod = 0; lod < kLodCount; ++lod)
        lodModes[lod] = std::max<uint32_t>(1, modesForRelativeError(out.pca, bounds[lod]));
    out.basis = makeMotionBasis(out.pca, lodModes);
    // The bound is a target, not a guarantee: the library keeps at most kMaxModesPerRod per rod.
    // Say so; inspect reports the error per mode count.
    if (out.pca.relativeErrorPerMode[lodModes[0]] > bounds[0])
        std::fprintf(stderr,
                     "meadow: warning: clump %s: %u motion modes leave %.2f%% error, above the scene's "
                     "motion.lod0MaxError of %.2f%%\n",
                     clump.name.c_str(), lodModes[0], out.pca.relativeErrorPerMode[lodModes[0]] * 100.0,
                     double(bounds[0]) * 100.0);
    out.pcaSeconds = secondsSince(start);

    // The graph works on LOD0's reduced coordinates: the blocks are orthonormal, so distances
    // between coordinate vectors are distances between the reconstructed frames.
    start = std::chrono::steady_clock::now();
    MotionGraphParams graphParams;
    graphParams.frameRate = scene.motion.frameRate;
    const Eigen::MatrixXf q = Eigen::Map<const Eigen::MatrixXf>(
        out.basis.coords.data(), Eigen::Index(out.basis.modesPerFrame()), Eigen::Index(out.basis.frames));
    // A level whose motion offers too few transitions (short or slowly drifting clips, a stiff or
    // tiny plant in calm air) loses its frames to pruning. Adapt that level and build again: its
    // threshold doubled up to kMaxLevelThresholdScale, then its clips looped.
    graphParams.levelThresholdScale.assign(levels, 1.0f);
    graphParams.levelLooped.assign(levels, 0);
    for (;;) {
        try {
            out.graph = buildMotionGraph(q, out.clips, graphParams);
            break;
        } catch (const MotionGraphLevelError& e) {
            // A looped level that still fails lost its joins to a neighbour that is not looped:
            // loop the neighbours too (with every level looped the graph cannot fail).
            const uint32_t level = e.level;
            std::vector<uint8_t>& looped = graphParams.levelLooped;
            if (graphParams.levelThresholdScale[level] < kMaxLevelThresholdScale)
                graphParams.levelThresholdScale[level] *= 2.0f;
            else if (!looped[level])
                looped[level] = 1;
            else if (level > 0 && !looped[level - 1])
                looped[level - 1] = 1;
            else if (level + 1 < levels && !looped[level + 1])
                looped[level + 1] = 1;
            else
                throw Error("clump " + clump.name + ": " + e.what());
        } catch (const Error& e) {
            throw Error("clump " + clump.name + ": " + e.what());
        }
    }
    out.graphSeconds = secondsSince(start);

    for (const LevelSimulation& run : runs) {
        LevelStats s;
        s.meanSpeed = scene.wind.levelSpeeds[run.level];
        s.frames = run.frames;
        s.maxPenetration = run.maxPenetration;
        s.maxKineticEnergy = run.maxKineticEnergy;
        s.kineticEnergyFirstHalf = run.firstHalfKineticEnergy;
        s.kineticEnergySecondHalf = run.secondHalfKineticEnergy;
        s.maxAirDivergence = run.maxAirDivergence;
        out.levels.push_back(s);
    }
    return out;
}

Mesh clumpRenderMesh(const ClumpMotion& motion) {
    Mesh mesh;
    const PlantMesh& src = motion.clump.mesh;
    mesh.vertices.resize(src.positions.size());
    for (size_t v = 0; v < src.positions.size(); ++v) {
        mesh.vertices[v].positionU = glm::vec4(motion.meanPositions[v], src.uvs[v].x);
        mesh.vertices[v].normalV = glm::vec4(motion.meanNormals[v], src.uvs[v].y);
    }
    mesh.indices = src.indices;
    mesh.fitBoundingSphere();
    return mesh;
}

} // namespace meadow
