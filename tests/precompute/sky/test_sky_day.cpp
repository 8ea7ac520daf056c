// A day of sky frames (precompute/sky/sky_day.h): layout, SH against the backdrop image,
// determinism, blending, parameter checks, and the full preset's build.
#include "sky/sky_day.h"
#include "sky/sun.h"

#include "core/error.h"
#include "light/latlong.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstring>

namespace meadow::sky {
namespace {

const SkyDay& ciDay() {
    static const SkyDay day = buildSkyDay(skyParamsForPreset("ci"));
    return day;
}

std::vector<glm::dvec3> coefficientsOf(const std::vector<float>& sh) {
    std::vector<glm::dvec3> c(sh.size() / 3);
    for (size_t i = 0; i < c.size(); ++i)
        c[i] = glm::dvec3(sh[i * 3], sh[i * 3 + 1], sh[i * 3 + 2]);
    return c;
}

// Solid-angle mean of a lat-long image.
glm::dvec3 imageMean(const std::vector<float>& image, uint32_t width, uint32_t height) {
    glm::dvec3 sum(0.0);
    for (uint32_t j = 0; j < height; ++j)
        for (uint32_t i = 0; i < width; ++i) {
            const float* t = &image[(size_t(j) * width + i) * 3];
            sum += glm::dvec3(t[0], t[1], t[2]) * latLongPixelSolidAngle(j, width, height);
        }
    return sum / (4.0 * M_PI);
}

TEST(SkyDay, PresetsAndLayout) {
    const SkyParams full = skyParamsForPreset("full"), ci = skyParamsForPreset("ci");
    EXPECT_GE(full.frames, 288u);
    EXPECT_LT(ci.frames, full.frames);
    EXPECT_THROW(skyParamsForPreset("huge"), Error);
    const SkyDay& day = ciDay();
    ASSERT_EQ(day.frames.size(), ci.frames);
    EXPECT_EQ(day.imageWidth, 2 * day.imageHeight);
    for (size_t i = 0; i < day.frames.size(); ++i) {
        const SkyFrame& f = day.frames[i];
        EXPECT_DOUBLE_EQ(f.hours, 24.0 * double(i) / double(day.frames.size()));
        EXPECT_EQ(f.sh.size(), size_t(sh::coefficientCount(day.shOrder)) * 3);
        EXPECT_EQ(f.image.size(), size_t(day.imageWidth) * day.imageHeight * 3);
        EXPECT_NEAR(glm::length(f.sunDirection), 1.0f, 1e-6f); // float storage of a unit vector
        for (float v : f.image)
            ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << "frame " << i;
        for (float v : f.sh)
            ASSERT_TRUE(std::isfinite(v)) << "frame " << i;
    }
}

TEST(SkyDay, ShMeanMatchesTheImageMean) {
    // c00 Y00 is the sphere's mean radiance; the image's solid-angle mean is the same integral
    // taken another way (2 x 2 points per pixel against 24 x 48 nodes on the sky). The sun is in
    // the SH (a delta of weight sunIrradiance adds sunIrradiance / 4 pi to the mean) but not in
    // the image, so it is taken out first. Tolerance 0.2 %: both rules resolve the smooth Perez
    // distribution far better than that (0.05 % measured); the circumsolar peak is what is left.
    const SkyDay& day = ciDay();
    const double y00 = 0.5 / std::sqrt(M_PI);
    for (const SkyFrame& f : day.frames) {
        const std::vector<glm::dvec3> c = coefficientsOf(f.sh);
        const glm::dvec3 mean = imageMean(f.image, day.imageWidth, day.imageHeight);
        const glm::dvec3 shMean = c[0] * y00 - glm::dvec3(f.sunIrradiance) / (4.0 * M_PI);
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(shMean[ch], mean[ch], 2e-3 * mean[ch] + 1e-12) << "hours " << f.hours << " channel " << ch;
    }
}

TEST(SkyDay, DaytimeLightComesFromAboveAndTheSunSide) {
    const SkyDay& day = ciDay();
    const SkyFrame& noon = day.frames[day.frames.size() / 2];
    ASSERT_DOUBLE_EQ(noon.hours, 12.0);
    const std::vector<glm::dvec3> c = coefficientsOf(noon.sh);
    // Band 1 ∝ (x, y, z): up-weighted and towards the south (-z) where the noon sun stands.
    EXPECT_GT(c[2].g, 0.0);
    EXPECT_LT(c[3].g, 0.0);
    // Irradiance on an upward surface at noon: units of sky/sun.h, sky and sun together on the
    // order of 10 (10^5 lx); and far less at midnight.
    const std::vector<glm::dvec3> e = sh::irradianceRgb(day.shOrder, c);
    const double up = luminance(sh::reconstructRgb(day.shOrder, e, {0, 1, 0}));
    EXPECT_GT(up, 6.0);
    EXPECT_LT(up, 16.0);
    const std::vector<glm::dvec3> night = sh::irradianceRgb(day.shOrder, coefficientsOf(day.frames[0].sh));
    EXPECT_LT(luminance(sh::reconstructRgb(day.shOrder, night, {0, 1, 0})), 1e-3 * up);
}

bool sameBytes(const SkyDay& a, const SkyDay& b) {
    if (a.frames.size() != b.frames.size() || a.shOrder != b.shOrder || a.imageWidth != b.imageWidth)
        return false;
    for (size_t i = 0; i < a.frames.size(); ++i) {
        const SkyFrame &x = a.frames[i], &y = b.frames[i];
        if (std::memcmp(&x.hours, &y.hours, sizeof x.hours) != 0 ||
            std::memcmp(&x.sunDirection, &y.sunDirection, sizeof x.sunDirection) != 0 ||
            std::memcmp(&x.sunRadiance, &y.sunRadiance, sizeof x.sunRadiance) != 0 ||
            std::memcmp(&x.sunIrradiance, &y.sunIrradiance, sizeof x.sunIrradiance) != 0 ||
            x.sh.size() != y.sh.size() || x.image.size() != y.image.size() ||
            std::memcmp(x.sh.data(), y.sh.data(), x.sh.size() * sizeof(float)) != 0 ||
            std::memcmp(x.image.data(), y.image.data(), x.image.size() * sizeof(float)) != 0)
            return false;
    }
    return true;
}

TEST(SkyDay, DeterministicForAnyThreadCount) {
    const SkyParams params = skyParamsForPreset("ci");
    const SkyDay again = buildSkyDay(params);
    EXPECT_TRUE(sameBytes(ciDay(), again));
    {
        tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
        EXPECT_TRUE(sameBytes(ciDay(), buildSkyDay(params)));
    }
    // ... and a frame built alone equals the same frame of the day.
    const SkyFrame alone = buildSkyFrame(params, ciDay().frames[17].hours);
    EXPECT_EQ(alone.sh, ciDay().frames[17].sh);
    EXPECT_EQ(alone.image, ciDay().frames[17].image);
    // Other inputs, other bytes (the comparison can fail).
    SkyParams hazy = params;
    hazy.daylight.turbidity = 6.0;
    EXPECT_FALSE(sameBytes(ciDay(), buildSkyDay(hazy)));
}

TEST(SkyBlend, ExactFrameTimesReturnThatFrame) {
    const SkyDay& day = ciDay();
    for (uint32_t i = 0; i < day.frames.size(); ++i) {
        const SkyBlend blend = skyBlendAt(day, day.frames[i].hours);
        EXPECT_EQ(blend.first, i);
        EXPECT_EQ(blend.weight, 0.0);
        EXPECT_EQ(blendSh(day, blend), day.frames[i].sh);
        // The same time a day later or earlier.
        EXPECT_EQ(shAt(day, day.frames[i].hours + 24.0), day.frames[i].sh);
        EXPECT_EQ(shAt(day, day.frames[i].hours - 48.0), day.frames[i].sh);
    }
}

TEST(SkyBlend, LinearBetweenFramesAndWrapsAtMidnight) {
    const SkyDay& day = ciDay();
    const double step = 24.0 / double(day.frames.size());
    const SkyBlend mid = skyBlendAt(day, 10.0 * step + 0.25 * step);
    EXPECT_EQ(mid.first, 10u);
    EXPECT_EQ(mid.second, 11u);
    EXPECT_NEAR(mid.weight, 0.25, 1e-12); // rounding of the time arithmetic
    // Across midnight: last frame to the first.
    const SkyBlend late = skyBlendAt(day, 24.0 - 0.5 * step);
    EXPECT_EQ(late.first, uint32_t(day.frames.size() - 1));
    EXPECT_EQ(late.second, 0u);
    EXPECT_NEAR(late.weight, 0.5, 1e-12);
    const std::vector<float> blended = blendSh(day, late);
    for (size_t k = 0; k < blended.size(); ++k) {
        const double expected = 0.5 * day.frames.back().sh[k] + 0.5 * day.frames[0].sh[k];
        EXPECT_NEAR(blended[k], expected, 1e-6 * (std::abs(expected) + 1e-6)); // float rounding
    }
}

TEST(SkyBlend, ContinuousInTime) {
    // Sweep the whole day in 10 s steps: between two samples the blended c00 moves by at most
    // its frame-to-frame change times the fraction of a frame step elapsed (plus float rounding),
    // i.e. no jump at frame boundaries or at midnight.
    const SkyDay& day = ciDay();
    const double step = 24.0 / double(day.frames.size()), dt = 10.0 / 3600.0;
    double largestFrameChange = 0.0;
    for (size_t i = 0; i < day.frames.size(); ++i)
        largestFrameChange = std::max(
            largestFrameChange, double(std::abs(day.frames[(i + 1) % day.frames.size()].sh[1] - day.frames[i].sh[1])));
    ASSERT_GT(largestFrameChange, 0.0);
    std::vector<float> previous = shAt(day, -dt);
    for (double t = 0.0; t <= 24.0 + dt; t += dt) {
        const std::vector<float> current = shAt(day, t);
        EXPECT_LE(std::abs(current[1] - previous[1]), largestFrameChange * (dt / step) * 1.001 + 1e-6) << t;
        previous = current;
    }
}

TEST(SkyDay, RejectsMeaninglessParameters) {
    const auto expectError = [](SkyParams params, const std::string& fragment) {
        try {
            buildSkyDay(params);
            ADD_FAILURE() << "no error for " << fragment;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
        }
    };
    SkyParams p = skyParamsForPreset("ci");
    p.latitudeDegrees = 95.0;
    expectError(p, "sky: latitude is 95");
    p = skyParamsForPreset("ci");
    p.daylight.turbidity = 12.0;
    expectError(p, "sky: turbidity is 12; Preetham");
    p = skyParamsForPreset("ci");
    p.imageWidth = 64;
    p.imageHeight = 64;
    expectError(p, "sky: the image size is 64x64");
    p = skyParamsForPreset("ci");
    p.frames = 0;
    expectError(p, "frame count");
    p = skyParamsForPreset("ci");
    p.shOrder = sh::kMaxOrder + 1;
    expectError(p, "SH order");
    p = skyParamsForPreset("ci");
    p.dayOfYear = 0.0;
    expectError(p, "day of year is 0");
    p = skyParamsForPreset("ci");
    p.daylight.nightLuminance = std::nan("");
    expectError(p, "night luminance is nan");
    p = skyParamsForPreset("ci");
    p.daylight.groundAlbedo = -0.1;
    expectError(p, "ground albedo is -0.1");
}

TEST(SkyDay, FullPresetBuildsEveryFiveMinutes) {
    // Timing is reported, never asserted (docs/BENCHMARKS.md).
    const SkyParams params = skyParamsForPreset("full");
    const auto start = std::chrono::steady_clock::now();
    const SkyDay day = buildSkyDay(params);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    RecordProperty("full_preset_build_ms", std::to_string(int(seconds * 1000.0)));
    std::printf("full preset sky day (%u frames, %ux%u, order %d): %.3f s\n", params.frames, params.imageWidth,
                params.imageHeight, params.shOrder, seconds);
    ASSERT_EQ(day.frames.size(), 288u);
    EXPECT_DOUBLE_EQ(day.frames[1].hours - day.frames[0].hours, 5.0 / 60.0);
    // Higher orders work too (the sky is smooth; its band energy falls off).
    SkyParams order5 = skyParamsForPreset("ci");
    order5.shOrder = 5;
    const SkyFrame frame = buildSkyFrame(order5, 12.0);
    EXPECT_EQ(frame.sh.size(), size_t(25 * 3));
}

} // namespace
} // namespace meadow::sky
