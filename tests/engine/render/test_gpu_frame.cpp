// A whole frame on a real device: timestamps around every pass, what the CPU uploads per frame,
// the CPU-driven comparison path against the GPU-driven one, with and without the far field, and
// the far field's splat pass against its CPU reference.
// ctest runs these at two lavapipe vector widths (LP_NATIVE_VECTOR_WIDTH=128 and 256).
#include "gpu_fixture.h"
#include "library/mesh.h"
#include "near_raster.h"
#include "pipeline/far_samples.h"
#include "render/cpu_driver.h"
#include "render/far_reference.h"
#include "render/field_packing.h"
#include "render/field_renderer.h"
#include "render/near_reference.h"
#include "render/offscreen.h"
#include "render/render_targets.h"
#include "sh_light.h"
#include "sky/sky_day.h"
#include "vk/context.h"
#include "vk/memory.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>
#include <numeric>
#include <random>
#include <string>

using namespace meadow;
using namespace meadow::test;

TEST_F(Gpu, TimestampsBracketEveryPass) {
    std::vector<gpu::GpuInstance> instances = scatter(1000, 3);
    FieldRenderer renderer =
        createFieldRenderer(*context, staticClumps(testMeshes()), instances, testAtlas(), testScenery());
    Offscreen offscreen = createOffscreen(*context, {32, 32});
    Camera camera;
    FrameTimings t = renderOffscreenFrame(*context, renderer, offscreen, frameState(camera, 32, 32));
    ASSERT_EQ(t.gpu.size(), 7u);
    EXPECT_EQ(t.gpu[0].label, "animate");
    EXPECT_EQ(t.gpu[1].label, "cull");
    EXPECT_EQ(t.gpu[2].label, "light");
    EXPECT_EQ(t.gpu[3].label, "groundMap");
    EXPECT_EQ(t.gpu[4].label, "sky");
    EXPECT_EQ(t.gpu[5].label, "draw");
    EXPECT_EQ(t.gpu[6].label, "tonemap");
    for (const PassTime& p : t.gpu) {
        EXPECT_GE(p.milliseconds, 0.0) << p.label;
        EXPECT_LT(p.milliseconds, 10000.0) << p.label;
    }
    destroyOffscreen(*context, offscreen);
    destroyFieldRenderer(*context, renderer);
}

// The per-frame CPU contract: what the CPU writes for a frame does not grow with the field and
// stays within 1 KiB, with the sky moving (the light pass runs) or not. The bytes are counted
// where they are written (Context::hostBytesWritten: every mapped write, upload and push
// constant goes through vk/memory.h and vk/pipeline.h), so a per-instance upload added anywhere
// makes the two field sizes differ; CpuDrivenPathDrawsTheSamePicture shows the count sees one.
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
            const uint64_t before = context->hostBytesWritten;
            renderOffscreenFrame(*context, renderer, offscreen, state);
            bytes[f].push_back(context->hostBytesWritten - before);
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

namespace {

// The clump's far-field samples, as the precompute builds them (pipeline/far_samples.h): over its
// LOD 0, each following a vertex of its last LOD, with their measured coverage gains.
void giveFarSamples(FieldClump& clump) {
    FarSurface surface;
    for (const gpu::GpuVertex& v : clump.mesh.vertices) {
        surface.positions.push_back(glm::vec3(v.positionU));
        surface.normals.push_back(glm::vec3(v.normalV));
        surface.uvs.emplace_back(v.positionU.w, v.normalV.w);
    }
    for (uint32_t i : clump.lods[0].indices)
        surface.indices.push_back(clump.lods[0].vertices[i]);
    surface.farVertices = clump.lods.back().vertices;
    const FarSamples far = buildFarSamples(surface, 512, 5);
    clump.far = far.samples;
    clump.farArea = far.area;
    clump.farGain = farCoverageGains(surface, far);
}

// The field both driving paths draw: a moving and a static clump, each with far-field samples,
// 4,000 instances within 20 m, five LODs and, with farRadius > 0, the far field; the camera 25 m
// away.
struct ComparisonField {
    std::vector<FieldClump> clumps;
    std::vector<gpu::GpuInstance> instances;
    FieldScenery scenery;
    Camera camera;
};

ComparisonField comparisonField(float farRadius, uint32_t lastLodRank = 1) {
    ComparisonField f;
    f.clumps = {movingClump(6, lastLodRank), staticFieldClump(makeTuftMesh(3), kLodCount)};
    for (FieldClump& clump : f.clumps)
        giveFarSamples(clump);
    f.instances = scatter(4000, 29);
    for (gpu::GpuInstance& inst : f.instances) {
        inst.mesh %= 2;
        inst.positionScale = glm::vec4(glm::vec3(inst.positionScale) * 0.1f, inst.positionScale.w > 0 ? 1.0f : -1.0f);
        inst.positionScale.y = 0.0f;
        inst.boundingRadius = 1.0f;
    }
    f.scenery = testScenery();
    f.scenery.lodCount = kLodCount;
    f.scenery.lod = {{60.0f, 25.0f, 10.0f, 4.0f}, 0.1f, 0.2f, 0.05f, farRadius};
    f.camera.eye = glm::vec3(0.0f, 3.0f, -25.0f);
    f.camera.target = glm::vec3(0.0f, 0.0f, 0.0f);
    return f;
}

// What one driving path drew of the field after `frames` frames, 0.1 s apart, the camera sliding.
struct PathRun {
    std::vector<uint8_t> picture;
    std::vector<uint8_t> hdr; // the HDR image's bytes, whatever the targets say it holds
    FieldStats stats;
    std::vector<gpu::GpuMotionState> states;
    uint64_t lastFrameUpload = 0;        // host bytes written for the last frame
    std::array<uint32_t, 2> nearTaken{}; // the near raster's counters of draws taken (near_raster.h)
    uint32_t nearListed = 0;             // and the length of its list, in the last frame
    std::vector<uint64_t> visibility;    // the visibility buffer's words (depth key, radiance), with the near raster
};

PathRun drawOnPath(Context& context, const ComparisonField& field, bool cpuDriven, int frames,
                   HdrContents hdr = HdrContents::Frame) {
    FieldRenderer renderer = createFieldRenderer(context, field.clumps, field.instances, testAtlas(), field.scenery);
    if (cpuDriven)
        enableCpuDriver(context, renderer, field.clumps, field.instances);
    Offscreen offscreen = createOffscreen(context, {160, 90}, hdr);
    FrameState state = frameState(field.camera, 160, 90);
    state.wind.baseLevel = 2.0f;
    PathRun run;
    for (int frame = 0; frame < frames; ++frame) {
        state.seconds = frame * 0.1;
        state.camera.eye.x = float(frame) * 0.5f;
        const uint64_t before = context.hostBytesWritten;
        renderOffscreenFrame(context, renderer, offscreen, state);
        run.lastFrameUpload = context.hostBytesWritten - before;
    }
    run.picture = readLdrPixels(context, offscreen.targets);
    run.hdr = readImageBytes(context, offscreen.targets.hdr, VK_IMAGE_ASPECT_COLOR_BIT, 8, VK_IMAGE_LAYOUT_GENERAL,
                             access::kComputeReadWrite);
    run.stats = readFieldStats(renderer);
    if (renderer.nearRasterOn) {
        readbackBuffer(context, renderer.nearTaken, run.nearTaken.data(), sizeof(run.nearTaken));
        gpu::GpuNearDispatch dispatch{};
        readbackBuffer(context, renderer.nearDispatch, &dispatch, sizeof dispatch);
        run.nearListed = dispatch.count;
        run.visibility = readFarVisibility(context, offscreen.targets);
    }
    run.states.resize(field.instances.size());
    if (cpuDriven)
        run.states = cpuDriverStates(*renderer.cpuDriver);
    else
        readbackBuffer(context, renderer.motionStates, run.states.data(),
                       run.states.size() * sizeof(gpu::GpuMotionState));
    destroyOffscreen(context, offscreen);
    destroyFieldRenderer(context, renderer);
    return run;
}

// Channels of two pictures that differ by more than 8 of 255.
size_t differingChannels(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    size_t differing = 0;
    for (size_t i = 0; i < a.size(); ++i)
        differing += std::abs(int(a[i]) - int(b[i])) > 8;
    return differing;
}

} // namespace

