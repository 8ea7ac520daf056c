// The animate pass and the vertex shader's motion on a real device against the CPU's
// motion-graph steps (shaders/shared/motion_step.h).
// ctest runs these at two lavapipe vector widths (LP_NATIVE_VECTOR_WIDTH=128 and 256).
#include "gpu_fixture.h"
#include "library/mesh.h"
#include "library/terrain.h"
#include "render/field_renderer.h"
#include "render/offscreen.h"
#include "sh_light.h"
#include "vk/memory.h"
#include "wind_field.h"
#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>
#include <random>

using namespace meadow;
using namespace meadow::test;

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
    // The frames took 0, 1, several and 62 steps; the wind spanned every level.
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

// Motion keeps real time at any frame rate: after T seconds the instances' motion states are the
// same whether the frames came every 1/30 s or every 1/2 s (15 steps a frame) or once after 6 s
// (180 steps); only a stall longer than kMaxMotionStepsPerFrame steps drops motion.
TEST_F(Gpu, MotionKeepsRealTimeAtAnyFrameRate) {
    std::vector<FieldClump> clumps = {movingClump(), movingClump(4)};
    std::vector<gpu::GpuInstance> instances = scatter(2000, 29);
    for (gpu::GpuInstance& inst : instances)
        inst.mesh %= 2;
    FieldScenery scenery = testScenery();
    scenery.lodCount = kLodCount;
    scenery.lod = {{120.0f, 50.0f, 20.0f, 8.0f}, 0.1f, 0.2f, 0.05f, 0.0f};
    auto statesAfter = [&](double seconds, double frameTime) {
        FieldRenderer renderer = createFieldRenderer(*context, clumps, instances, testAtlas(), scenery);
        Offscreen offscreen = createOffscreen(*context, {16, 16});
        FrameState state = frameState(Camera{}, 16, 16);
        state.wind.baseLevel = 1.5f;
        state.wind.waveAmplitude = 1.5f;
        state.wind.gustAmplitude = 1.0f;
        uint32_t steps = 0;
        for (int frame = 0; frame * frameTime <= seconds + 1e-9; ++frame) {
            state.seconds = frame * frameTime + 1e-7; // clear of the tick boundaries floor() meets
            renderOffscreenFrame(*context, renderer, offscreen, state);
            gpu::GpuFrame f;
            std::memcpy(&f, renderer.frameUniforms.mapped(), sizeof(f));
            steps += f.motion.y;
        }
        EXPECT_EQ(steps, uint32_t(std::lround(seconds * 30.0))) << "frames of " << frameTime << " s";
        std::vector<gpu::GpuMotionState> states(instances.size());
        readbackBuffer(*context, renderer.motionStates, states.data(), states.size() * sizeof(states[0]));
        destroyOffscreen(*context, offscreen);
        destroyFieldRenderer(*context, renderer);
        return states;
    };
    const std::vector<gpu::GpuMotionState> smooth = statesAfter(6.0, 1.0 / 30.0);
    const std::vector<gpu::GpuMotionState> slow = statesAfter(6.0, 0.5);
    const std::vector<gpu::GpuMotionState> once = statesAfter(6.0, 6.0);
    for (const std::vector<gpu::GpuMotionState>* other : {&slow, &once}) {
        size_t differing = 0;
        for (size_t i = 0; i < instances.size(); ++i)
            differing += std::memcmp(&smooth[i], &(*other)[i], sizeof(smooth[i])) != 0;
        EXPECT_EQ(differing, 0u) << "instances whose motion differs between 1/30 s frames and "
                                 << (other == &slow ? "1/2 s" : "6 s") << " frames";
    }
    EXPECT_EQ(smooth[0].counter, 180u);
}
