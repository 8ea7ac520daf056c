// The CPU references' displacement of a clump vertex (render/reference_motion.h), the sum
// shaders/shared/clump_motion.glsl makes on the GPU (the references are checked against the GPU
// passes in meadow_gpu_tests; this pins the sum itself down by hand).
#include "render/reference_motion.h"

#include "core/error.h"

#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <vector>

namespace meadow {
namespace {

// Rows U0 = (1, 2, 3) and U1 = (4, 5, 6) of one vertex, 4 floats each (rows 0 and 1: the fourth is
// never read), then two frames of two blocks' coordinates, each block padded to 4 floats: frame A
// at 8, (0.5, -1) and (3, 1); frame B at 16, (2, 0) and (-2, 4).
const std::vector<float> kMotionData = {1, 2, 3, 0, 4, 5, 6, 0, 0.5f, -1, 0, 0, 3, 1, 0, 0, 2, 0, 0, 0, -2, 4, 0, 0};

gpu::GpuDrawInstance instanceAt(uint32_t frameA, uint32_t frameB, float blend) {
    gpu::GpuDrawInstance inst{};
    inst.pose = glm::vec4(1.0f, 0.0f, blend, 0.0f);
    inst.offsets = glm::uvec4(frameA, frameB, 0u, 0u);
    return inst;
}

void expectNear(const glm::vec3& got, const glm::vec3& want) {
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(got[i], want[i], 1e-6f) << i;
}

TEST(ReferenceMotion, SumsTheVertexsModesWithItsFramesCoordinates) {
    // Rank 2 in w's low 16 bits, the LOD (3) above: d = 0.5 U0 - 1 U1.
    const glm::uvec4 motion(0u, 0u, 0u, 2u | (3u << 16));
    expectNear(clumpVertexDisplacement(kMotionData, motion, instanceAt(8, 16, 0.0f), "test"),
               glm::vec3(-3.5f, -4.0f, -4.5f));
    // Rank 1: the first mode alone.
    expectNear(clumpVertexDisplacement(kMotionData, glm::uvec4(0u, 0u, 0u, 1u), instanceAt(8, 16, 0.0f), "test"),
               glm::vec3(0.5f, 1.0f, 1.5f));
    // The second block's coordinates, 4 further in: q = (3, 1) from frame A's.
    expectNear(clumpVertexDisplacement(kMotionData, glm::uvec4(0u, 4u, 0u, 2u), instanceAt(8, 16, 0.0f), "test"),
               glm::vec3(7.0f, 11.0f, 15.0f));
}

TEST(ReferenceMotion, BlendsTheTwoFramesCoordinatesAcrossAJump) {
    // A quarter of the way to frame B: q = (0.875, -0.75); the second block's (1.75, 1.75).
    expectNear(clumpVertexDisplacement(kMotionData, glm::uvec4(0u, 0u, 0u, 2u), instanceAt(8, 16, 0.25f), "test"),
               glm::vec3(-2.125f, -2.0f, -1.875f));
    expectNear(clumpVertexDisplacement(kMotionData, glm::uvec4(0u, 4u, 0u, 2u), instanceAt(8, 16, 0.25f), "test"),
               glm::vec3(8.75f, 12.25f, 15.75f));
}

TEST(ReferenceMotion, RefusesRowsAndCoordinatesOutsideTheData) {
    try {
        clumpVertexDisplacement(kMotionData, glm::uvec4(0u, 0u, 0u, 2u), instanceAt(24, 16, 0.0f), "farSplatReference");
        FAIL() << "a coordinate past the data was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("farSplatReference: motion coordinate index 24"), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(clumpVertexDisplacement(kMotionData, glm::uvec4(5u, 0u, 0u, 2u), instanceAt(8, 16, 0.0f), "test"),
                 Error); // the second mode's row (row 6, floats 24-26) runs past the end
}

TEST(ReferenceMotion, RefusesCoordinatesOffATexelBoundary) {
    // The shader fetches a block's coordinates four to a texel from its first: a block that starts
    // one float in would read its neighbour's. Blending, the other frame's start counts too.
    for (const auto& [motionY, frameB, blend] :
         {std::tuple{1u, 16u, 0.0f}, std::tuple{0u, 18u, 0.5f}, std::tuple{2u, 18u, 0.5f}}) {
        try {
            clumpVertexDisplacement(kMotionData, glm::uvec4(0u, motionY, 0u, 2u), instanceAt(8, frameB, blend), "test");
            FAIL() << "coordinates at " << motionY << " of frames 8 and " << frameB << " were read";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("not start on a texel's 4-float boundary"), std::string::npos)
                << e.what();
        }
    }
    // Unblended, the other frame is not read: its start does not matter.
    expectNear(clumpVertexDisplacement(kMotionData, glm::uvec4(0u, 0u, 0u, 2u), instanceAt(8, 18, 0.0f), "test"),
               glm::vec3(-3.5f, -4.0f, -4.5f));
}

} // namespace
} // namespace meadow
