#include "pipeline/clump_lod.h"

#include "core/error.h"

#include <algorithm>

namespace meadow {
namespace {

// Irradiance of each vertex's front side at its mean pose under the test sky, averaged over the
// channels: the light scalar the LOD error compares.
std::vector<float> frontIrradiance(const VertexAppearance& appearance, const std::vector<float>& sky, int order) {
    const std::vector<glm::vec3> atRest(appearance.vertexCount, glm::vec3(0.0f));
    // Per vertex: front R, G, B, then back R, G, B (transfer.h's layout).
    const Eigen::VectorXd e = irradiance(evaluateVertexAppearance(appearance, atRest), sky, order);
    std::vector<float> out(appearance.vertexCount);
    for (uint32_t v = 0; v < appearance.vertexCount; ++v)
        out[v] = float((e(6 * v) + e(6 * v + 1) + e(6 * v + 2)) / 3.0);
    return out;
}

} // namespace

SimplifyInput ClumpSimplifyData::input() const {
    SimplifyInput in;
    in.positions = positions;
    in.normals = normals;
    in.uvs = uvs;
    in.indices = indices;
    // Motion in metres (weight 1: a vertex that moves differently costs like one that is out of
    // place) and the mean light transfer in units of its own spread over the clump.
    in.attributes = {{"motion", motionRows.values, motionRows.width, 1.0f},
                     {"light", transfer.values, transfer.width, 0.01f}};
    in.collapseGroups = groups;
    return in;
}

ClumpSimplifyData clumpSimplifyData(const ClumpMotion& motion, const Mesh& meanPose) {
    ClumpSimplifyData data;
    const uint32_t vertexCount = uint32_t(meanPose.vertices.size());
    data.positions.resize(vertexCount);
    data.normals.resize(vertexCount);
    data.uvs.resize(vertexCount);
    for (uint32_t v = 0; v < vertexCount; ++v) {
        data.positions[v] = glm::vec3(meanPose.vertices[v].positionU);
        data.normals[v] = glm::vec3(meanPose.vertices[v].normalV);
        data.uvs[v] = glm::vec2(meanPose.vertices[v].positionU.w, meanPose.vertices[v].normalV.w);
    }
    data.indices = meanPose.indices;
    data.groups = rodGroups(motion.clump.mesh);
    data.motionRows = motionAttributes(motion.basis, 0);
    return data;
}

std::array<ClumpLod, kLodCount> buildClumpLods(const ClumpMotion& motion, const ClumpLight& light, const Mesh& meanPose,
                                               const std::vector<float>& testSky, const LodParams& params) {
    ClumpSimplifyData data = clumpSimplifyData(motion, meanPose);
    data.transfer = meanTransferAttributes(light.vertices);
    const SimplifyInput input = data.input();
    LodOptions options;
    options.triangleFractions = params.triangleFractions;
    const std::array<MeshLod, kLodCount> lods = buildLods(input, options);
    const std::vector<glm::vec3>& positions = data.positions;
    const uint32_t vertexCount = uint32_t(positions.size());

    // The error over frames of the strongest wind, where LODs differ most.
    const MotionClip& strongest = motion.clips.back();
    std::vector<std::vector<glm::vec3>> frames;
    for (uint32_t k = 0; k < 8; ++k) {
        const uint32_t frame = strongest.firstFrame + k * (strongest.frameCount - 1) / 7;
        std::vector<glm::vec3> p(vertexCount);
        for (uint32_t v = 0; v < vertexCount; ++v)
            p[v] = positions[v] + motion.basis.displacement(v, frame);
        frames.push_back(std::move(p));
    }
    const std::vector<float> lightScalar = frontIrradiance(light.vertices, testSky, light.order);
    LodErrorInput full;
    full.positions = positions;
    full.indices = meanPose.indices;
    full.lightScalar = lightScalar;
    full.frames = frames;
    const std::array<LodError, kLodCount> errors = measureLodErrors(full, lods);

    std::array<ClumpLod, kLodCount> out;
    for (uint32_t l = 0; l < kLodCount; ++l)
        out[l] = {lods[l].vertices, lods[l].indices, errors[l]};
    return out;
}

} // namespace meadow
