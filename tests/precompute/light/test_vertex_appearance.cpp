// First-order vertex appearance: exact for transfer linear in the displacement, the mean alone
// for vertices that do not move, and rejection of inconsistent input.
#include "light/vertex_appearance.h"

#include "core/error.h"
#include "core/random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace meadow;

namespace {

constexpr uint32_t kValues = 5;

struct Synthetic {
    Eigen::MatrixXf baked;
    std::vector<std::vector<glm::vec3>> displacements;
    std::vector<float> mean, gradient; // [v][value], [v][value][axis]
};

// Three vertices: two move (centimetres) and follow T = T̄ + G d exactly; vertex 2 stays put.
Synthetic makeSynthetic(uint32_t frames, uint64_t seed) {
    Random random(seed);
    Synthetic s;
    const uint32_t vertices = 3;
    s.mean.resize(vertices * kValues);
    s.gradient.resize(vertices * kValues * 3);
    for (float& m : s.mean)
        m = random.uniform(0.2f, 2.0f);
    for (float& g : s.gradient)
        g = random.uniform(-8.0f, 8.0f); // per metre: 8 cm of travel changes T by ~0.6
    for (uint32_t v = 2 * kValues * 3; v < 3 * kValues * 3; ++v)
        s.gradient[v] = 0.0f;
    s.baked.resize(vertices * kValues, frames);
    for (uint32_t f = 0; f < frames; ++f) {
        std::vector<glm::vec3> d(vertices, glm::vec3(0.0f));
        for (uint32_t v = 0; v < 2; ++v)
            d[v] =
                glm::vec3(random.uniform(-0.08f, 0.08f), random.uniform(-0.02f, 0.02f), random.uniform(-0.08f, 0.08f));
        for (uint32_t v = 0; v < vertices; ++v)
            for (uint32_t i = 0; i < kValues; ++i) {
                const float* g = &s.gradient[(v * kValues + i) * 3];
                s.baked(v * kValues + i, f) = s.mean[v * kValues + i] + g[0] * d[v].x + g[1] * d[v].y + g[2] * d[v].z;
            }
        s.displacements.push_back(d);
    }
    return s;
}

} // namespace

TEST(VertexAppearance, RecoversLinearTransferExactly) {
    const Synthetic s = makeSynthetic(24, 1);
    // No ridge: the least-squares fit of exactly linear data is the data's own mean and gradient.
    const VertexAppearance model = fitVertexAppearance(s.baked, kValues, s.displacements, 0.0f);
    ASSERT_EQ(model.vertexCount, 3u);
    for (uint32_t v = 0; v < 2; ++v)
        for (uint32_t i = 0; i < kValues; ++i) {
            const float* c = model.at(v, i);
            // Tolerance: float data of order 1, solved in double.
            EXPECT_NEAR(c[0], s.mean[v * kValues + i], 1e-4f);
            for (int axis = 0; axis < 3; ++axis)
                EXPECT_NEAR(c[1 + axis], s.gradient[(v * kValues + i) * 3 + axis], 2e-3f) << v << " " << i;
        }
    // And at a displacement it never saw.
    const std::vector<glm::vec3> d = {{0.05f, -0.01f, 0.02f}, {-0.03f, 0.015f, 0.07f}, {0.0f, 0.0f, 0.0f}};
    const Eigen::VectorXf t = evaluateVertexAppearance(model, d);
    for (uint32_t v = 0; v < 3; ++v)
        for (uint32_t i = 0; i < kValues; ++i) {
            const float* g = &s.gradient[(v * kValues + i) * 3];
            const float expected = s.mean[v * kValues + i] + g[0] * d[v].x + g[1] * d[v].y + g[2] * d[v].z;
            EXPECT_NEAR(t(v * kValues + i), expected, 1e-4f);
        }
}

TEST(VertexAppearance, StillVerticesKeepTheirMean) {
    Synthetic s = makeSynthetic(16, 2);
    // Noise on the still vertex's transfer must not turn into a gradient: with no displacement the
    // ridge leaves the gradient at zero and the mean at the average.
    Random random(3);
    for (uint32_t f = 0; f < 16; ++f)
        for (uint32_t i = 0; i < kValues; ++i)
            s.baked(2 * kValues + i, f) += random.uniform(-0.05f, 0.05f);
    const VertexAppearance model = fitVertexAppearance(s.baked, kValues, s.displacements, 1e-3f);
    for (uint32_t i = 0; i < kValues; ++i) {
        const float* c = model.at(2, i);
        EXPECT_NEAR(c[0], s.baked.row(2 * kValues + i).mean(), 1e-5f);
        EXPECT_EQ(c[1], 0.0f);
        EXPECT_EQ(c[2], 0.0f);
        EXPECT_EQ(c[3], 0.0f);
    }
    // A 1 mm ridge barely touches gradients learnt from centimetres of travel: it shrinks them by
    // about ridge^2 / variance of the displacement, (1 mm)^2 / (1.15 cm)^2 = 0.75 % along y, the
    // axis with the least travel. Correlated axes spread that over the components, so the
    // tolerance is 2 % of the gradient's largest component.
    const VertexAppearance exact = fitVertexAppearance(s.baked, kValues, s.displacements, 0.0f);
    for (uint32_t i = 0; i < kValues; ++i) {
        const float* e = exact.at(0, i);
        const float largest = std::max({std::abs(e[1]), std::abs(e[2]), std::abs(e[3])});
        for (int k = 0; k < 4; ++k)
            EXPECT_NEAR(model.at(0, i)[k], e[k], 0.02f * largest + 1e-4f);
    }
}

TEST(VertexAppearance, RejectsInconsistentInput) {
    const Synthetic s = makeSynthetic(8, 4);
    EXPECT_THROW(fitVertexAppearance(s.baked, 4, s.displacements, 0.0f), Error); // 15 rows, 4 per vertex
    std::vector<std::vector<glm::vec3>> short_ = s.displacements;
    short_.pop_back();
    EXPECT_THROW(fitVertexAppearance(s.baked, kValues, short_, 0.0f), Error);
    std::vector<std::vector<glm::vec3>> wrong = s.displacements;
    wrong[2].pop_back();
    EXPECT_THROW(fitVertexAppearance(s.baked, kValues, wrong, 0.0f), Error);
    Eigen::MatrixXf nan = s.baked;
    nan(3, 3) = std::nanf("");
    EXPECT_THROW(fitVertexAppearance(nan, kValues, s.displacements, 0.0f), Error);
    EXPECT_THROW(fitVertexAppearance(s.baked.leftCols(1), kValues, {s.displacements[0]}, 0.0f), Error);
    EXPECT_THROW(fitVertexAppearance(s.baked, kValues, s.displacements, -1.0f), Error);
}