// The CPU-driven comparison path steps, culls and uploads on the host what the compute passes
// produce on the GPU: the same motion states, and the same picture.
TEST_F(Gpu, CpuDrivenPathDrawsTheSamePicture) {
    const ComparisonField field = comparisonField(0.0f);
    const PathRun gpuPath = drawOnPath(*context, field, false, 8), cpuPath = drawOnPath(*context, field, true, 8);
    EXPECT_GT(gpuPath.stats.visibleInstances, 100u);
    EXPECT_GT(cpuPath.stats.visibleInstances, 100u);
    ASSERT_EQ(gpuPath.states.size(), cpuPath.states.size());
    EXPECT_EQ(
        std::memcmp(gpuPath.states.data(), cpuPath.states.data(), gpuPath.states.size() * sizeof(gpu::GpuMotionState)),
        0);
    EXPECT_LE(differingChannels(gpuPath.picture, cpuPath.picture), gpuPath.picture.size() / 1000);
    // The CPU path uploads a draw record per visible instance every frame: far more than the GPU
    // path's uniforms.
    EXPECT_GT(cpuPath.lastFrameUpload, gpuPath.lastFrameUpload + 100 * sizeof(gpu::GpuDrawInstance));
}

// With the far field on, the CPU-driven path writes the far list and its dispatch that the cull
// pass would, and the same splat pass draws them: the same picture, the same far instances.
TEST_F(Gpu, CpuDrivenPathDrawsTheSameFarField) {
    const ComparisonField field = comparisonField(3.0f);
    const PathRun gpuPath = drawOnPath(*context, field, false, 4), cpuPath = drawOnPath(*context, field, true, 4);
    EXPECT_GT(gpuPath.stats.farInstances, 200u);
    EXPECT_EQ(cpuPath.stats.farInstances, gpuPath.stats.farInstances);
    EXPECT_EQ(cpuPath.stats.farSamples, gpuPath.stats.farSamples);
    EXPECT_LE(differingChannels(gpuPath.picture, cpuPath.picture), gpuPath.picture.size() / 1000);
}

// The splat pass's threads per far instance (gpu_types.h: 2 on a CPU, more on a GPU) only share
// the samples out differently: the nearest sample of each pixel wins whatever the order, so every
// width draws the same picture, byte for byte, on both driving paths. Widths outside the powers
// of two up to kFarMaxLanes are refused.
TEST_F(Gpu, TheSplatPassDrawsTheSamePictureWithAnyThreadsPerInstance) {
    ComparisonField field = comparisonField(6.0f);
    field.scenery.farLanes = 2;
    const PathRun two = drawOnPath(*context, field, false, 3);
    EXPECT_GT(two.stats.farInstances, 200u);
    for (uint32_t lanes : {1u, 8u, gpu::kFarMaxLanes}) {
        field.scenery.farLanes = lanes;
        for (bool cpuDriven : {false, true}) {
            const PathRun other = drawOnPath(*context, field, cpuDriven, 3);
            EXPECT_EQ(other.stats.farSamples, two.stats.farSamples) << lanes << " lanes";
            EXPECT_TRUE(other.picture == two.picture) << lanes << " lanes, cpuDriven " << cpuDriven;
        }
    }
    for (uint32_t lanes : {3u, 2 * gpu::kFarMaxLanes}) {
        field.scenery.farLanes = lanes;
        EXPECT_THROW(drawOnPath(*context, field, false, 1), Error) << lanes << " lanes";
    }
}

