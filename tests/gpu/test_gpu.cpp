// Compute passes on a real Vulkan device (lavapipe in CI) against their CPU references, plus
// the core's upload/readback, timestamps and validation plumbing. ctest runs this binary at two
// lavapipe vector widths (LP_NATIVE_VECTOR_WIDTH=128 and 256).
#include "../motion/synthetic_motion.h"
#include "core/error.h"
#include "library/mesh.h"
#include "library/terrain.h"
#include "light/sh.h"
#include "motion/motion_graph.h"
#include "render/cpu_driver.h"
#include "render/cull_reference.h"
#include "render/draw_ranges.h"
#include "render/field_renderer.h"
#include "render/offscreen.h"
#include "sh_light.h"
#include "sky/sky_day.h"
#include "vk/barriers.h"
#include "vk/context.h"
#include "vk/memory.h"
#include "vk/pipeline.h"
#include "wind_field.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>
#include <random>

using namespace meadow;

namespace {

class Gpu : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        context = new Context;
        ContextOptions options;
        options.validation = true; // every GPU test runs validated; any message fails the suite
        createContext(*context, options);
    }
    static void TearDownTestSuite() {
        destroyContext(*context);
        delete context;
    }
    void TearDown() override {
        EXPECT_EQ(context->validation->total(), 0u) << "the validation layer reported messages (see stderr)";
    }
    static Context* context;
};
Context* Gpu::context = nullptr;

// Three small meshes (draw buckets) and a plain texture for them.
std::vector<Mesh> testMeshes() {
    return {makeTuftMesh(9), makeTuftMesh(5), makeTuftMesh(3)};
}
std::vector<FieldClump> staticClumps(const std::vector<Mesh>& meshes) {
    std::vector<FieldClump> clumps;
    for (const Mesh& mesh : meshes)
        clumps.push_back(staticFieldClump(mesh, 1));
    return clumps;
}

// A clump whose LODs are separate meshes: its vertices are all of theirs, each LOD its own range.
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

// One frame of the analytic sky, at 10 h.
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

// Instances scattered in a box around the origin, some huge, some tiny, spread over three
// meshes; deterministic.
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
        inst.tint = next();
        inst.mesh = uint32_t(next() * 3.0f) % 3;
        if (next() < 0.5f)
            inst.positionScale.w = -inst.positionScale.w; // mirrored: the same sphere
    }
    return out;
}

// A moving clump: the tuft with a synthetic motion library (four wind levels of damped,
// gust-driven coordinates, as a simulated clump's PCA coordinates behave), its real motion graph,
// and random basis rows in one block of `dims` modes (LODs play 6, 4, 2, 1, 1 of them).
FieldClump movingClump(uint32_t dims = 6) {
    FieldClump clump = staticFieldClump(makeTuftMesh(7), kLodCount);
    test::SyntheticMotion synthetic = test::makeSyntheticMotion(4, 2, 90, dims, 5);
    clump.graph = buildMotionGraph(synthetic.q, synthetic.clips, MotionGraphParams{});
    MotionBasis& m = clump.motion;
    m.frames = uint32_t(synthetic.q.cols());
    const uint32_t ranks[kLodCount] = {dims, 4, 2, 1, 1};
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

} // namespace

TEST_F(Gpu, UploadAndReadbackRoundTrip) {
    std::vector<uint32_t> data(100000);
    for (size_t i = 0; i < data.size(); ++i)
        data[i] = uint32_t(i * 2654435761u);
    Buffer buffer = createBuffer(*context, data.size() * 4,
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                 MemoryUse::Device);
    uploadToBuffer(*context, buffer, data.data(), data.size() * 4);
    std::vector<uint32_t> back(data.size());
    readbackBuffer(*context, buffer, back.data(), back.size() * 4);
    EXPECT_EQ(back, data);
    // A partial range at an offset.
    uint32_t patch[3] = {7, 8, 9};
    uploadToBuffer(*context, buffer, patch, sizeof(patch), 400);
    uint32_t readPatch[4] = {};
    readbackBuffer(*context, buffer, readPatch, sizeof(readPatch), 396);
    EXPECT_EQ(readPatch[0], data[99]);
    EXPECT_EQ(readPatch[1], 7u);
    EXPECT_EQ(readPatch[3], 9u);
    destroyBuffer(*context, buffer);
}

TEST_F(Gpu, SubAllocatorSharesBlocksAndReturnsMemory) {
    VkDeviceSize before = context->memory->bytesInUse();
    std::vector<Buffer> buffers;
    for (int i = 0; i < 64; ++i)
        buffers.push_back(
            createBuffer(*context, 4096 + 17 * VkDeviceSize(i), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::Device));
    // Sixty-four small buffers fit in one block.
    for (const Buffer& b : buffers)
        EXPECT_EQ(b.allocation.memory, buffers[0].allocation.memory);
    for (Buffer& b : buffers)
        destroyBuffer(*context, b);
    EXPECT_EQ(context->memory->bytesInUse(), before);
    // A buffer bigger than a block gets its own.
    Buffer big = createBuffer(*context, MemoryAllocator::kBlockSize + 4096, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              MemoryUse::Device);
    EXPECT_EQ(big.allocation.offset, 0u);
    destroyBuffer(*context, big);
}

