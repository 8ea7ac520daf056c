// Attribute and collapse groups from a clump's data (precompute/lod/lod_attributes.cpp).
#include "lod/lod.h"

#include "core/error.h"
#include "light/vertex_appearance.h"
#include "plants/plant.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace meadow;

namespace {

// Two rods' blocks: block 0 with 2 modes (1 from LOD 1 on), block 1 with 3 (2 at LOD 1, 1 after);
// vertices 0 and 1 follow block 0, vertices 2 and 3 block 1. Coordinates over 8 frames are
// cosines and sines of whole periods: centred and mutually uncorrelated, as PCA's are.
MotionBasis twoBlockBasis() {
    MotionBasis basis;
    basis.frames = 8;
    basis.blocks = {{0, {2, 1, 1, 1, 1}}, {2, {3, 2, 1, 1, 1}}};
    basis.lodModes = {5, 3, 2, 2, 2};
    basis.vertexBlock = {0, 0, 1, 1};
    for (uint32_t v = 0; v < 4; ++v)
        for (uint32_t i = 0; i < 3 * basis.blocks[basis.vertexBlock[v]].ranks[0]; ++i)
            basis.basis.push_back(std::sin(1.3f * float(v * 11 + i) + 0.4f));
    const float amplitude[5] = {0.5f, 0.2f, 0.8f, 0.3f, 0.1f};
    for (uint32_t f = 0; f < basis.frames; ++f) {
        const float phase = 2.0f * 3.14159265f * float(f) / 8.0f;
        const float wave[5] = {std::cos(phase), std::sin(phase), std::cos(2.0f * phase), std::sin(2.0f * phase),
                               std::cos(3.0f * phase)};
        for (uint32_t k = 0; k < 5; ++k)
            basis.coords.push_back(amplitude[k] * wave[k]);
    }
    basis.relativeErrorPerMode.assign(6, 0.0);
    basis.finish("test basis");
    return basis;
}

} // namespace

TEST(LodAttributes, MotionRowsAreScaledToMetresOfDisplacement) {
    const MotionBasis basis = twoBlockBasis();
    const AttributeValues all = motionAttributes(basis, 0);
    ASSERT_EQ(all.width, 9u); // the widest block: 3 modes x (x, y, z)
    ASSERT_EQ(all.values.size(), 4u * 9u);
    // Vertex 0: its block's 2 modes scaled by their coordinates' RMS (amplitude / sqrt 2 for a
    // whole period of a sinusoid), then zero padding. Float tolerance.
    const float sigma0 = 0.5f / std::sqrt(2.0f), sigma1 = 0.2f / std::sqrt(2.0f);
    for (uint32_t axis = 0; axis < 3; ++axis) {
        EXPECT_NEAR(all.values[axis], basis.basis[axis] * sigma0, 1e-6f);
        EXPECT_NEAR(all.values[3 + axis], basis.basis[3 + axis] * sigma1, 1e-6f);
        EXPECT_EQ(all.values[6 + axis], 0.0f);
    }
    // The header's claim: within a block, the squared distance of two vertices' attributes is
    // their mean squared displacement difference over the frames. Float tolerance, relative.
    for (auto [u, v] : {std::pair{0u, 1u}, std::pair{2u, 3u}}) {
        double attribute = 0.0, motion = 0.0;
        for (uint32_t i = 0; i < all.width; ++i) {
            const double d = double(all.values[u * all.width + i]) - double(all.values[v * all.width + i]);
            attribute += d * d;
        }
        for (uint32_t f = 0; f < basis.frames; ++f) {
            const glm::vec3 d = basis.displacement(u, f) - basis.displacement(v, f);
            motion += glm::dot(d, d) / double(basis.frames);
        }
        EXPECT_NEAR(attribute, motion, 1e-5 * motion) << u << "-" << v;
    }
    // At LOD 2 each block keeps one mode.
    const AttributeValues far = motionAttributes(basis, 2);
    EXPECT_EQ(far.width, 3u);
    EXPECT_NEAR(far.values[3 * 2], basis.basis[basis.vertexRowOffset[2]] * 0.8f / std::sqrt(2.0f), 1e-6f);
}

TEST(LodAttributes, MotionRejectsBadInput) {
    MotionBasis basis = twoBlockBasis();
    EXPECT_THROW(motionAttributes(basis, kLodCount), Error);
    basis.vertexRowOffset.clear();
    try {
        motionAttributes(basis, 0);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("not finished"), std::string::npos) << e.what();
    }
}

TEST(LodAttributes, MeanTransferIsNormalisedToUnitSpread) {
    VertexAppearance appearance;
    appearance.vertexCount = 3;
    appearance.valuesPerVertex = 2;
    const float means[3][2] = {{1.0f, 4.0f}, {2.0f, 4.0f}, {6.0f, 7.0f}};
    for (uint32_t v = 0; v < 3; ++v)
        for (uint32_t j = 0; j < 2; ++j)
            appearance.coefficients.insert(appearance.coefficients.end(), {means[v][j], 9.0f, -9.0f, 9.0f});
    const AttributeValues a = meanTransferAttributes(appearance);
    ASSERT_EQ(a.width, 2u);
    // Deviations from the per-value means (3, 5): -2, -1, 3 and -1, -1, 2: RMS sqrt(20 / 6).
    const float scale = 1.0f / std::sqrt(20.0f / 6.0f);
    for (uint32_t v = 0; v < 3; ++v)
        for (uint32_t j = 0; j < 2; ++j)
            EXPECT_NEAR(a.values[v * 2 + j], means[v][j] * scale, 1e-6f); // float rounding
    appearance.coefficients.pop_back();
    EXPECT_THROW(meanTransferAttributes(appearance), Error);
}

TEST(LodAttributes, RodGroupsFollowTheSkin) {
    PlantMesh mesh;
    mesh.positions.resize(3);
    mesh.skin = {{4, 0, 0.0f, {}}, {4, 1, 0.5f, {}}, {7, 0, 0.0f, {}}};
    EXPECT_EQ(rodGroups(mesh), (std::vector<uint32_t>{4, 4, 7}));
    mesh.skin.pop_back();
    EXPECT_THROW(rodGroups(mesh), Error);
}