// The LDR image is the HDR image tone mapped (tonemap.h: the exposure, ACES, then the sRGB curve,
// which the shader takes from a fit by square roots): the exact curve on the CPU, from the HDR
// image's half floats and the frame's exposure, gives every channel within one 8-bit step of it,
// and nearly every one exactly (the fit lies within 0.012 of a step of the curve). A wrong
// coefficient, toe or exposure breaks it.
TEST_F(Gpu, TheLdrImageIsTheHdrImageToneMapped) {
    const ComparisonField field = comparisonField(6.0f);
    FieldRenderer renderer = createFieldRenderer(*context, field.clumps, field.instances, testAtlas(), field.scenery);
    Offscreen offscreen = createOffscreen(*context, {160, 90}, HdrContents::Frame);
    const FrameState state = frameState(field.camera, 160, 90);
    renderOffscreenFrame(*context, renderer, offscreen, state);
    const double exposure = frameUniforms(renderer, state).skyZenith.w;
    const std::vector<uint8_t> ldr = readLdrPixels(*context, offscreen.targets);
    const std::vector<uint16_t> hdr = readHdrPixels(*context, offscreen.targets);
    destroyOffscreen(*context, offscreen);
    destroyFieldRenderer(*context, renderer);
    ASSERT_EQ(ldr.size(), hdr.size());
    auto srgb = [](double c) { return c > 0.0031308 ? 1.055 * std::pow(c, 1.0 / 2.4) - 0.055 : 12.92 * c; };
    auto aces = [](double x) { return std::clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); };
    size_t exact = 0, channels = 0;
    int worst = 0;
    std::vector<bool> seen(256, false);
    for (size_t i = 0; i < ldr.size(); ++i) {
        if (i % 4 == 3)
            continue; // alpha
        const double x = double(glm::unpackHalf1x16(hdr[i])) * exposure;
        const int expected = int(std::lround(255.0 * srgb(aces(x))));
        const int difference = std::abs(int(ldr[i]) - expected);
        worst = std::max(worst, difference);
        exact += difference == 0;
        ++channels;
        seen[ldr[i]] = true;
    }
    EXPECT_LE(worst, 1);
    EXPECT_GT(double(exact), 0.97 * double(channels));
    EXPECT_GT(std::count(seen.begin(), seen.end(), true), 100) << "the frame spans the curve";
}

// Targets made for the LDR image alone (the bench's and the window's, HdrContents::MeshPass) resolve
// the far field without storing it into the HDR image: the same picture, byte for byte, and an HDR
// image without the far field's pixels, which readHdrPixels refuses to hand out.
TEST_F(Gpu, TargetsForTheLdrImageAloneDrawTheSamePicture) {
    const ComparisonField field = comparisonField(6.0f);
    const PathRun frame = drawOnPath(*context, field, false, 3, HdrContents::Frame);
    const PathRun ldrOnly = drawOnPath(*context, field, false, 3, HdrContents::MeshPass);
    EXPECT_GT(frame.stats.farInstances, 200u);
    EXPECT_TRUE(ldrOnly.picture == frame.picture);
    ASSERT_EQ(ldrOnly.hdr.size(), frame.hdr.size());
    size_t differing = 0;
    for (size_t i = 0; i < frame.hdr.size(); i += 8)
        differing += std::memcmp(&frame.hdr[i], &ldrOnly.hdr[i], 8) != 0;
    EXPECT_GT(differing, 1000u) << "pixels of the far field only the whole frame's HDR image holds";

    Offscreen offscreen = createOffscreen(*context, {8, 8}, HdrContents::MeshPass);
    EXPECT_THROW(readHdrPixels(*context, offscreen.targets), Error);
    destroyOffscreen(*context, offscreen);
}

// A far radius above LOD 4's switch (4 px, band 0.1: the far field's band, 4.5 to 5.5 px, does not
// lie below LOD 4's, 3.6 to 4.4 px): LOD 3 hands over to the far field, LOD 4 is never drawn, on
// either driving path, and both draw the same picture.
TEST_F(Gpu, AFarRadiusAboveLod4sSwitchSkipsLod4OnBothPaths) {
    const ComparisonField field = comparisonField(5.0f);
    const PathRun gpuPath = drawOnPath(*context, field, false, 4), cpuPath = drawOnPath(*context, field, true, 4);
    EXPECT_GT(gpuPath.stats.farInstances, 200u);
    EXPECT_EQ(cpuPath.stats.farInstances, gpuPath.stats.farInstances);
    EXPECT_EQ(cpuPath.stats.farSamples, gpuPath.stats.farSamples);
    for (const PathRun* run : {&gpuPath, &cpuPath}) {
        ASSERT_EQ(run->stats.visiblePerMesh.size(), field.clumps.size() * kLodCount);
        uint32_t lod3 = 0;
        for (size_t clump = 0; clump < field.clumps.size(); ++clump) {
            EXPECT_EQ(run->stats.visiblePerMesh[clump * kLodCount + 4], 0u) << "clump " << clump;
            lod3 += run->stats.visiblePerMesh[clump * kLodCount + 3];
        }
        EXPECT_GT(lod3, 0u);
    }
    EXPECT_LE(differingChannels(gpuPath.picture, cpuPath.picture), gpuPath.picture.size() / 1000);
}

namespace {

template <typename T> std::vector<T> readAll(Context& context, const Buffer& buffer, size_t count) {
    std::vector<T> values(count);
    readbackBuffer(context, buffer, values.data(), count * sizeof(T));
    return values;
}

// Two visibility buffers (far_splat.h's words) pixel by pixel: covered by either, by one only, both
// covered with words more than 1 % apart in colour or 1e-5 in depth, and equal bit for bit.
struct WordComparison {
    size_t covered = 0, oneSided = 0, differing = 0, identical = 0;
};

WordComparison compareWords(const std::vector<uint64_t>& gpuWords, const std::vector<uint64_t>& cpuWords) {
    const uint64_t empty = (uint64_t(gpu::kFarEmpty) << 32) | gpu::kFarEmpty;
    WordComparison c;
    for (size_t i = 0; i < gpuWords.size() && i < cpuWords.size(); ++i) {
        const bool onGpu = gpuWords[i] != empty, onCpu = cpuWords[i] != empty;
        c.covered += onGpu || onCpu;
        if (onGpu != onCpu) {
            ++c.oneSided;
            continue;
        }
        if (!onGpu)
            continue;
        c.identical += gpuWords[i] == cpuWords[i];
        const gpu::FarVec3 a = gpu::unpackRgb9e5(uint32_t(gpuWords[i])), b = gpu::unpackRgb9e5(uint32_t(cpuWords[i]));
        const float largest = std::max({a.x, a.y, a.z, b.x, b.y, b.z, 1e-6f});
        const float colour = std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.z - b.z)}) / largest;
        const float depthA = gpu::farKeyDepth(uint32_t(gpuWords[i] >> 32));
        const float depthB = gpu::farKeyDepth(uint32_t(cpuWords[i] >> 32));
        c.differing += colour > 0.01f || std::abs(depthA - depthB) > 1e-5f * std::max(depthA, depthB);
    }
    return c;
}

} // namespace