TEST_F(Gpu, CullPassMatchesCpuReference) {
    std::vector<gpu::GpuInstance> instances = scatter(20011, 7); // not a multiple of the group size
    FieldRenderer renderer =
        createFieldRenderer(*context, staticClumps(testMeshes()), instances, testAtlas(), testScenery());
    Offscreen offscreen = createOffscreen(*context, {64, 48});

    struct View {
        glm::vec3 eye, target;
        float fov, farCull;
    };
    const View views[] = {{{0, 2, 0}, {10, 1, 30}, 50.0f, 250.0f},
                          {{-150, 30, -150}, {0, 0, 0}, 70.0f, 250.0f},
                          {{50, 5, 20}, {49, 4, 21}, 20.0f, 120.0f},
                          {{0, 300, 0}, {1, 0, 0}, 40.0f, 1000.0f}};
    for (const View& v : views) {
        Camera camera;
        camera.eye = v.eye;
        camera.target = v.target;
        camera.fovYDegrees = v.fov;
        camera.farCull = v.farCull;
        renderOffscreenFrame(*context, renderer, offscreen, frameState(camera, 64, 48));
        gpu::GpuFrame frame; // exactly what the GPU saw
        std::memcpy(&frame, renderer.frameUniforms.mapped(), sizeof(frame));

        std::vector<gpu::GpuDrawIndexedCommand> draws(renderer.meshCount);
        readbackBuffer(*context, renderer.drawCommands, draws.data(), draws.size() * sizeof(draws[0]));
        std::vector<uint32_t> list(renderer.instanceCount);
        readbackBuffer(*context, renderer.visibleList, list.data(), list.size() * 4);
        // Each mesh's visible instances lie in its own range and are of that mesh.
        std::vector<uint32_t> gpuVisible;
        uint32_t meshInstances = 0;
        for (uint32_t m = 0; m < renderer.meshCount; ++m) {
            EXPECT_EQ(draws[m].firstInstance, meshInstances);
            uint32_t ofMesh = uint32_t(std::count_if(instances.begin(), instances.end(),
                                                     [&](const gpu::GpuInstance& i) { return i.mesh == m; }));
            EXPECT_LE(draws[m].instanceCount, ofMesh);
            for (uint32_t k = 0; k < draws[m].instanceCount; ++k) {
                uint32_t index = list[draws[m].firstInstance + k];
                ASSERT_LT(index, instances.size());
                EXPECT_EQ(instances[index].mesh, m);
                gpuVisible.push_back(index);
            }
            meshInstances += ofMesh;
        }
        std::sort(gpuVisible.begin(), gpuVisible.end());
        FieldStats stats = readFieldStats(renderer);

        // Conservative cases: an instance whose sphere grazes a plane within this margin may
        // be classified either way by a different evaluation order of the same arithmetic.
        const float kGraze = 1e-4f;
        std::vector<uint32_t> expected = cullReference(frame, instances);
        std::vector<uint32_t> gpuStrict, refStrict;
        for (uint32_t i : gpuVisible)
            if (visibilityMargin(frame, instances[i]) > kGraze)
                gpuStrict.push_back(i);
        for (uint32_t i : expected)
            if (visibilityMargin(frame, instances[i]) > kGraze)
                refStrict.push_back(i);
        size_t grazing = std::count_if(instances.begin(), instances.end(), [&](const gpu::GpuInstance& inst) {
            return std::abs(visibilityMargin(frame, inst)) <= kGraze;
        });

        EXPECT_EQ(gpuStrict, refStrict) << "view at " << v.eye.x << "," << v.eye.y << "," << v.eye.z;
        EXPECT_LE(std::max(gpuVisible.size(), expected.size()) - std::min(gpuVisible.size(), expected.size()), grazing);
        if (grazing == 0) {
            EXPECT_EQ(gpuVisible, expected);
        }
        EXPECT_TRUE(std::adjacent_find(gpuVisible.begin(), gpuVisible.end()) == gpuVisible.end()) << "duplicates";
        EXPECT_EQ(draws[1].indexCount, testMeshes()[1].indices.size());
        EXPECT_EQ(stats.visibleInstances, gpuVisible.size());
        EXPECT_EQ(stats.visiblePerMesh.size(), renderer.meshCount);
        EXPECT_EQ(stats.testedInstances, renderer.instanceCount);
        EXPECT_GT(expected.size(), 0u);
        EXPECT_LT(expected.size(), instances.size());
    }
    destroyOffscreen(*context, offscreen);
    destroyFieldRenderer(*context, renderer);
}

