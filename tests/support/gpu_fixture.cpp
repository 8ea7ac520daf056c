#include "gpu_fixture.h"

#include "library/terrain.h"
#include "motion/motion_graph.h"
#include "sky/sky_day.h"
#include "synthetic_motion.h"

#include <algorithm>

namespace meadow::test {

Context* Gpu::context = nullptr;

void Gpu::SetUpTestSuite() {
    context = new Context;
    ContextOptions options;
    options.validation = true; // every GPU test runs validated; any message fails the suite
    createContext(*context, options);
}
void Gpu::TearDownTestSuite() {
    destroyContext(*context);
    delete context;
}
void Gpu::TearDown() {
    EXPECT_EQ(context->validation->total(), 0u) << "the validation layer reported messages (see stderr)";
}

std::vector<Mesh> testMeshes() {
    return {makeTuftMesh(9), makeTuftMesh(5), makeTuftMesh(3)};
}
std::vector<FieldClump> staticClumps(const std::vector<Mesh>& meshes) {
    std::vector<FieldClump> clumps;
    for (const Mesh& mesh : meshes)
        clumps.push_back(staticFieldClump(mesh, 1));
    return clumps;
}

FieldClump clumpOfLods(const std::vector<Mesh>& lods) {
    FieldClump clump = staticFieldClump(lods[0], 1);
    clump.mesh.vertices.clear();
    clump.lods.clear();
    for (const Mesh& mesh : lods) {
        FieldLod lod;
        for (size_t v = 0; v < mesh.vertices.size(); ++v)
            lod.vertices.push_back(uint32_t(clump.mesh.vertices.size() + v));
        lod.indices = mesh.indices;
        clump.mesh.vertices.insert(clump.mesh.vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
        clump.lods.push_back(std::move(lod));
    }
    return clump;
}

sky::SkyDay testSky() {
    sky::SkyParams params = sky::skyParamsForPreset("ci");
    sky::SkyDay day;
    day.shOrder = params.shOrder;
    day.imageWidth = params.imageWidth;
    day.imageHeight = params.imageHeight;
    day.frames.push_back(sky::buildSkyFrame(params, 10.0));
    return day;
}

FrameState frameState(const Camera& camera, uint32_t width, uint32_t height) {
    FrameState state;
    state.camera = camera;
    state.width = width;
    state.height = height;
    state.hours = 10.0;
    return state;
}
RgbaImage testAtlas() {
    return {4, 4, std::vector<uint8_t>(64, 200)};
}

FieldScenery testScenery() {
    FieldScenery scenery{makeTerrainMesh(TerrainParams{0.0f}, glm::vec2(20.0f), 5.0f, 2.0f), glm::vec2(1.0f, 0.0f)};
    scenery.sky = testSky();
    return scenery;
}

std::vector<gpu::GpuInstance> scatter(uint32_t count, uint32_t seed) {
    std::vector<gpu::GpuInstance> out(count);
    uint64_t s = seed;
    auto next = [&] {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        return float(s >> 40) / float(1 << 24);
    };
    for (gpu::GpuInstance& inst : out) {
        inst.positionScale =
            glm::vec4(next() * 400.0f - 200.0f, next() * 40.0f - 10.0f, next() * 400.0f - 200.0f, 0.2f + next() * 3.0f);
        inst.boundingRadius = 0.2f + next() * 2.0f;
        inst.yaw = next() * 6.28f;
        next(); // a value once drawn for a tint: skipped, so that the instances stay the same
        inst.mesh = uint32_t(next() * 3.0f) % 3;
        if (next() < 0.5f)
            inst.positionScale.w = -inst.positionScale.w; // mirrored: the same sphere
    }
    return out;
}

FieldClump movingClump(uint32_t dims, uint32_t lastLodRank) {
    FieldClump clump = staticFieldClump(makeTuftMesh(7), kLodCount);
    test::SyntheticMotion synthetic = test::makeSyntheticMotion(4, 2, 90, dims, 5);
    clump.graph = buildMotionGraph(synthetic.q, synthetic.clips, MotionGraphParams{});
    MotionBasis& m = clump.motion;
    m.frames = uint32_t(synthetic.q.cols());
    const uint32_t ranks[kLodCount] = {dims, std::max(4u, lastLodRank), std::max(2u, lastLodRank),
                                       std::max(1u, lastLodRank), lastLodRank};
    for (uint32_t l = 0; l < kLodCount; ++l)
        m.lodModes[l] = std::min(ranks[l], dims);
    m.blocks.push_back(MotionBlock{0, {m.lodModes[0], m.lodModes[1], m.lodModes[2], m.lodModes[3], m.lodModes[4]}});
    m.vertexBlock.assign(clump.mesh.vertices.size(), 0);
    uint64_t seed = 99;
    for (size_t i = 0; i < clump.mesh.vertices.size() * dims * 3; ++i) {
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        m.basis.push_back((float(seed >> 40) / float(1 << 24) - 0.5f) * 0.1f); // metres per unit of q
    }
    for (Eigen::Index f = 0; f < synthetic.q.cols(); ++f)
        for (uint32_t k = 0; k < dims; ++k)
            m.coords.push_back(synthetic.q(k, f));
    m.relativeErrorPerMode.assign(dims + 1, 0.0);
    m.finish("test clump");
    return clump;
}

} // namespace meadow::test