// The splat pass against its CPU reference (render/far_reference.h), from the very inputs the GPU
// read in the frame: the far list the cull pass wrote, the draw records, the light the light pass
// projected and the depth the mesh pass left. Pixels may differ where a sample lies within
// rounding of a pixel edge, a coverage threshold or another sample's depth (the shader may fuse a
// multiply-add the C++ rounds twice): at most 1 % of the covered pixels. Everywhere else the
// words agree: the same nearest sample, with the same depth and colour.
static void splatPassMatchesCpuReference(Context& ctx, uint32_t lastLodRank) {
    Context* context = &ctx;
    // 320x180, the far field below 6 px: most of the field.
    ComparisonField field = comparisonField(6.0f, lastLodRank);
    FieldRenderer renderer = createFieldRenderer(*context, field.clumps, field.instances, testAtlas(), field.scenery);
    const VkExtent2D extent{320, 180};
    Offscreen offscreen = createOffscreen(*context, extent);
    FrameState state = frameState(field.camera, extent.width, extent.height);
    state.wind.baseLevel = 2.0f;
    for (int frame = 0; frame < 3; ++frame) {
        state.seconds = frame * 0.1;
        renderOffscreenFrame(*context, renderer, offscreen, state);
    }

    FarSplatInputs in;
    std::memcpy(&in.frame, renderer.frameUniforms.mapped(), sizeof(in.frame));
    in.mirrorNormal = renderer.mirrorNormal;
    const gpu::GpuFarDispatch dispatch = readAll<gpu::GpuFarDispatch>(*context, renderer.farDispatch, 1)[0];
    in.farList = readAll<glm::uvec2>(*context, renderer.farList, dispatch.count);
    in.drawInstances = readAll<gpu::GpuDrawInstance>(*context, renderer.drawInstances, field.instances.size());
    in.clumps = readAll<gpu::GpuClump>(*context, renderer.clumps, field.clumps.size());
    in.farSamples =
        readAll<gpu::GpuFarSample>(*context, renderer.farSamples, renderer.farSamples.size / sizeof(gpu::GpuFarSample));
    in.farMotion =
        readAll<gpu::GpuFarMotion>(*context, renderer.farMotion, renderer.farMotion.size / sizeof(gpu::GpuFarMotion));
    in.motionData = readAll<float>(*context, renderer.motionData, renderer.motionData.size / sizeof(float));
    in.vertexLight = readAll<glm::uvec4>(*context, renderer.vertexLight, renderer.vertexLight.size / 16);
    const std::vector<float> meshDepth = readFarDepth(*context, offscreen.targets);
    const std::vector<uint64_t> gpuWords = readFarVisibility(*context, offscreen.targets);
    const std::vector<uint64_t> cpuWords = farSplatReference(in);
    const std::vector<uint16_t> hdr = readHdrPixels(*context, offscreen.targets);
    destroyOffscreen(*context, offscreen);
    destroyFieldRenderer(*context, renderer);

    EXPECT_GT(dispatch.count, 200u);
    ASSERT_EQ(gpuWords.size(), cpuWords.size());
    const WordComparison words = compareWords(gpuWords, cpuWords);
    const size_t covered = words.covered, oneSided = words.oneSided, differing = words.differing,
                 identical = words.identical;
    const uint64_t empty = (uint64_t(gpu::kFarEmpty) << 32) | gpu::kFarEmpty;
    std::printf("far instances %u, covered %zu, one-sided %zu, differing %zu, identical %zu\n", dispatch.count, covered,
                oneSided, differing, identical);
    // The far field fills a good part of the frame: the comparison is not of two empty buffers.
    EXPECT_GT(covered, 1000u);
    EXPECT_LE(oneSided, covered / 100) << "pixels only one of GPU and CPU covered, of " << covered;
    EXPECT_LE(differing, covered / 100) << "pixels whose nearest sample differs, of " << covered;
    EXPECT_GT(identical, covered / 2) << "pixels with the same word, bit for bit, of " << covered;

    // The resolve pass: every pixel whose winning sample lies nearer than the meshes holds that
    // sample's radiance in the HDR image (to half-float precision); where the meshes are as near
    // or nearer, the HDR image keeps the mesh pass's colour, which is almost never the sample's.
    size_t resolved = 0, wrong = 0, hidden = 0, hiddenButWritten = 0;
    const int width = int(extent.width), height = int(extent.height);
    const auto depthAt = [&](int x, int y) {
        return meshDepth[size_t(std::clamp(y, 0, height - 1)) * size_t(width) + size_t(std::clamp(x, 0, width - 1))];
    };
    for (size_t i = 0; i < gpuWords.size(); ++i) {
        if (gpuWords[i] == empty)
            continue;
        const int x = int(i % size_t(width)), y = int(i / size_t(width));
        const gpu::FarVec3 radiance = gpu::unpackRgb9e5(uint32_t(gpuWords[i]));
        const float want[3] = {radiance.x, radiance.y, radiance.z};
        bool same = true;
        for (int c = 0; c < 3; ++c) {
            const float got = glm::unpackHalf1x16(hdr[i * 4 + size_t(c)]);
            same = same && std::abs(got - want[c]) <= 1e-3f * std::max(want[c], 1e-3f);
        }
        if (gpu::farWordShows(uint32_t(gpuWords[i] >> 32),
                              gpu::farMeshDepthLimit(depthAt(x, y), depthAt(x - 1, y), depthAt(x + 1, y),
                                                     depthAt(x, y - 1), depthAt(x, y + 1)))) {
            ++resolved;
            wrong += !same;
        } else {
            ++hidden;
            hiddenButWritten += same;
        }
    }
    std::printf("resolved %zu, hidden behind the meshes %zu\n", resolved, hidden);
    EXPECT_GT(resolved, 1000u);
    EXPECT_EQ(wrong, 0u) << "of " << resolved << " pixels the far field won";
    EXPECT_GT(hidden, 100u) << "samples behind the meshes: the resolve's depth test is exercised";
    EXPECT_LE(hiddenButWritten, hidden / 20) << "of " << hidden << " pixels whose sample lies behind the meshes";
}

