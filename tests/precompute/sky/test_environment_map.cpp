// HDR environment maps in place of the analytic sky (precompute/sky/environment_map.h). The
// panoramas, good and bad, are written at test time into a temporary folder.
#include "sky/environment_map.h"
#include "sky/sun.h"

#include "core/error.h"
#include "light/latlong.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <limits>

namespace meadow::sky {
namespace {

// Each test writes into its own folder, removed when it ends (ctest runs tests one per process).
std::filesystem::path scratch;

class SkyMap : public ::testing::Test {
  protected:
    void SetUp() override {
        scratch =
            std::filesystem::temp_directory_path() / ("meadow-sky-test-" + std::to_string(getpid()) + "-" +
                                                      ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::create_directories(scratch);
    }
    void TearDown() override { std::filesystem::remove_all(scratch); }
};

std::filesystem::path scratchDir() {
    return scratch;
}

// Writes a float image through OpenImageIO; the extension picks the format (.exr, .hdr).
std::filesystem::path writeImage(const std::string& name, int width, int height, int channels,
                                 const std::function<float(int x, int y, int c)>& texel) {
    const std::filesystem::path path = scratchDir() / name;
    std::vector<float> pixels(size_t(width) * size_t(height) * size_t(channels));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < channels; ++c)
                pixels[(size_t(y) * size_t(width) + size_t(x)) * size_t(channels) + size_t(c)] = texel(x, y, c);
    auto out = OIIO::ImageOutput::create(path.string());
    EXPECT_TRUE(out) << OIIO::geterror();
    const OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
    EXPECT_TRUE(out->open(path.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) &&
                out->close())
        << out->geterror();
    return path;
}

const float kConstant[3] = {0.5f, 1.0f, 2.0f}; // exact in half, float and RGBE

std::filesystem::path constantMap(const std::string& name, int width = 64, int height = 32, int channels = 3) {
    return writeImage(name, width, height, channels, [](int, int, int c) { return c < 3 ? kConstant[c] : 1.0f; });
}

void expectLoadError(const std::filesystem::path& path, const std::string& problem) {
    try {
        loadEnvironmentMap(path);
        ADD_FAILURE() << "no error for " << path;
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("sky map " + path.string() + ": "), std::string::npos) << message;
        EXPECT_NE(message.find(problem), std::string::npos) << message;
    }
}

TEST_F(SkyMap, AcceptsExrAndHdrPanoramas) {
    for (const char* name : {"good.exr", "good.hdr"}) {
        const EnvironmentMap map = loadEnvironmentMap(constantMap(name));
        EXPECT_EQ(map.width, 64u);
        EXPECT_EQ(map.height, 32u);
        ASSERT_EQ(map.rgb.size(), size_t(64 * 32 * 3));
        for (size_t k = 0; k < map.rgb.size(); ++k)
            ASSERT_EQ(map.rgb[k], kConstant[k % 3]) << name; // the values are exact in both formats
        // A constant sky projects to c00 = 2 sqrt(pi) times its radiance; tolerance: float output.
        const SkyFrame frame = environmentFrame(map, 9.0, 3, 16, 8);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(frame.sh[size_t(c)], 2.0 * std::sqrt(M_PI) * kConstant[c], 1e-5) << name;
            for (size_t i = 1; i < 9; ++i)
                EXPECT_NEAR(frame.sh[i * 3 + size_t(c)], 0.0, 1e-5) << name << " coefficient " << i;
        }
        EXPECT_EQ(frame.hours, 9.0);
        EXPECT_EQ(frame.sunIrradiance, glm::vec3(0.0f));
        EXPECT_EQ(frame.sunDirection, glm::vec3(0.0f, 1.0f, 0.0f)); // no dominant direction
        ASSERT_EQ(frame.image.size(), size_t(16 * 8 * 3));
        for (size_t k = 0; k < frame.image.size(); ++k)
            EXPECT_NEAR(frame.image[k], kConstant[k % 3], 1e-6); // a weighted mean of equal values
    }
    // RGBA: the first three channels are the radiance.
    const EnvironmentMap rgba = loadEnvironmentMap(constantMap("rgba.exr", 8, 4, 4));
    EXPECT_EQ(rgba.rgb[0], 0.5f);
    EXPECT_EQ(rgba.rgb[2], 2.0f);
}