// The cull pass with five LODs per clump: every visible instance's LOD coordinate agrees with the
// CPU reference (lod_select.h, shared), and the visible list holds exactly the entries that
// coordinate implies: one per instance on a plateau, two (the second marked) while crossfading.
TEST_F(Gpu, LodCullMatchesCpuReference) {
    std::vector<gpu::GpuInstance> instances = scatter(20011, 11);
    std::vector<FieldClump> clumps;
    for (uint32_t clump = 0; clump < 3; ++clump) {
        std::vector<Mesh> lods;
        for (uint32_t lod = 0; lod < kLodCount; ++lod)
            lods.push_back(makeTuftMesh(9 - 2 * lod, 5));
        clumps.push_back(clumpOfLods(lods));
    }
    FieldScenery scenery = testScenery();
    scenery.lodCount = kLodCount;
    scenery.lod = {{120.0f, 50.0f, 20.0f, 8.0f}, 0.1f, 0.2f, 0.05f, 0.0f};
    FieldRenderer renderer = createFieldRenderer(*context, clumps, instances, testAtlas(), scenery);
    Offscreen offscreen = createOffscreen(*context, {160, 120});
    const glm::vec3 eyes[] = {{0, 2, 0}, {-150, 30, -150}, {0, 2.2f, 0.4f}, {50, 5, 20}};
    std::vector<uint32_t> indices(renderer.indices.size / sizeof(uint32_t));
    readbackBuffer(*context, renderer.indices, indices.data(), renderer.indices.size);
    size_t crossfading = 0, lodsSeen = 0;
    for (const glm::vec3& eye : eyes) {
        Camera camera;
        camera.eye = eye;
        camera.target = glm::vec3(10, 1, 30);
        camera.farCull = 400.0f;
        std::vector<float> before(instances.size()), after(instances.size());
        readbackBuffer(*context, renderer.lodState, before.data(), before.size() * 4);
        renderOffscreenFrame(*context, renderer, offscreen, frameState(camera, 160, 120));
        gpu::GpuFrame frame; // exactly what the GPU saw, LOD fields included
        std::memcpy(&frame, renderer.frameUniforms.mapped(), sizeof(frame));
        readbackBuffer(*context, renderer.lodState, after.data(), after.size() * 4);
        std::vector<gpu::GpuDrawIndexedCommand> draws(renderer.meshCount);
        readbackBuffer(*context, renderer.drawCommands, draws.data(), draws.size() * sizeof(draws[0]));
        // Every draw the cull pass left reads inside the index, LOD vertex and visible buffers.
        std::vector<std::string> outside =
            checkDrawRanges(draws, {indices, renderer.lodVertexCount, renderer.visibleCount, renderer.drawCapacity});
        EXPECT_TRUE(outside.empty()) << outside.front();
        EXPECT_EQ(renderer.visibleList.size, std::max<VkDeviceSize>(renderer.visibleCount * 4, 16));
        std::vector<uint32_t> list(size_t(draws.back().firstInstance) + instances.size());
        readbackBuffer(*context, renderer.visibleList, list.data(), renderer.visibleList.size);

        // The entries each visible instance's GPU coordinate implies, bucket by bucket.
        std::vector<std::vector<uint32_t>> implied(renderer.meshCount), listed(renderer.meshCount);
        std::vector<float> cpuX = before;
        const std::vector<std::vector<uint32_t>> reference = cullReferenceBuckets(frame, instances, cpuX);
        size_t disagreeing = 0;
        std::vector<bool> lodUsed(kLodCount, false);
        for (uint32_t i : cullReference(frame, instances)) {
            const float x = after[i];
            disagreeing += std::abs(x - cpuX[i]) > 1e-4f;
            const uint32_t lod = uint32_t(std::floor(x)), first = instances[i].mesh * kLodCount;
            implied[first + lod].push_back(i);
            lodUsed[lod] = true;
            if (x != std::floor(x)) {
                implied[first + lod + 1].push_back(i | gpu::kLodFadeEntryBit);
                ++crossfading;
            }
        }
        for (uint32_t m = 0; m < renderer.meshCount; ++m) {
            listed[m].assign(list.begin() + draws[m].firstInstance,
                             list.begin() + draws[m].firstInstance + draws[m].instanceCount);
            std::sort(listed[m].begin(), listed[m].end());
            std::sort(implied[m].begin(), implied[m].end());
            EXPECT_EQ(listed[m], implied[m]) << "bucket " << m;
            // Tolerance for the CPU reference: entries of the few instances whose coordinate
            // differs in the last bits at a band edge or a hysteresis threshold.
            EXPECT_LE(std::max(listed[m].size(), reference[m].size()) - std::min(listed[m].size(), reference[m].size()),
                      2 * disagreeing)
                << "bucket " << m;
        }
        EXPECT_LE(disagreeing, 3u) << "instances whose LOD coordinate differs from the CPU reference";
        lodsSeen += size_t(std::count(lodUsed.begin(), lodUsed.end(), true));
    }
    EXPECT_GT(crossfading, 0u); // the views cross bands
    EXPECT_GE(lodsSeen, 8u);    // and use several LODs
    destroyOffscreen(*context, offscreen);
    destroyFieldRenderer(*context, renderer);
}