// The far field plays at most kFarMotionModes modes of a sample's block, its strongest (the last
// LOD's first): a sample's motion texel holds all its rows, and the far coordinates of a frame hold
// those modes' coordinates alone. (No device: packField on the CPU, here beside the splat pass's
// tests for the moving clump they share.) A clump whose last LOD plays 3 modes in its one block, and one
// whose last LOD plays 1.
TEST(FieldPacking, FarSamplesPlayAtMostTwoModesOfTheirBlock) {
    for (uint32_t lastLodRank : {3u, 1u}) {
        FieldClump clump = movingClump(6, lastLodRank);
        ASSERT_EQ(clump.motion.blocks.size(), 1u);
        ASSERT_EQ(clump.motion.blocks[0].ranks[kLodCount - 1], lastLodRank);
        const std::vector<uint32_t>& farVertices = clump.lods.back().vertices;
        for (uint32_t k = 0; k < 8; ++k) {
            FarSample s;
            s.vertex = s.lightVertex = farVertices[(k * 7) % farVertices.size()];
            clump.far.push_back(s);
        }
        clump.farArea = 1.0f;
        const FieldPacking packed =
            packField(std::span<const FieldClump>(&clump, 1), std::span<const gpu::GpuInstance>(), kLodCount);
        const uint32_t played = std::min(lastLodRank, gpu::kFarMotionModes);
        const gpu::GpuClump& g = packed.clumps.at(0);
        ASSERT_EQ(g.graphSizes.w, played) << "far coordinates per frame";
        const size_t modesPerFrame = clump.motion.modesPerFrame();
        for (uint32_t f = 0; f < clump.motion.frames; ++f)
            for (uint32_t k = 0; k < played; ++k)
                ASSERT_EQ(packed.motionData.at(g.motion.x + f * played + k), clump.motion.coords[f * modesPerFrame + k])
                    << "frame " << f << " mode " << k;
        for (uint32_t i = 0; i < clump.far.size(); ++i) {
            const gpu::GpuFarSample& sample = packed.farSamples.at(g.far.x + i);
            const gpu::GpuLodVertex& vertex = packed.lodVertices.at(sample.data.w);
            ASSERT_EQ(vertex.motion.w & 0xffffu, lastLodRank) << "the LOD vertex keeps the last LOD's rank";
            const gpu::GpuFarMotion& motion = packed.farMotion.at(sample.data.w);
            EXPECT_EQ(motion.rows.w >> gpu::kFarMotionRankShift, played) << "sample " << i;
            EXPECT_EQ(motion.rows.w & gpu::kFarMotionOffsetMask, 0u) << "the block's first far coordinate";
            const glm::vec2 halves[3] = {glm::unpackHalf2x16(motion.rows.x), glm::unpackHalf2x16(motion.rows.y),
                                         glm::unpackHalf2x16(motion.rows.z)};
            for (uint32_t k = 0; k < 2; ++k)
                for (uint32_t c = 0; c < 3; ++c) {
                    const uint32_t h = 3 * k + c;
                    const float got = halves[h / 2][int(h % 2)];
                    const float want = k < played ? packed.motionData.at(4 * size_t(vertex.motion.x + k) + c) : 0.0f;
                    EXPECT_NEAR(got, want, std::abs(want) * 1e-3f + 7e-5f) << "sample " << i << " row " << k;
                }
        }
    }
}

// The moving clump's last LOD (which its far samples follow) playing one mode, as the test field's.
TEST_F(Gpu, SplatPassMatchesCpuReference) {
    splatPassMatchesCpuReference(*context, 1);
}

// ...and three, of which the far field plays the first two, both in the sample's motion texel
// (GpuFarMotion; FieldPacking.FarSamplesPlayAtMostTwoModesOfTheirBlock).
TEST_F(Gpu, SplatPassMatchesCpuReferenceWithThreeModesAtTheLastLod) {
    splatPassMatchesCpuReference(*context, 3);
}

// The sky blend pass against its CPU reference: every texel of the backdrop is the two sky frames
// around the hour blended by the hour's weight, to half-float precision, after a frame that
// blended it and after one that kept it. Two frames whose backdrops differ, at hours between them.
TEST_F(Gpu, SkyBlendMatchesCpuReference) {
    const sky::SkyParams params = sky::skyParamsForPreset("ci");
    FieldScenery scenery = testScenery();
    scenery.sky.frames = {sky::buildSkyFrame(params, 9.0), sky::buildSkyFrame(params, 11.0)};
    FieldRenderer renderer =
        createFieldRenderer(*context, staticClumps(testMeshes()), scatter(100, 3), testAtlas(), scenery);
    Offscreen offscreen = createOffscreen(*context, {32, 32});
    FrameState state = frameState(Camera{}, 32, 32);
    // The same hour twice (the image is kept, not blended again), then a later one (blended again).
    double previous = -1.0;
    for (double hours : {10.3, 10.3, 10.6}) {
        state.hours = hours;
        renderOffscreenFrame(*context, renderer, offscreen, state);
        EXPECT_EQ(renderer.skyBlendThisFrame, hours != previous) << hours;
        previous = hours;
        const std::vector<glm::vec3> gpuSky = readSkyImage(*context, renderer);

        const sky::SkyBlend blend = sky::skyBlendAt(scenery.sky, hours);
        ASSERT_EQ(blend.first, 0u);
        ASSERT_EQ(blend.second, 1u);
        ASSERT_GT(blend.weight, 0.2) << hours; // well inside the blend
        ASSERT_LT(blend.weight, 0.95) << hours;
        const std::vector<float>& a = scenery.sky.frames[0].image;
        const std::vector<float>& b = scenery.sky.frames[1].image;
        ASSERT_EQ(gpuSky.size(), size_t(params.imageWidth) * params.imageHeight);
        const float w = float(blend.weight);
        size_t apart = 0; // texels where the two frames differ by more than 5 %: the blend is exercised
        for (size_t i = 0; i < gpuSky.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                const float first = a[3 * i + size_t(c)], second = b[3 * i + size_t(c)];
                const float want = first * (1.0f - w) + second * w;
                ASSERT_NEAR(gpuSky[i][c], want, 1e-3f * std::abs(want) + 1e-6f)
                    << "hour " << hours << ", texel " << i << ", channel " << c;
                apart += std::abs(first - second) > 0.05f * std::max(std::abs(first), std::abs(second));
            }
        EXPECT_GT(apart, gpuSky.size() / 4);
    }
    destroyOffscreen(*context, offscreen);
    destroyFieldRenderer(*context, renderer);
}