TEST_F(SkyMap, RejectsEachBadCaseWithItsReason) {
    expectLoadError(scratchDir() / "missing.exr", "no such file");
    expectLoadError(scratchDir(), "is a folder");
    const std::filesystem::path garbage = scratchDir() / "garbage.exr";
    std::ofstream(garbage) << "this is not an OpenEXR file, only some text long enough to be read";
    expectLoadError(garbage, "cannot read it as an image");
    expectLoadError(constantMap("wide.exr", 96, 32), "96 x 32 is not a 2:1 latitude-longitude panorama");
    expectLoadError(constantMap("square.hdr", 32, 32), "32 x 32 is not a 2:1 latitude-longitude panorama");
    expectLoadError(constantMap("two_channels.exr", 16, 8, 2), "has 2 channel(s); an RGB panorama needs at least 3");
    expectLoadError(constantMap("grey.exr", 16, 8, 1), "has 1 channel(s)");
    const auto poisoned = [](const std::string& name, float value) {
        return writeImage(name, 16, 8, 3,
                          [value](int x, int y, int c) { return x == 3 && y == 2 && c == 1 ? value : 1.0f; });
    };
    expectLoadError(poisoned("nan.exr", std::numeric_limits<float>::quiet_NaN()),
                    "texel (3, 2) channel 1 is not finite");
    expectLoadError(poisoned("inf.exr", std::numeric_limits<float>::infinity()),
                    "texel (3, 2) channel 1 is not finite");
    expectLoadError(poisoned("negative.exr", -1.5f), "texel (3, 2) channel 1 is negative (-1.5)");
}

TEST_F(SkyMap, ResamplingConservesTheSphereIntegral) {
    // A map with structure: radiance rising towards the zenith and a bright patch in the east.
    const uint32_t w = 96, h = 48;
    std::vector<float> src(size_t(w) * h * 3);
    for (uint32_t j = 0; j < h; ++j)
        for (uint32_t i = 0; i < w; ++i)
            for (int c = 0; c < 3; ++c)
                src[(size_t(j) * w + i) * 3 + size_t(c)] =
                    float(1.0 + std::cos(M_PI * (j + 0.5) / h) + (i / 8 == 3 && j / 8 == 2 ? 10.0 : 0.0) + 0.1 * c);
    const auto mean = [](const std::vector<float>& image, uint32_t width, uint32_t height) {
        glm::dvec3 sum(0.0);
        for (uint32_t j = 0; j < height; ++j)
            for (uint32_t i = 0; i < width; ++i)
                for (int c = 0; c < 3; ++c)
                    sum[c] += image[(size_t(j) * width + i) * 3 + size_t(c)] * latLongPixelSolidAngle(j, width, height);
        return sum / (4.0 * M_PI);
    };
    const glm::dvec3 before = mean(src, w, h);
    // Divisible, non-divisible and upsampling sizes: the box filter weights partial overlaps by
    // their exact solid angle, so the integral is kept to float rounding.
    for (auto [dw, dh] : {std::pair<uint32_t, uint32_t>{16, 8}, {10, 5}, {2, 1}, {200, 100}}) {
        const std::vector<float> dst = resampleLatLong(w, h, src, dw, dh);
        const glm::dvec3 after = mean(dst, dw, dh);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(after[c], before[c], 1e-6 * before[c]) << dw << "x" << dh;
    }
}

TEST_F(SkyMap, DominantLightGivesTheSunDirection) {
    // A dim sky with a bright patch a quarter across at the horizon: east, +x.
    const std::filesystem::path path = writeImage("east.exr", 64, 32, 3, [](int x, int y, int) {
        return (x == 15 || x == 16) && (y == 15 || y == 16) ? 100.0f : 0.1f;
    });
    const SkyFrame frame = environmentFrame(loadEnvironmentMap(path), 0.0, 3, 64, 32);
    EXPECT_GT(frame.sunDirection.x, 0.999f); // the patch is symmetric about east
}

TEST_F(SkyMap, SequenceSpreadsOverTheDay) {
    const std::vector<std::filesystem::path> files = {
        writeImage("seq0.exr", 32, 16, 3, [](int, int, int) { return 1.0f; }),
        writeImage("seq1.exr", 32, 16, 3, [](int, int, int) { return 3.0f; }),
        writeImage("seq2.hdr", 32, 16, 3, [](int, int, int) { return 2.0f; })};
    SkyParams params = skyParamsForPreset("ci");
    const SkyDay day = buildEnvironmentDay(files, params);
    ASSERT_EQ(day.frames.size(), 3u);
    EXPECT_EQ(day.frames[1].hours, 8.0);
    EXPECT_EQ(day.frames[2].hours, 16.0);
    EXPECT_EQ(day.frames[0].image.size(), size_t(params.imageWidth) * params.imageHeight * 3);
    // Halfway between the first two maps (4 h) and across midnight (20 h, between the last and
    // the first). Tolerance: float SH of exact texels.
    const double c00 = 2.0 * std::sqrt(M_PI);
    EXPECT_NEAR(shAt(day, 4.0)[0], c00 * 2.0, 1e-5);
    EXPECT_NEAR(shAt(day, 20.0)[0], c00 * 1.5, 1e-5);

    EXPECT_THROW(buildEnvironmentDay({}, params), Error);
    // The first bad file of a sequence is the one named.
    const std::vector<std::filesystem::path> withBad = {files[0], scratchDir() / "absent.hdr", files[1]};
    try {
        buildEnvironmentDay(withBad, params);
        ADD_FAILURE() << "a sequence with a missing file was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("absent.hdr: no such file"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace meadow::sky