TEST_F(Gpu, TimestampsBracketEveryPass) {
    std::vector<gpu::GpuInstance> instances = scatter(1000, 3);
    FieldRenderer renderer =
        createFieldRenderer(*context, staticClumps(testMeshes()), instances, testAtlas(), testScenery());
    Offscreen offscreen = createOffscreen(*context, {32, 32});
    Camera camera;
    FrameTimings t = renderOffscreenFrame(*context, renderer, offscreen, frameState(camera, 32, 32));
    ASSERT_EQ(t.gpu.size(), 5u);
    EXPECT_EQ(t.gpu[0].label, "animate");
    EXPECT_EQ(t.gpu[1].label, "cull");
    EXPECT_EQ(t.gpu[2].label, "light");
    EXPECT_EQ(t.gpu[3].label, "draw");
    EXPECT_EQ(t.gpu[4].label, "tonemap");
    for (const PassTime& p : t.gpu) {
        EXPECT_GE(p.milliseconds, 0.0) << p.label;
        EXPECT_LT(p.milliseconds, 10000.0) << p.label;
    }
    destroyOffscreen(*context, offscreen);
    destroyFieldRenderer(*context, renderer);
}

// A mirrored instance (negative scale) must look exactly like the mesh reflected on the CPU about
// the vertical plane that holds the wind direction (placement/instance.h), then turned by the
// same yaw: the placement's voxel tests assume that transform.
TEST_F(Gpu, MirroredInstanceMatchesTheReflectedMesh) {
    const glm::vec2 wind = glm::normalize(glm::vec2(1.0f, 0.25f));
    const glm::vec3 n(-wind.y, 0.0f, wind.x); // the mirror plane's normal
    const Mesh tuft = makeTuftMesh(5);        // no mirror symmetry
    Mesh reflected = tuft;
    for (gpu::GpuVertex& v : reflected.vertices) {
        glm::vec3 p(v.positionU), q(v.normalV);
        p -= 2.0f * glm::dot(p, n) * n;
        q -= 2.0f * glm::dot(q, n) * n;
        v.positionU = glm::vec4(p, v.positionU.w);
        v.normalV = glm::vec4(q, v.normalV.w);
    }
    auto render = [&](const Mesh& mesh, float scale) {
        gpu::GpuInstance inst{};
        inst.positionScale = glm::vec4(0.3f, 0.0f, -0.2f, scale);
        inst.yaw = 0.7f;
        inst.boundingRadius = mesh.boundingRadius;
        inst.tint = 0.5f;
        FieldScenery scenery{makeTerrainMesh(TerrainParams{0.0f}, glm::vec2(4.0f), 1.0f, 1.0f), wind};
        scenery.sky = testSky();
        FieldRenderer renderer = createFieldRenderer(*context, staticClumps({mesh}),
                                                     std::vector<gpu::GpuInstance>{inst}, testAtlas(), scenery);
        Offscreen offscreen = createOffscreen(*context, {96, 96});
        Camera camera;
        camera.eye = glm::vec3(0.4f, 0.9f, -2.2f);
        camera.target = glm::vec3(0.3f, 0.35f, -0.2f);
        renderOffscreenFrame(*context, renderer, offscreen, frameState(camera, 96, 96));
        std::vector<uint8_t> pixels = readLdrPixels(*context, offscreen.targets);
        destroyOffscreen(*context, offscreen);
        destroyFieldRenderer(*context, renderer);
        return pixels;
    };
    const std::vector<uint8_t> mirrored = render(tuft, -1.0f), expected = render(reflected, 1.0f),
                               plain = render(tuft, 1.0f);
    ASSERT_EQ(mirrored.size(), expected.size());
    // The same triangles at the same places: allow only the odd rasterisation tie (reflected
    // vertices are computed in another order, so positions may differ in the last bit).
    size_t differing = 0, differingFromPlain = 0;
    for (size_t i = 0; i < mirrored.size(); ++i) {
        differing += std::abs(int(mirrored[i]) - int(expected[i])) > 8;
        differingFromPlain += std::abs(int(mirrored[i]) - int(plain[i])) > 8;
    }
    EXPECT_LE(differing, mirrored.size() / 500);
    EXPECT_GT(differingFromPlain, mirrored.size() / 100); // the mirror changes the picture
}