// The sky backdrop shows the sun's disk where a pixel's view ray lies within the sun's angular
// radius of its direction (sky.frag, with the radius's cosine from sky.vert). Looking straight at
// the sun through a picture of odd size, the middle pixel's ray is the sun's direction: it takes
// the sun's radiance on top of the sky's (as much of it as a half float holds). Its neighbour's ray
// is about 0.85 degrees off, over three times the radius (0.27 degrees), and sees the sky alone; so
// does a pixel three to the side.
TEST_F(Gpu, TheSkyShowsTheSunsDiskWithinItsAngularRadius) {
    const FieldScenery scenery = testScenery();
    const sky::SkyFrame& sun = scenery.sky.frames[0]; // the test sky's one frame: every hour shows it
    ASSERT_GT(sun.sunDirection.y, 0.1f);
    std::vector<gpu::GpuInstance> instances = scatter(1, 3);
    instances[0].positionScale = glm::vec4(0.0f, 0.0f, 0.0f, 0.2f) - glm::vec4(sun.sunDirection * 50.0f, 0.0f);
    FieldRenderer renderer = createFieldRenderer(*context, staticClumps(testMeshes()), instances, testAtlas(), scenery);
    const uint32_t size = 65;
    Offscreen offscreen = createOffscreen(*context, {size, size});
    Camera camera;
    camera.eye = glm::vec3(0.0f, 2.0f, 0.0f);
    camera.target = camera.eye + sun.sunDirection * 10.0f;
    renderOffscreenFrame(*context, renderer, offscreen, frameState(camera, size, size));
    const std::vector<uint8_t> hdr = readImageBytes(*context, offscreen.targets.hdr, VK_IMAGE_ASPECT_COLOR_BIT, 8,
                                                    VK_IMAGE_LAYOUT_GENERAL, access::kComputeReadWrite);
    const auto radiance = [&](uint32_t x, uint32_t y) {
        uint16_t h[4];
        std::memcpy(h, hdr.data() + 8 * (size_t(y) * size + x), sizeof(h));
        return glm::vec3(glm::unpackHalf1x16(h[0]), glm::unpackHalf1x16(h[1]), glm::unpackHalf1x16(h[2]));
    };
    const glm::vec3 middle = radiance(32, 32), beside = radiance(31, 32), aside = radiance(29, 32);
    std::printf("sun %.1f %.1f %.1f; the middle pixel %.1f %.1f %.1f, beside it %.3f %.3f %.3f, three aside %.3f %.3f "
                "%.3f\n",
                sun.sunRadiance.r, sun.sunRadiance.g, sun.sunRadiance.b, middle.r, middle.g, middle.b, beside.r,
                beside.g, beside.b, aside.r, aside.g, aside.b);
    for (int c = 0; c < 3; ++c) {
        ASSERT_GT(sun.sunRadiance[c], 10.0f * aside[c]) << c; // a disk far brighter than the sky
        // The HDR image's half floats end at 65,504, below the disk's radiance in this sky: lavapipe
        // stores their largest there (a device may store infinity, which passes too).
        EXPECT_GE(middle[c], 0.99f * std::min(aside[c] + sun.sunRadiance[c], 65504.0f)) << c;
        EXPECT_NEAR(beside[c], aside[c], 0.1f * aside[c]) << c;
    }
    destroyOffscreen(*context, offscreen);
    destroyFieldRenderer(*context, renderer);
}

// With the far field, its splat pass is timed between the draw and the tone map (which is then the
// resolve pass).
TEST_F(Gpu, TimestampsBracketTheFarFieldsPasses) {
    const ComparisonField field = comparisonField(3.0f);
    FieldRenderer renderer = createFieldRenderer(*context, field.clumps, field.instances, testAtlas(), field.scenery);
    Offscreen offscreen = createOffscreen(*context, {160, 90});
    const FrameTimings t = renderOffscreenFrame(*context, renderer, offscreen, frameState(field.camera, 160, 90));
    std::vector<std::string> labels;
    for (const PassTime& p : t.gpu) {
        labels.push_back(p.label);
        EXPECT_GE(p.milliseconds, 0.0) << p.label;
    }
    EXPECT_EQ(labels, (std::vector<std::string>{"animate", "cull", "light", "groundMap", "sky", "draw", "farSplat",
                                                "tonemap"}));
    destroyOffscreen(*context, offscreen);
    destroyFieldRenderer(*context, renderer);
}

// The near raster (near_raster.h): the comparison field 12 m away, so that its clumps (1 m
// spheres) span 6 to 30 px at 320x180 and most lie at LODs 1 to 3, which the near raster takes.
namespace {

ComparisonField nearField(float farRadius) {
    ComparisonField field = comparisonField(farRadius);
    field.scenery.nearRaster = true;
    field.camera.eye = glm::vec3(0.0f, 3.0f, -12.0f);
    return field;
}

} // namespace

// LOD 0 too goes to the near raster below kNearMaxRadius: with the LOD switches a tenth of the
// comparison field's, the draw pass draws none of the LOD 0 meshes it draws without the near raster
// (buckets are clump-major, LOD 0 every kLodCount-th), and the pictures agree as above.
TEST_F(Gpu, NearRasterTakesLod0BelowItsRadius) {
    ComparisonField field = nearField(0.3f);
    const float switches[4] = {6.0f, 2.5f, 1.0f, 0.4f};
    std::copy(switches, switches + 4, field.scenery.lod.switchRadius);
    const PathRun raster = drawOnPath(*context, field, false, 4);
    field.scenery.nearRaster = false;
    const PathRun meshes = drawOnPath(*context, field, false, 4);
    uint32_t lod0WithRaster = 0, lod0WithMeshes = 0;
    for (size_t b = 0; b < meshes.stats.visiblePerMesh.size(); b += kLodCount) {
        lod0WithRaster += raster.stats.visiblePerMesh[b];
        lod0WithMeshes += meshes.stats.visiblePerMesh[b];
    }
    std::printf("LOD 0 draws in the draw pass: %u with the near raster, %u without\n", lod0WithRaster, lod0WithMeshes);
    EXPECT_GT(lod0WithMeshes, 50u);
    EXPECT_EQ(lod0WithRaster, 0u);
    EXPECT_EQ(raster.stats.trianglesDrawn + raster.stats.nearTriangles, meshes.stats.trianglesDrawn);
    // The same draws per LOD, whichever pass draws them (bench's instancesPerLod, the HUD's).
    EXPECT_EQ(raster.stats.drawsPerLod(), meshes.stats.drawsPerLod());
    EXPECT_GT(raster.stats.nearPerLod.at(0), 50u);
    EXPECT_LE(differingChannels(raster.picture, meshes.picture), raster.picture.size() / 100);
}

