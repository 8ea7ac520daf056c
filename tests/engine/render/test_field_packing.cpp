// What field_packing.cpp lays out on the CPU for the renderer's buffers and images, where a test
// can pin it down without a device.
#include "render/field_packing.h"

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

} // namespace
} // namespace meadow