// animate.comp against the CPU reference: the same wind level at every instance and tick
// (wind_field.h) and the same motion-graph walk (motion_step.h), bit for bit, over frames that
// take one, several and (capped) many motion steps. Static clumps hold still.
TEST_F(Gpu, AnimatePassMatchesCpuReference) {
    std::vector<FieldClump> clumps = {movingClump(), staticFieldClump(makeTuftMesh(3), kLodCount), movingClump(4)};
    std::vector<gpu::GpuInstance> instances = scatter(3001, 17);
    for (gpu::GpuInstance& inst : instances)
        inst.mesh %= 3;
    FieldScenery scenery = testScenery();
    scenery.lodCount = kLodCount;
    scenery.lod = {{120.0f, 50.0f, 20.0f, 8.0f}, 0.1f, 0.2f, 0.05f, 0.0f};
    FieldRenderer renderer = createFieldRenderer(*context, clumps, instances, testAtlas(), scenery);
    Offscreen offscreen = createOffscreen(*context, {32, 24});

    std::vector<gpu::GpuMotionState> cpu(instances.size());
    readbackBuffer(*context, renderer.motionStates, cpu.data(), cpu.size() * sizeof(cpu[0]));
    std::vector<gpu::MotionTables> tables;
    for (const FieldClump& clump : clumps)
        tables.push_back(makeMotionTables(clump.graph));

    FrameState state = frameState(Camera{}, 32, 24);
    state.wind.baseLevel = 1.5f;
    state.wind.waveAmplitude = 1.5f;
    state.wind.wavelength = 60.0f;
    state.wind.gustAmplitude = 1.0f;
    const double times[] = {0.0, 0.04, 0.07, 0.2, 0.21, 0.5, 0.9, 0.95, 3.0, 3.1, 3.2, 3.4};
    std::vector<uint32_t> levelsSeen(4, 0);
    uint32_t stepsTaken = 0;
    for (double seconds : times) {
        state.seconds = seconds;
        renderOffscreenFrame(*context, renderer, offscreen, state);
        gpu::GpuFrame frame; // exactly what the GPU saw
        std::memcpy(&frame, renderer.frameUniforms.mapped(), sizeof(frame));
        stepsTaken += frame.motion.y;
        for (size_t i = 0; i < instances.size(); ++i) {
            const uint32_t c = instances[i].mesh;
            if (clumps[c].motion.frames == 0)
                continue;
            for (uint32_t s = 0; s < frame.motion.y; ++s) {
                const float level = gpu::windLevelAt(frame, instances[i].positionScale.x, instances[i].positionScale.z,
                                                     frame.motion.x + s);
                const uint32_t target = gpu::windTargetLevel(level, tables[c].levelCount);
                levelsSeen[target]++;
                gpu::motionStep(tables[c], cpu[i], target, uint32_t(i));
            }
        }
        std::vector<gpu::GpuMotionState> gpuStates(instances.size());
        readbackBuffer(*context, renderer.motionStates, gpuStates.data(), gpuStates.size() * sizeof(gpuStates[0]));
        size_t differing = 0;
        for (size_t i = 0; i < instances.size(); ++i) {
            if (clumps[instances[i].mesh].motion.frames == 0) // holds its one frame
                differing += gpuStates[i].frame != 0u || gpuStates[i].blendFramesLeft != 0u;
            else
                differing += std::memcmp(&gpuStates[i], &cpu[i], sizeof(cpu[i])) != 0;
        }
        ASSERT_EQ(differing, 0u) << "instances whose motion state differs after t = " << seconds << " s";
    }
    // The frames took 0, 1, several and the capped 8 steps; the wind spanned every level.
    EXPECT_GT(stepsTaken, 20u);
    for (uint32_t level = 0; level < 4; ++level)
        EXPECT_GT(levelsSeen[level], 0u) << "wind level " << level << " never targeted";
    destroyOffscreen(*context, offscreen);
    destroyFieldRenderer(*context, renderer);
}

// The vertex shader's x̄ + U q, blended across a graph jump, draws the same picture as the CPU's
// reconstruction of that blended pose drawn as a static mesh.
TEST_F(Gpu, VertexShaderPlaysTheMotion) {
    const FieldClump moving = movingClump();
    gpu::GpuInstance inst{};
    inst.positionScale = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    inst.boundingRadius = 1.0f;
    const uint32_t frameA = 40, frameB = 200, left = 2;
    const float w = float(left) / float(moving.graph.blendFrames);
    Camera camera;
    camera.eye = glm::vec3(0.0f, 0.5f, -1.4f);
    camera.target = glm::vec3(0.0f, 0.3f, 0.0f);
    auto render = [&](const FieldClump& clump, const gpu::GpuMotionState* state) {
        FieldRenderer renderer = createFieldRenderer(*context, std::vector<FieldClump>{clump},
                                                     std::vector<gpu::GpuInstance>{inst}, testAtlas(), testScenery());
        if (state)
            uploadToBuffer(*context, renderer.motionStates, state, sizeof(*state));
        Offscreen offscreen = createOffscreen(*context, {96, 96});
        renderOffscreenFrame(*context, renderer, offscreen, frameState(camera, 96, 96)); // first frame: no step
        std::vector<uint8_t> pixels = readLdrPixels(*context, offscreen.targets);
        destroyOffscreen(*context, offscreen);
        destroyFieldRenderer(*context, renderer);
        return pixels;
    };
    FieldClump single = moving;
    single.lods.resize(1);
    const gpu::GpuMotionState state{frameA, frameB, left, 0};
    // The blended pose on the CPU, as a static clump (unshadowed light: no gradient either way).
    Mesh posed = moving.mesh;
    for (uint32_t v = 0; v < posed.vertices.size(); ++v) {
        const glm::vec3 d =
            (1.0f - w) * moving.motion.displacement(v, frameA) + w * moving.motion.displacement(v, frameB);
        posed.vertices[v].positionU += glm::vec4(d, 0.0f);
    }
    const std::vector<uint8_t> gpuPose = render(single, &state);
    const std::vector<uint8_t> cpuPose = render(staticFieldClump(posed, 1), nullptr);
    const std::vector<uint8_t> rest = render(staticFieldClump(moving.mesh, 1), nullptr);
    size_t differing = 0, differingFromRest = 0;
    for (size_t i = 0; i < gpuPose.size(); ++i) {
        differing += std::abs(int(gpuPose[i]) - int(cpuPose[i])) > 8;
        differingFromRest += std::abs(int(gpuPose[i]) - int(rest[i])) > 8;
    }
    EXPECT_LE(differing, gpuPose.size() / 500);
    EXPECT_GT(differingFromRest, gpuPose.size() / 200); // the pose is not the mean
}