// With the near raster, its two passes are timed between the draw and the splat pass.
TEST_F(Gpu, TimestampsBracketTheNearRastersPasses) {
    const ComparisonField field = nearField(3.0f);
    FieldRenderer renderer = createFieldRenderer(*context, field.clumps, field.instances, testAtlas(), field.scenery);
    Offscreen offscreen = createOffscreen(*context, {160, 90});
    const FrameTimings t = renderOffscreenFrame(*context, renderer, offscreen, frameState(field.camera, 160, 90));
    std::vector<std::string> labels;
    for (const PassTime& p : t.gpu)
        labels.push_back(p.label);
    EXPECT_EQ(labels, (std::vector<std::string>{"animate", "cull", "light", "groundMap", "sky", "draw", "nearVertices",
                                                "nearRaster", "farSplat", "tonemap"}));
    destroyOffscreen(*context, offscreen);
    destroyFieldRenderer(*context, renderer);
}

// The near raster against its CPU reference (render/near_reference.h), from the very inputs the GPU
// read in the frame: the near list the cull pass wrote, the draw records and the light the light
// pass projected. Coverage is integer arithmetic on both (near_raster.h), so the same pixels are
// covered; the interpolation's floats may round differently (the shader may fuse a multiply-add the
// C++ rounds twice), so colours and depths agree to 1 % and 1e-5, except at most 1 % of the pixels,
// where two triangles lie within rounding of each other's depth.
TEST_F(Gpu, NearRasterMatchesCpuReference) {
    ComparisonField field = nearField(0.0f);
    FieldRenderer renderer = createFieldRenderer(*context, field.clumps, field.instances, testAtlas(), field.scenery);
    const VkExtent2D extent{320, 180};
    Offscreen offscreen = createOffscreen(*context, extent);
    FrameState state = frameState(field.camera, extent.width, extent.height);
    state.wind.baseLevel = 2.0f;
    for (int frame = 0; frame < 3; ++frame) {
        state.seconds = frame * 0.1;
        renderOffscreenFrame(*context, renderer, offscreen, state);
    }

    NearRasterInputs in;
    std::memcpy(&in.frame, renderer.frameUniforms.mapped(), sizeof(in.frame));
    in.mirrorNormal = renderer.mirrorNormal;
    const gpu::GpuNearDispatch dispatch = readAll<gpu::GpuNearDispatch>(*context, renderer.nearDispatch, 1)[0];
    in.nearList = readAll<glm::uvec4>(*context, renderer.nearList, dispatch.count);
    in.drawInstances = readAll<gpu::GpuDrawInstance>(*context, renderer.drawInstances, field.instances.size());
    in.clumps = readAll<gpu::GpuClump>(*context, renderer.clumps, field.clumps.size());
    in.nearMeshes = readAll<glm::uvec4>(*context, renderer.nearMeshes, renderer.meshCount);
    in.indices = readAll<uint32_t>(*context, renderer.indices, renderer.indices.size / sizeof(uint32_t));
    in.lodVertices = readAll<gpu::GpuLodVertex>(*context, renderer.lodVertices,
                                                renderer.lodVertices.size / sizeof(gpu::GpuLodVertex));
    in.motionData = readAll<float>(*context, renderer.motionData, renderer.motionData.size / sizeof(float));
    in.vertexLight = readAll<glm::uvec4>(*context, renderer.vertexLight, renderer.vertexLight.size / 16);
    in.atlas = testAtlas();
    const FieldStats stats = readFieldStats(renderer);
    const std::vector<uint64_t> gpuWords = readFarVisibility(*context, offscreen.targets);
    const std::vector<uint64_t> cpuWords = nearRasterReference(in);
    destroyOffscreen(*context, offscreen);
    destroyFieldRenderer(*context, renderer);

    EXPECT_GT(dispatch.count, 200u);
    // Each draw listed once, or in kNearDrawParts parts when large (near_raster.h).
    EXPECT_EQ(dispatch.count,
              stats.nearInstances + (gpu::kNearDrawParts - 1) * std::min(dispatch.split, gpu::kNearMaxSplitDraws));
    EXPECT_GT(stats.nearTriangles, 10000u);
    ASSERT_EQ(gpuWords.size(), cpuWords.size());
    const WordComparison words = compareWords(gpuWords, cpuWords);
    const size_t covered = words.covered, oneSided = words.oneSided, differing = words.differing,
                 identical = words.identical;
    std::printf("near draws %u, triangles %llu, covered %zu, one-sided %zu, differing %zu, identical %zu\n",
                dispatch.count, static_cast<unsigned long long>(stats.nearTriangles), covered, oneSided, differing,
                identical);
    EXPECT_GT(covered, 5000u);
    EXPECT_LE(oneSided, covered / 1000) << "pixels only one of GPU and CPU covered, of " << covered;
    EXPECT_LE(differing, covered / 100) << "pixels whose nearest triangle differs, of " << covered;
}

// The CPU-driven path writes the near list and its dispatch that the cull pass would: the same
// draws, the same picture, byte for byte (the atomics make the order of the list immaterial).
TEST_F(Gpu, CpuDrivenPathDrawsTheSameNearRaster) {
    const ComparisonField field = nearField(3.0f);
    const PathRun gpuPath = drawOnPath(*context, field, false, 4), cpuPath = drawOnPath(*context, field, true, 4);
    EXPECT_GT(gpuPath.stats.nearInstances, 200u);
    EXPECT_EQ(cpuPath.stats.nearInstances, gpuPath.stats.nearInstances);
    EXPECT_EQ(cpuPath.stats.nearTriangles, gpuPath.stats.nearTriangles);
    EXPECT_EQ(cpuPath.stats.nearPerLod, gpuPath.stats.nearPerLod);
    EXPECT_TRUE(gpuPath.picture == cpuPath.picture);
}

// The near raster's workgroup width (two SIMD rows on lavapipe, 64 on a GPU) only shares the draws
// and their triangles out differently: the same picture, byte for byte.
TEST_F(Gpu, TheNearRasterDrawsTheSamePictureAtAnyWidth) {
    ComparisonField field = nearField(3.0f);
    field.scenery.nearWidth = nearWidthFor(*context);
    const PathRun narrow = drawOnPath(*context, field, false, 3);
    EXPECT_GT(narrow.stats.nearInstances, 200u);
    for (uint32_t width : {1u, 3u, gpu::kNearGroupSize, 256u}) {
        field.scenery.nearWidth = width;
        const PathRun other = drawOnPath(*context, field, false, 3);
        EXPECT_EQ(other.stats.nearTriangles, narrow.stats.nearTriangles) << width;
        EXPECT_TRUE(other.picture == narrow.picture) << width << " threads";
    }
    field.scenery.nearWidth = 2048;
    EXPECT_THROW(drawOnPath(*context, field, false, 1), Error);
}

