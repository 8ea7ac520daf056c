// What field_packing.cpp lays out on the CPU for the renderer's buffers and images, where a test
// can pin it down without a device.
#include "library/mesh.h"
#include "render/field_packing.h"
#include "render/field_renderer.h"

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace meadow {
namespace {

TEST(FieldPacking, AtlasIsLinearHalfFloats) {
    // Three texels: black and white, opaque; then sRGB 188 in each colour channel (about 0.5028
    // linear) with alpha 128 (128/255, not decoded).
    const RgbaImage atlas{3, 1, {0, 0, 0, 255, 255, 255, 255, 255, 188, 188, 188, 128}};
    const std::vector<uint16_t> texels = packAtlas(atlas);
    ASSERT_EQ(texels.size(), atlas.rgba.size());
    const float decoded = std::pow((188.0f / 255.0f + 0.055f) / 1.055f, 2.4f);
    const float want[12] = {0, 0, 0, 1, 1, 1, 1, 1, decoded, decoded, decoded, 128.0f / 255.0f};
    for (size_t i = 0; i < texels.size(); ++i)
        EXPECT_NEAR(glm::unpackHalf1x16(texels[i]), want[i], 5e-4f) << i;
    // The dark end of the curve is linear: sRGB 3 is 3 / 255 / 12.92.
    const std::vector<uint16_t> dark = packAtlas(RgbaImage{1, 1, {3, 3, 3, 3}});
    EXPECT_NEAR(glm::unpackHalf1x16(dark[0]), 3.0f / 255.0f / 12.92f, 1e-6f);
    EXPECT_NEAR(glm::unpackHalf1x16(dark[3]), 3.0f / 255.0f, 1e-5f);
}

// A closed surface (a rock) shows only its outer side, but the draws pick a fragment's side from the
// interpolated normal, which turns away from the eye just inside the silhouette: there the inner
// side's transfer (the inside of the rock, unlit) painted a black rim. Packed, both sides of a closed
// clump carry its outer side's transfer; a two-sided sheet keeps both of its own.
TEST(FieldPacking, ClosedSurfacesLightBothSidesAsTheOuterOne) {
    const Mesh mesh = makeTuftMesh(2, 1);
    const size_t vertexCount = mesh.vertices.size();
    const size_t perVertex = 54 * 4, perSide = perVertex / 2; // 2 sides x RGB x 9 SH, vec4 each
    std::vector<float> transfer(vertexCount * perVertex);
    for (size_t i = 0; i < transfer.size(); ++i)
        transfer[i] = (i % perVertex) < perSide ? 1.0f + float(i) : -1.0f - float(i);
    FieldClump sheet = staticFieldClump(mesh, 2);
    sheet.transfer = transfer;
    FieldClump rock = sheet;
    rock.farClosed = true;
    const std::vector<FieldClump> clumps{sheet, rock};
    const FieldPacking packed = packField(clumps, std::span<const gpu::GpuInstance>(), 2);
    ASSERT_EQ(packed.clumps.size(), 2u);
    for (size_t c = 0; c < 2; ++c) {
        const size_t base = size_t(packed.clumps[c].light.z) * 4;
        for (size_t v = 0; v < vertexCount; ++v)
            for (size_t k = 0; k < perSide; ++k) {
                const float outer = transfer[v * perVertex + k], inner = transfer[v * perVertex + perSide + k];
                EXPECT_EQ(packed.transfer[base + v * perVertex + k], outer) << "clump " << c << " vertex " << v;
                EXPECT_EQ(packed.transfer[base + v * perVertex + perSide + k], c == 1 ? outer : inner)
                    << "clump " << c << " vertex " << v;
            }
    }
}

} // namespace
} // namespace meadow