// light.comp against an independent CPU evaluation: a static clump's unshadowed transfer lit by
// the sky must give, for every yaw bin and mirror, the irradiance of the world sky on the
// vertex's normal as the instance turns it (clamped cosine in SH at R M n); a transfer with
// gradients gives T̄ and G dotted with the sky in the clump's frame (sh_light.h).
TEST_F(Gpu, LightPassMatchesCpuReference) {
    const glm::vec2 wind = glm::normalize(glm::vec2(1.0f, 0.25f));
    FieldClump plain = staticFieldClump(makeTuftMesh(5), 1);
    plain.yawLow = -0.3f;
    plain.yawHigh = 0.5f;
    plain.yawBins = 3;
    // A ground grid of open ground (the clamped cosine about +y) with one shaded point, a quarter
    // of the light, in the middle.
    plain.groundResolution = 3;
    plain.groundSize = 1.0f;
    {
        double up[9];
        sh::evaluate(3, glm::dvec3(0.0, 1.0, 0.0), up);
        const double lobe[9] = {M_PI,     2 * M_PI / 3, 2 * M_PI / 3, 2 * M_PI / 3, M_PI / 4,
                                M_PI / 4, M_PI / 4,     M_PI / 4,     M_PI / 4};
        for (uint32_t point = 0; point < 9; ++point)
            for (uint32_t c = 0; c < 3; ++c)
                for (uint32_t i = 0; i < 9; ++i)
                    plain.groundTransfer.push_back(float(lobe[i] * up[i] * (point == 4 ? 0.25 : 1.0)));
    }
    FieldClump graded = plain;
    uint64_t seed = 5;
    for (size_t i = 0; i < graded.mesh.vertices.size() * 216; ++i) {
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        graded.transfer.push_back(float(seed >> 40) / float(1 << 24) - 0.3f);
    }
    FieldScenery scenery = testScenery();
    scenery.windDirection = wind;
    gpu::GpuInstance inst{};
    inst.positionScale = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    inst.boundingRadius = 1.0f;
    FieldRenderer renderer = createFieldRenderer(*context, std::vector<FieldClump>{plain, graded},
                                                 std::vector<gpu::GpuInstance>{inst}, testAtlas(), scenery);
    Offscreen offscreen = createOffscreen(*context, {16, 16});
    renderOffscreenFrame(*context, renderer, offscreen, frameState(Camera{}, 16, 16));
    std::vector<glm::vec4> light(renderer.vertexLight.size / sizeof(glm::vec4));
    readbackBuffer(*context, renderer.vertexLight, light.data(), renderer.vertexLight.size);
    std::vector<glm::uvec4> words(light.size());
    std::memcpy(words.data(), light.data(), words.size() * sizeof(glm::uvec4));
    // (E, gradient) of side-and-channel sc at a vertex's first uvec4: half floats, two per word.
    auto lit = [&](size_t first, uint32_t sc) {
        const glm::uvec4 w = words[first + sc / 2];
        const uint32_t a = sc % 2 == 0 ? w.x : w.z, b = sc % 2 == 0 ? w.y : w.w;
        return glm::vec4(glm::unpackHalf2x16(a), glm::unpackHalf2x16(b));
    };

    const std::vector<float>& sky = scenery.sky.frames[0].sh;
    std::vector<glm::dvec3> skyRgb(9);
    for (int i = 0; i < 9; ++i)
        skyRgb[i] = glm::dvec3(sky[3 * i], sky[3 * i + 1], sky[3 * i + 2]);
    const double band[9] = {M_PI,     2 * M_PI / 3, 2 * M_PI / 3, 2 * M_PI / 3, M_PI / 4,
                            M_PI / 4, M_PI / 4,     M_PI / 4,     M_PI / 4};
    const glm::dvec3 mirrorNormal(-wind.y, 0.0, wind.x);
    const uint32_t variants = 2 * plain.yawBins, vertices = uint32_t(plain.mesh.vertices.size());
    double worst = 0.0, scale = 0.0;
    for (uint32_t v = 0; v < vertices; ++v)
        for (uint32_t variant = 0; variant < variants; ++variant) {
            const bool mirrored = variant >= plain.yawBins;
            const double yaw =
                plain.yawLow + (variant % plain.yawBins + 0.5) * (plain.yawHigh - plain.yawLow) / plain.yawBins;
            glm::dvec3 n = glm::normalize(glm::dvec3(plain.mesh.vertices[v].normalV));
            if (mirrored)
                n -= 2.0 * glm::dot(n, mirrorNormal) * mirrorNormal;
            const glm::dvec3 turned(std::cos(yaw) * n.x + std::sin(yaw) * n.z, n.y,
                                    -std::sin(yaw) * n.x + std::cos(yaw) * n.z);
            for (uint32_t side = 0; side < 2; ++side) {
                double y[9];
                sh::evaluate(3, side == 0 ? turned : -turned, y);
                glm::dvec3 e(0.0);
                for (int i = 0; i < 9; ++i)
                    e += band[i] * y[i] * skyRgb[i];
                for (uint32_t c = 0; c < 3; ++c) {
                    const glm::vec4 g = lit((size_t(v) * variants + variant) * gpu::kLightVec4sPerVertex, side * 3 + c);
                    worst = std::max(worst, std::abs(double(g.x) - e[c]));
                    scale = std::max(scale, std::abs(e[c]));
                    EXPECT_EQ(g.y, 0.0f);
                }
            }
        }
    EXPECT_GT(scale, 0.01);
    EXPECT_LT(worst, 1e-3 * scale) << "irradiance of the unshadowed clump (half floats)";
    // Its ground: open ground passes all the light, the shaded point a quarter, in every variant.
    const size_t groundBase = size_t(vertices) * variants * gpu::kLightVec4sPerVertex;
    for (uint32_t variant = 0; variant < variants; ++variant)
        for (uint32_t point = 0; point < 9; ++point) {
            const glm::vec4 ratio = light[groundBase + variant * 9 + point];
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(ratio[c], point == 4 ? 0.25f : 1.0f, 1e-4f) << "variant " << variant << " point " << point;
        }

    // The graded clump: T̄ and the gradient, per side and channel, against sh_light.h on the CPU.
    const size_t base = groundBase + variants * 9;
    worst = 0.0;
    scale = 0.0;
    for (uint32_t v = 0; v < vertices; ++v)
        for (uint32_t variant = 0; variant < variants; ++variant) {
            const bool mirrored = variant >= plain.yawBins;
            const float yaw = plain.yawLow + (float(variant % plain.yawBins) + 0.5f) * (plain.yawHigh - plain.yawLow) /
                                                 float(plain.yawBins);
            float in[27], local[27];
            std::copy(sky.begin(), sky.end(), in);
            gpu::shSkyToClumpFrame(in, gpu::shClumpFrameSign(mirrored),
                                   gpu::shClumpFrameDelta(yaw, mirrored, std::atan2(wind.x, wind.y)), local);
            for (uint32_t sc = 0; sc < 6; ++sc) {
                glm::dvec4 expected(0.0);
                for (uint32_t i = 0; i < 9; ++i)
                    for (uint32_t k = 0; k < 4; ++k)
                        expected[k] +=
                            double(graded.transfer[(size_t(v) * 54 + sc * 9 + i) * 4 + k]) * local[3 * i + sc % 3];
                const glm::vec4 g = lit(base + (size_t(v) * variants + variant) * gpu::kLightVec4sPerVertex, sc);
                for (int k = 0; k < 4; ++k) {
                    worst = std::max(worst, std::abs(double(g[k]) - expected[k]));
                    scale = std::max(scale, std::abs(expected[k]));
                }
            }
        }
    EXPECT_GT(scale, 0.01);
    EXPECT_LT(worst, 1e-3 * scale) << "transfer with gradients (half floats)";
    destroyOffscreen(*context, offscreen);
    destroyFieldRenderer(*context, renderer);
}