// The near raster's draws dealt to the workgroups in turn, or taken by each SIMD row from a counter
// (near_raster.h; lavapipe's way), at widths of whole and partial rows: the same picture, byte for
// byte. Taken, every pass handed out every draw: each counter ends at or past the list's length (a
// row that finds none left still counts its try).
TEST_F(Gpu, TheNearRasterDrawsTheSamePictureWhetherItsDrawsAreDealtOrTaken) {
    ComparisonField field = nearField(3.0f);
    field.scenery.nearTakeDraws = 0;
    const PathRun dealt = drawOnPath(*context, field, false, 3);
    EXPECT_GT(dealt.stats.nearInstances, 200u);
    EXPECT_EQ(dealt.nearTaken, (std::array<uint32_t, 2>{0u, 0u}));
    field.scenery.nearTakeDraws = 1;
    for (uint32_t width : {0u, 1u, 3u, gpu::kNearGroupSize}) {
        field.scenery.nearWidth = width;
        const PathRun taken = drawOnPath(*context, field, false, 3);
        EXPECT_EQ(taken.stats.nearTriangles, dealt.stats.nearTriangles) << width;
        EXPECT_TRUE(taken.picture == dealt.picture) << width << " threads";
        EXPECT_EQ(taken.nearListed, dealt.nearListed) << width;
        for (uint32_t counter : taken.nearTaken)
            EXPECT_GE(counter, taken.nearListed) << width;
    }
    field.scenery.nearTakeDraws = 2;
    EXPECT_THROW(drawOnPath(*context, field, false, 1), Error);
}

// A draw of many large triangles close to the eye, listed in parts (near_raster.h): llvmpipe ends a
// SIMD row's loops, silently, after 65,535 passes in all, and a row of 4 or 8 lanes that took this
// draw whole ran past that and lost its last triangles, the nearest (so did every row of 8 lanes
// with the draw dealt to workgroups of 8). Listed in kNearDrawParts parts, taken by rows or dealt
// to workgroups of 16 threads, and dealt to 256 threads at once (far under the limit), the
// visibility buffer is the same word for word: the same triangles won every pixel, at the same
// depth.
TEST_F(Gpu, TheNearRasterDrawsALargeDrawWholeWhenItsDrawsAreTaken) {
    constexpr uint32_t kQuads = 60;
    Mesh stack; // kQuads squares facing -z, each nearer the eye than the one before, all of one clump
    for (uint32_t q = 0; q < kQuads; ++q) {
        const float z = -0.01f * float(q);
        const uint32_t base = uint32_t(stack.vertices.size());
        for (int corner = 0; corner < 4; ++corner) {
            const float u = float(corner & 1), v = float(corner >> 1);
            stack.vertices.push_back({glm::vec4(u * 1.6f - 0.8f, v * 1.6f, z, u), glm::vec4(0.0f, 0.0f, -1.0f, v)});
        }
        stack.indices.insert(stack.indices.end(), {base, base + 2, base + 1, base + 1, base + 2, base + 3});
    }
    stack.fitBoundingSphere();
    ComparisonField field = nearField(0.3f);
    field.clumps = {staticFieldClump(stack, kLodCount)};
    giveFarSamples(field.clumps[0]);
    gpu::GpuInstance one{};
    one.positionScale = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    one.boundingRadius = stack.boundingRadius;
    field.instances = {one};
    field.camera.eye = glm::vec3(0.0f, 0.8f, -2.3f);
    field.camera.target = glm::vec3(0.0f, 0.8f, 0.0f);
    field.scenery.nearTakeDraws = 0;
    field.scenery.nearWidth = 16;
    const PathRun dealt = drawOnPath(*context, field, false, 1);
    ASSERT_EQ(dealt.stats.nearInstances, 1u); // the whole stack, in the near raster
    EXPECT_EQ(dealt.stats.nearTriangles, 2 * kQuads);
    EXPECT_EQ(dealt.nearListed, gpu::kNearDrawParts); // over 48 px: in parts
    // One draw per LOD count, whatever its parts.
    const std::vector<uint32_t> perLod = dealt.stats.drawsPerLod();
    EXPECT_EQ(std::accumulate(perLod.begin(), perLod.end(), 0u), 1u);
    size_t covered = 0;
    for (uint64_t word : dealt.visibility)
        covered += word != ~uint64_t(0);
    EXPECT_GT(covered, dealt.visibility.size() / 4); // a large draw: a quarter of the picture or more
    field.scenery.nearWidth = 256;
    EXPECT_TRUE(drawOnPath(*context, field, false, 1).visibility == dealt.visibility) << "dealt to 256 threads";
    field.scenery.nearTakeDraws = 1;
    field.scenery.nearWidth = 0;
    const PathRun taken = drawOnPath(*context, field, false, 1);
    EXPECT_TRUE(taken.visibility == dealt.visibility) << "taken in parts";
    EXPECT_TRUE(taken.picture == dealt.picture);
}

// The near raster draws what the mesh pass draws for the same LODs: the same picture but for the
// pixels where the two rasterisers' rounding, mip choice or light interpolation differ.
TEST_F(Gpu, NearRasterDrawsWhatTheMeshPassDraws) {
    ComparisonField field = nearField(3.0f);
    const PathRun raster = drawOnPath(*context, field, false, 4);
    field.scenery.nearRaster = false;
    const PathRun meshes = drawOnPath(*context, field, false, 4);
    EXPECT_GT(raster.stats.nearInstances, 200u);
    EXPECT_EQ(meshes.stats.nearInstances, 0u);
    EXPECT_EQ(raster.stats.trianglesDrawn + raster.stats.nearTriangles, meshes.stats.trianglesDrawn);
    size_t plant = 0; // pixels that differ from the sky and ground's colour in either
    for (size_t i = 0; i + 3 < raster.picture.size(); i += 4)
        plant += raster.picture[i] != meshes.picture[i] || raster.picture[i + 1] != meshes.picture[i + 1];
    const size_t differing = differingChannels(raster.picture, meshes.picture);
    std::printf("channels differing by more than 8: %zu of %zu (pixels with any change %zu)\n", differing,
                raster.picture.size(), plant);
    EXPECT_LE(differing, raster.picture.size() / 100);
}
