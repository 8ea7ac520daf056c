// The shared LOD choice (shaders/shared/lod_select.h) on hand-made cases: plateaus and bands,
// jittered switch radii, hysteresis, and complementary dither masks.
#include "lod_select.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

using namespace meadow::gpu;

namespace {

GpuLodParams params() {
    GpuLodParams p{};
    const float radii[4] = {200.0f, 80.0f, 30.0f, 10.0f};
    for (int i = 0; i < 4; ++i)
        p.switchRadius[i] = radii[i];
    p.band = 0.1f;
    p.jitter = 0.0f;
    p.hysteresis = 0.1f;
    return p;
}

} // namespace

TEST(LodSelect, PlateausAndBands) {
    const GpuLodParams p = params();
    // Far above the first band: LOD 0 alone; below the last: LOD 4 alone.
    GpuLodChoice c = lodSelect(p, 1000.0f, 0.5f, 0.0f);
    EXPECT_EQ(c.lod, 0u);
    EXPECT_EQ(c.fade, 0.0f);
    EXPECT_EQ(c.fadeLod, 0u);
    c = lodSelect(p, 2.0f, 0.5f, 4.0f);
    EXPECT_EQ(c.lod, 4u);
    EXPECT_EQ(c.fadeLod, 4u);
    // Between the bands of 80 px (72..88) and 30 px (27..33): LOD 2 exactly.
    c = lodSelect(p, 50.0f, 0.5f, 2.0f);
    EXPECT_EQ(c.x, 2.0f);
    EXPECT_EQ(c.lod, 2u);
    EXPECT_EQ(c.fade, 0.0f);
    // The middle of the 80 px band: half LOD 1, half LOD 2. Tolerance: float rounding.
    c = lodSelect(p, 80.0f, 0.5f, 1.5f);
    EXPECT_EQ(c.lod, 1u);
    EXPECT_EQ(c.fadeLod, 2u);
    EXPECT_NEAR(c.fade, 0.5f, 1e-6f);
    // A quarter into the band from its top (88 px) towards 72 px.
    EXPECT_NEAR(lodCoordinate(p, 84.0f, 0.5f), 1.25f, 1e-5f);
}

TEST(LodSelect, CoordinateFallsMonotonicallyWithScreenSize) {
    const GpuLodParams p = params();
    float previous = -1.0f;
    for (float r = 400.0f; r > 1.0f; r *= 0.99f) {
        const float x = lodCoordinate(p, r, 0.3f);
        EXPECT_GE(x, previous) << "r " << r;
        EXPECT_GE(x, 0.0f);
        EXPECT_LE(x, 4.0f);
        previous = x;
    }
    EXPECT_EQ(previous, 4.0f);
}

TEST(LodSelect, JitterSpreadsTheSwitchPerInstance) {
    GpuLodParams p = params();
    p.jitter = 0.3f;
    // Instance random numbers scale the switch radii by 1 + 0.3 (u - 1/2): 0.85x .. 1.15x.
    EXPECT_NEAR(lodCoordinate(p, 80.0f * 0.85f, 0.0f), 1.5f, 1e-5f);
    EXPECT_NEAR(lodCoordinate(p, 80.0f * 1.15f, 1.0f), 1.5f, 1e-5f);
    // At one distance, instances with different random numbers are at different points of the
    // crossfade, so the field shows no ring.
    std::set<int> steps;
    for (int i = 0; i < 16; ++i)
        steps.insert(int(lodCoordinate(p, 80.0f, (float(i) + 0.5f) / 16.0f) * 100.0f));
    EXPECT_GE(steps.size(), 10u);
}

TEST(LodSelect, HysteresisHoldsInsideABandAndSnapsOnPlateaus) {
    const GpuLodParams p = params();
    // A camera hovering around 80 px: +-1 px moves the target by ~0.06, less than the 0.1 of
    // hysteresis, so x (and with it the dither masks) stays put.
    float x = lodSelect(p, 80.0f, 0.5f, 0.0f).x; // arriving from a plateau: jumps to the target
    EXPECT_NEAR(x, 1.5f, 1e-6f);
    for (int frame = 0; frame < 50; ++frame) {
        const float r = frame % 2 ? 81.0f : 79.0f;
        const GpuLodChoice c = lodSelect(p, r, 0.5f, x);
        EXPECT_EQ(c.x, x) << "frame " << frame;
        x = c.x;
    }
    // A steady approach still follows: never more than the hysteresis behind the target.
    for (float r = 88.0f; r > 72.0f; r -= 0.5f) {
        const GpuLodChoice c = lodSelect(p, r, 0.5f, x);
        EXPECT_LT(std::abs(c.x - lodCoordinate(p, r, 0.5f)), p.hysteresis + 1e-6f);
        x = c.x;
    }
    // Leaving the band onto the plateau of LOD 2 lands exactly on 2: nothing stays half-faded.
    const GpuLodChoice settled = lodSelect(p, 60.0f, 0.5f, 1.97f);
    EXPECT_EQ(settled.x, 2.0f);
    EXPECT_EQ(settled.fade, 0.0f);
    EXPECT_EQ(settled.lod, settled.fadeLod);
}

TEST(LodSelect, DitherMasksAreComplementary) {
    std::set<float> thresholds;
    for (uint y = 0; y < 4; ++y)
        for (uint x = 0; x < 4; ++x)
            thresholds.insert(lodDitherThreshold(x, y));
    EXPECT_EQ(thresholds.size(), 16u); // a full 4 x 4 ordered dither
    for (float fade : {0.0f, 0.1f, 0.5f, 0.77f, 1.0f}) {
        int fadeLodPixels = 0;
        for (uint y = 0; y < 8; ++y)
            for (uint x = 0; x < 8; ++x) {
                const bool a = lodDitherKeeps(false, fade, x, y), b = lodDitherKeeps(true, fade, x, y);
                EXPECT_NE(a, b) << "pixel " << x << "," << y << " fade " << fade; // exactly one draws it
                fadeLodPixels += b;
            }
        // The share of pixels drawn in the second LOD follows the fade, to one step of 1/16.
        EXPECT_NEAR(fadeLodPixels / 64.0f, fade, 1.0f / 16.0f + 1e-6f);
    }
}

// The dither as a whole level (what instance.vert passes to the fragment stage) keeps exactly the
// pixels the fade keeps, at every threshold and a float step either side of it.
TEST(LodSelect, DitherLevelKeepsWhatTheFadeKeeps) {
    std::vector<float> fades = {0.0f, 1e-8f, 0.5f, 0.999f, 1.0f};
    for (int i = 0; i < 16; ++i) {
        const float t = (float(i) + 0.5f) / 16.0f;
        fades.insert(fades.end(), {t, std::nextafter(t, 0.0f), std::nextafter(t, 1.0f)});
    }
    for (int i = 0; i <= 1000; ++i)
        fades.push_back(float(i) / 1000.0f);
    for (const float fade : fades) {
        const uint level = lodDitherLevel(fade);
        EXPECT_LE(level, 16u);
        for (uint y = 0; y < 4; ++y)
            for (uint x = 0; x < 4; ++x)
                for (bool isFadeLod : {false, true})
                    EXPECT_EQ(lodDitherKeepsLevel(isFadeLod, level, x + 4, y),
                              lodDitherKeeps(isFadeLod, fade, x + 4, y))
                        << "fade " << fade << " pixel " << x << "," << y;
    }
    EXPECT_EQ(lodDitherLevel(0.0f), 0u);
    EXPECT_EQ(lodDitherLevel(1.0f), 16u);
}
