// The CPU references' displacement of a clump vertex (render/reference_motion.h), the sum
// shaders/shared/clump_motion.glsl makes on the GPU (the references are checked against the GPU
// passes in meadow_gpu_tests; this pins the sum itself down by hand).
#include "render/reference_motion.h"

#include "core/error.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace meadow {
namespace {

// Rows U0 = (1, 2, 3) and U1 = (4, 5, 6) of one vertex, 4 floats each (rows 0 and 1: the fourth is
// never read), then two frames' coordinates of its block: frame A (0.5, -1) at 8, frame B (2, 0)
// at 10.
const std::vector<float> kMotionData = {1, 2, 3, 0, 4, 5, 6, 0, 0.5f, -1, 2, 0};

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
    expectNear(clumpVertexDisplacement(kMotionData, motion, instanceAt(8, 10, 0.0f), "test"),
               glm::vec3(-3.5f, -4.0f, -4.5f));
    // Rank 1: the first mode alone.
    expectNear(clumpVertexDisplacement(kMotionData, glm::uvec4(0u, 0u, 0u, 1u), instanceAt(8, 10, 0.0f), "test"),
               glm::vec3(0.5f, 1.0f, 1.5f));
    // The block's coordinates start one further in: q = (-1, 2) from frame A's.
    expectNear(clumpVertexDisplacement(kMotionData, glm::uvec4(0u, 1u, 0u, 2u), instanceAt(8, 10, 0.0f), "test"),
               glm::vec3(7.0f, 8.0f, 9.0f));
}

TEST(ReferenceMotion, BlendsTheTwoFramesCoordinatesAcrossAJump) {
    // A quarter of the way to frame B: q = (0.875, -0.75).
    expectNear(clumpVertexDisplacement(kMotionData, glm::uvec4(0u, 0u, 0u, 2u), instanceAt(8, 10, 0.25f), "test"),
               glm::vec3(-2.125f, -2.0f, -1.875f));
}

TEST(ReferenceMotion, RefusesRowsAndCoordinatesOutsideTheData) {
    try {
        clumpVertexDisplacement(kMotionData, glm::uvec4(0u, 0u, 0u, 2u), instanceAt(11, 10, 0.0f), "farSplatReference");
        FAIL() << "a coordinate past the data was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("farSplatReference: motion coordinate index 12"), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(clumpVertexDisplacement(kMotionData, glm::uvec4(2u, 0u, 0u, 2u), instanceAt(8, 10, 0.0f), "test"),
                 Error); // the second mode's row (row 3, floats 12-14) runs past the end
}

} // namespace
} // namespace meadow
