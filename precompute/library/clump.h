// A clump as the library keeps it: what the engine draws and what `meadow inspect` reports. The
// precompute's stages build richer types (pipeline/clump_motion.h, clump_light.h, clump_lod.h);
// the pipeline turns them into these, and only these are written and read.
#pragma once

#include "library/far_samples.h"
#include "library/mesh.h"
#include "library/motion_basis.h"
#include "library/motion_graph.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace meadow {

// The simulation of one wind level, as recorded.
struct LevelStats {
    float meanSpeed = 0.0f;               // m/s of the level's wind
    uint32_t frames = 0;                  // recorded
    float maxPenetration = 0.0f;          // deepest contact interpenetration while recording (m)
    double maxKineticEnergy = 0.0;        // J
    double kineticEnergyFirstHalf = 0.0;  // mean J, first half of the recording
    double kineticEnergySecondHalf = 0.0; // mean J, second half: bounded means no growth
    double maxAirDivergence = 0.0;        // of the wind solver (1/s)
};

// Distances between two surfaces sampled both ways (points of each to the nearest point of the
// other), symmetric as in Metro (Cignoni et al. 1998): the larger of the two one-sided figures.
// hausdorff: the largest sampled value; rms: the area-weighted root mean square. Metres.
struct SurfaceDistance {
    double hausdorff = 0.0;
    double rms = 0.0;
};

// A LOD's error against the full mesh (lod/lod.h measures it).
struct LodError {
    SurfaceDistance rest;
    SurfaceDistance deformed; // Hausdorff: the largest over frames; RMS: over all frames
    // |full - LOD| of the light scalar, each surface's value interpolated at a sample point and at
    // its nearest point on the other surface (at rest). Units of the scalar; zero without one.
    SurfaceDistance light;
    // |displacement of the full surface - displacement of the LOD| at each sample and its nearest
    // point on the other surface at rest, over all frames. Metres; zero without frames.
    SurfaceDistance motion;
    uint32_t fullSamples = 0, lodSamples = 0;
};

// One level of detail: a subset of the original vertices (so motion rows and transfer are the
// originals'), with its error measured against the full mesh at rest and over simulated frames.
struct ClumpLod {
    std::vector<uint32_t> vertices; // original vertex indices, in vertex-fetch order
    std::vector<uint32_t> indices;  // triangles into `vertices`
    LodError error;                 // against LOD 0 (the full mesh)
};

// A vertex's light transfer to first order in its own displacement: T_v(f) ≈ T̄_v + G_v d_v(f)
// (light/vertex_appearance.h fits it).
struct VertexAppearance {
    uint32_t vertexCount = 0;
    uint32_t valuesPerVertex = 0; // transfer values of one vertex (sides x channels x order^2)
    // Per vertex, per value: (T̄, dT/dx, dT/dy, dT/dz), i.e. [vertex][value][4]; gradients per metre.
    std::vector<float> coefficients;

    const float* at(uint32_t vertex, uint32_t value) const {
        return &coefficients[(size_t(vertex) * valuesPerVertex + value) * 4];
    }
};

// The ground grid's transfer: its mean over the baked frames, which is what the run time plays.
// relativeErrorPerMode says what a low-rank model of its change over the motion would gain
// (light/appearance.h): [0] the mean's error, [k] with k modes. Over the iris clumps the first
// mode gains less than the bake's own noise, so no modes are kept (pipeline/clump_light.cpp).
struct GroundAppearance {
    std::vector<float> mean; // n values
    std::vector<uint32_t> bakedFrames;
    std::vector<double> relativeErrorPerMode;
};

// The light transfer of a clump and of the ground around it over its motion, in transfer/
// transfer.h's layouts, with the figures of the bake that made it (pipeline/clump_light.h).
struct LibraryLight {
    int order = 0;
    std::vector<uint32_t> bakedFrames;
    VertexAppearance vertices;
    GroundAppearance ground; // empty when groundResolution is 0
    uint32_t groundResolution = 0;
    float groundSize = 0.0f;
    double vertexNoise = 0.0, groundNoise = 0.0;
    double vertexHeldOutError = 0.0, vertexMeanOnlyError = 0.0, groundHeldOutError = 0.0;
    double vertexIrradianceNoise = 0.0, groundIrradianceNoise = 0.0;
};

// What the engine and `meadow inspect` need of one clump.
struct LibraryClump {
    std::string name;
    uint32_t plants = 0;
    Mesh mesh;                            // the mean pose, atlas UVs
    MotionBasis motion;                   // x̄ + U q per rod block; frames over all levels
    LibraryLight light;                   // transfer of the clump and its ground over the motion
    std::array<ClumpLod, kLodCount> lods; // LOD 0 is the full mesh, reordered for the vertex cache
    MotionGraph graph;
    std::vector<LevelStats> levels;
    FarSamples far; // surface samples for the far field, over LOD 0, playing the last LOD's vertices
};

// The LOD's mesh at a motion frame: the gathered vertices of meshAtFrame with the LOD's modes.
Mesh lodMeshAtFrame(const Mesh& meanPose, const MotionBasis& motion, const ClumpLod& lod, uint32_t lodIndex,
                    uint32_t frame);

} // namespace meadow
