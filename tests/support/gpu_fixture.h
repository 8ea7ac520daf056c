// The fixture of the GPU tests (tests/engine/*/test_gpu_*.cpp): one validated Vulkan context for
// the suite `Gpu`, whose validation counter must stay at zero, and the small scenes they render.
#pragma once
#include "library/mesh.h"
#include "library/sky_day.h"
#include "render/field_renderer.h"
#include "vk/context.h"

#include <cstdint>
#include <gtest/gtest.h>
#include <vector>

namespace meadow::test {

class Gpu : public ::testing::Test {
  protected:
    static void SetUpTestSuite();
    static void TearDownTestSuite();
    void TearDown() override;
    static Context* context;
};

// Three small meshes (draw buckets), each a static clump.
std::vector<Mesh> testMeshes();
std::vector<FieldClump> staticClumps(const std::vector<Mesh>& meshes);
// A clump whose LODs are separate meshes: its vertices are all of theirs, each LOD its own range.
FieldClump clumpOfLods(const std::vector<Mesh>& lods);
// One frame of the analytic sky, at 10 h.
sky::SkyDay testSky();
FrameState frameState(const Camera& camera, uint32_t width, uint32_t height);
// A plain 4 x 4 texture.
RgbaImage testAtlas();
// A flat terrain 20 m square and the test sky.
FieldScenery testScenery();
// Instances scattered in a box around the origin, some huge, some tiny, spread over three
// meshes; deterministic.
std::vector<gpu::GpuInstance> scatter(uint32_t count, uint32_t seed);
// A moving clump: the tuft with a synthetic motion library (four wind levels of damped,
// gust-driven coordinates, as a simulated clump's PCA coordinates behave), its real motion graph,
// and random basis rows in one block of `dims` modes (LODs play 6, 4, 2, 1, 1 of them).
// A moving tuft: `dims` modes at LOD 0, then 4, 2, 1 and 1, each at least `lastLodRank` (the modes
// its last LOD plays, which the far field's samples follow).
FieldClump movingClump(uint32_t dims = 6, uint32_t lastLodRank = 1);

} // namespace meadow::test