// The per-frame CPU contract (DESIGN.md 3 and 5): what the CPU writes for a frame (the uniform
// block and the push constants it records) does not grow with the field and stays within 1 KiB,
// with the sky moving (the light pass runs) or not.
TEST_F(Gpu, UploadPerFrameIsSmallAndIndependentOfFieldSize) {
    std::vector<FieldClump> clumps = {movingClump(), staticFieldClump(makeTuftMesh(3), kLodCount)};
    FieldScenery scenery = testScenery();
    scenery.lodCount = kLodCount;
    scenery.lod = {{120.0f, 50.0f, 20.0f, 8.0f}, 0.1f, 0.2f, 0.05f, 0.0f};
    std::vector<uint64_t> bytes[2];
    const uint32_t counts[2] = {50, 40000};
    for (int f = 0; f < 2; ++f) {
        std::vector<gpu::GpuInstance> instances = scatter(counts[f], 23);
        for (gpu::GpuInstance& inst : instances)
            inst.mesh %= 2;
        FieldRenderer renderer = createFieldRenderer(*context, clumps, instances, testAtlas(), scenery);
        Offscreen offscreen = createOffscreen(*context, {32, 24});
        FrameState state = frameState(Camera{}, 32, 24);
        for (int frame = 0; frame < 4; ++frame) {
            state.seconds = frame / 30.0;
            state.hours = frame < 2 ? 10.0 : 10.0 + frame * 0.1; // still, then moving
            renderOffscreenFrame(*context, renderer, offscreen, state);
            bytes[f].push_back(renderer.uploadBytesLastFrame);
        }
        destroyOffscreen(*context, offscreen);
        destroyFieldRenderer(*context, renderer);
    }
    EXPECT_EQ(bytes[0], bytes[1]);
    for (uint64_t b : bytes[1]) {
        EXPECT_GE(b, sizeof(gpu::GpuFrame));
        EXPECT_LE(b, 1024u);
    }
    EXPECT_LT(bytes[1][1], bytes[1][0]); // no light pass while the sky holds still
}

