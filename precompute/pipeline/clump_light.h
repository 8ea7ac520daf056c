// The light transfer of one clump over its motion (docs/ARCHITECTURE.md, Light transfer): the
// clump's transfer and that of the ground around it are baked on a sample of the motion frames
// (transfer/transfer.h). The clump's vertices keep their mean transfer and its gradient in their
// own displacement (light/vertex_appearance.h); the ground grid, which does not move, its mean
// over the baked frames (a low-rank basis, light/appearance.h after James and Fatahalian 2003, is
// fitted only to report what its modes would gain). The renderer projects all of it onto the sky's
// SH once per sky change.
#pragma once

#include "library/mesh.h"
#include "light/appearance.h"
#include "light/vertex_appearance.h"
#include "pipeline/clump_motion.h"
#include "scene/scene.h"
#include "transfer/transfer.h"

#include <cstdint>
#include <vector>

namespace meadow {

struct ClumpLight {
    int order = 0;
    // Vertex transfer, 2 sides x 3 channels x order^2 values per vertex in transfer::VertexTransfer's
    // order; irradiance transfer without the vertex's own albedo (transfer.h).
    VertexAppearance vertices;
    std::vector<uint32_t> bakedFrames;
    // Ground grid transfer, n = points x 3 channels x order^2 (transfer::GroundTransfer's layout).
    AppearanceModel ground;
    uint32_t groundResolution = 0;
    float groundSize = 0.0f;
    // The Monte-Carlo noise of one bake, ||T_a - T_b|| / (sqrt 2 ||T||) for two bakes of one frame
    // with different ray seeds, over the transfer coefficients. The truncation never goes below it.
    double vertexNoise = 0.0, groundNoise = 0.0;
    // What the picture shows: irradiance E = T · L under a test sky (clear noon), per vertex, side
    // and channel. heldOut: ||E - Ê|| / ||E|| at frames that were baked but not used to build the
    // models (one between the first two baked frames of every clip), the error of the time
    // interpolation and the truncation together; it includes the held-out bake's own noise, whose
    // size is irradianceNoise (as vertexNoise, in irradiance).
    // vertexMeanOnlyError: the same with the mean transfer alone, what the gradient improves on.
    double vertexHeldOutError = 0.0, vertexMeanOnlyError = 0.0, groundHeldOutError = 0.0;
    double vertexIrradianceNoise = 0.0, groundIrradianceNoise = 0.0;
    double bakeSeconds = 0.0, reduceSeconds = 0.0;
};

// E = T · L for every group of order^2 coefficients of a transfer vector, `sky` the RGB radiance
// SH (sky::SkyFrame::sh layout); the groups cycle through the three channels (transfer.h's
// layouts, vertex and ground alike).
Eigen::VectorXd irradiance(const Eigen::VectorXf& transfer, const std::vector<float>& sky, int order);

// The linear albedo of each vertex: the atlas (8-bit sRGB) averaged over a 3 x 3 texel patch
// around the vertex's UV.
std::vector<glm::vec3> vertexAlbedo(const Mesh& mesh, const RgbaImage& atlas);

// Bakes and reduces. `meanPose` is the clump as drawn (clumpRenderMesh), `albedo` per vertex,
// `testSky` RGB radiance SH (sky::SkyFrame::sh layout, the bake's order) for the error figures.
// Deterministic for the same inputs.
ClumpLight buildClumpLight(const ClumpMotion& motion, const Mesh& meanPose, const std::vector<glm::vec3>& albedo,
                           const LightParams& params, const std::vector<float>& testSky);

// The light as the library keeps it: the models' values without Eigen, the bake's figures
// without its timings.
LibraryLight libraryLight(const ClumpLight& light);

} // namespace meadow