// The CPU-driven comparison path steps, culls and uploads on the host what the compute passes
// produce on the GPU: the same motion states, and the same picture.
TEST_F(Gpu, CpuDrivenPathDrawsTheSamePicture) {
    std::vector<FieldClump> clumps = {movingClump(), staticFieldClump(makeTuftMesh(3), kLodCount)};
    std::vector<gpu::GpuInstance> instances = scatter(4000, 29);
    for (gpu::GpuInstance& inst : instances) {
        inst.mesh %= 2;
        inst.positionScale = glm::vec4(glm::vec3(inst.positionScale) * 0.1f, inst.positionScale.w > 0 ? 1.0f : -1.0f);
        inst.positionScale.y = 0.0f;
        inst.boundingRadius = 1.0f;
    }
    FieldScenery scenery = testScenery();
    scenery.lodCount = kLodCount;
    scenery.lod = {{60.0f, 25.0f, 10.0f, 4.0f}, 0.1f, 0.2f, 0.05f, 0.0f};
    Camera camera;
    camera.eye = glm::vec3(0.0f, 3.0f, -25.0f);
    camera.target = glm::vec3(0.0f, 0.0f, 0.0f);
    std::vector<uint8_t> pictures[2];
    std::vector<gpu::GpuMotionState> states[2];
    uint64_t uploads[2] = {0, 0};
    for (int path = 0; path < 2; ++path) {
        FieldRenderer renderer = createFieldRenderer(*context, clumps, instances, testAtlas(), scenery);
        if (path == 1)
            enableCpuDriver(*context, renderer, clumps, instances);
        Offscreen offscreen = createOffscreen(*context, {160, 90});
        FrameState state = frameState(camera, 160, 90);
        state.wind.baseLevel = 2.0f;
        for (int frame = 0; frame < 8; ++frame) {
            state.seconds = frame * 0.1;
            state.camera.eye.x = float(frame) * 0.5f;
            renderOffscreenFrame(*context, renderer, offscreen, state);
        }
        pictures[path] = readLdrPixels(*context, offscreen.targets);
        states[path].resize(instances.size());
        if (path == 0)
            readbackBuffer(*context, renderer.motionStates, states[path].data(),
                           states[path].size() * sizeof(gpu::GpuMotionState));
        else
            states[path] = cpuDriverStates(*renderer.cpuDriver);
        uploads[path] = renderer.uploadBytesLastFrame;
        EXPECT_GT(readFieldStats(renderer).visibleInstances, 100u);
        destroyOffscreen(*context, offscreen);
        destroyFieldRenderer(*context, renderer);
    }
    ASSERT_EQ(states[0].size(), states[1].size());
    EXPECT_EQ(std::memcmp(states[0].data(), states[1].data(), states[0].size() * sizeof(gpu::GpuMotionState)), 0);
    size_t differing = 0;
    for (size_t i = 0; i < pictures[0].size(); ++i)
        differing += std::abs(int(pictures[0][i]) - int(pictures[1][i])) > 8;
    EXPECT_LE(differing, pictures[0].size() / 1000);
    // The CPU path uploads a draw record per visible instance every frame: far more than the GPU
    // path's uniforms.
    EXPECT_GT(uploads[1], uploads[0] + 100 * sizeof(gpu::GpuDrawInstance));
}

// The validation plumbing itself: a real hazard must be reported, or the validation tests
// could never fail. Uses its own context so the suite's counter stays clean.
TEST(GpuValidation, SynchronizationHazardIsReported) {
    Context ctx;
    ContextOptions options;
    options.validation = true;
    createContext(ctx, options);
    Buffer buffer = createBuffer(ctx, 1024, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Device);
    testing::internal::CaptureStderr();
    submitAndWait(ctx, [&](VkCommandBuffer cmd) {
        // Two writes to the same range with no barrier between them: a write-after-write hazard.
        vkCmdFillBuffer(cmd, buffer.buffer, 0, 1024, 1);
        vkCmdFillBuffer(cmd, buffer.buffer, 0, 1024, 2);
    });
    std::string messages = testing::internal::GetCapturedStderr();
    EXPECT_GE(ctx.validation->errors.load(), 1u);
    EXPECT_NE(messages.find("SYNC-HAZARD-WRITE-AFTER-WRITE"), std::string::npos) << messages;
    destroyBuffer(ctx, buffer);
    destroyContext(ctx);
}

TEST(GpuContext, UnknownDeviceOverrideIsNamed) {
    Context ctx;
    ContextOptions options;
    options.deviceOverride = "no-such-gpu-model";
    try {
        createContext(ctx, options);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        std::string m = e.what();
        EXPECT_NE(m.find("no-such-gpu-model"), std::string::npos) << m;
        EXPECT_NE(m.find("devices:"), std::string::npos) << m;
    }
    destroyContext(ctx);
}
