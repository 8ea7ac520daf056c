#include "core/error.h"
#include "io/image_io.h"

#include <OpenImageIO/imagebuf.h>
#include <filesystem>
#include <gtest/gtest.h>

using namespace meadow;

TEST(ImageIo, KindsAndFrameNames) {
    EXPECT_EQ(imageKindForPath("a/b.PNG"), ImageFileKind::Png);
    EXPECT_EQ(imageKindForPath("b.exr"), ImageFileKind::Exr);
    EXPECT_THROW(imageKindForPath("b.jpg"), Error);
    EXPECT_THROW(imageKindForPath("noext"), Error);
    EXPECT_EQ(framePath("out/f.png", 0, 1), "out/f.png");
    EXPECT_EQ(framePath("out/f.png", 3, 10), "out/f.0003.png");
}

TEST(ImageIo, UnwritableOutputsAreRejectedUpFront) {
    EXPECT_THROW(checkOutputWritable("/nonexistent-dir/x.png"), Error);
    EXPECT_THROW(checkOutputWritable(std::filesystem::temp_directory_path()), Error); // a folder
    EXPECT_NO_THROW(checkOutputWritable(std::filesystem::temp_directory_path() / "x.png"));
}

TEST(ImageIo, WritesWholeFilesThatReadBack) {
    auto dir = std::filesystem::temp_directory_path() / "meadow-unit-images";
    std::filesystem::create_directories(dir);
    std::vector<uint8_t> rgba(4 * 3 * 2);
    for (size_t i = 0; i < rgba.size(); ++i)
        rgba[i] = i % 4 == 3 ? 255 : uint8_t(i * 10); // frames are opaque
    writeRgba8(dir / "t.png", 3, 2, rgba);
    OIIO::ImageBuf buf((dir / "t.png").string());
    ASSERT_TRUE(buf.read());
    EXPECT_EQ(buf.spec().width, 3);
    EXPECT_EQ(buf.spec().height, 2);
    EXPECT_NEAR(buf.getchannel(1, 0, 0, 2), (4 + 2) * 10 / 255.0, 1e-6);
    std::vector<uint16_t> half(4 * 2 * 2, 0x3c00); // 1.0 in IEEE half
    writeRgbaHalf(dir / "t.exr", 2, 2, half);
    OIIO::ImageBuf exr((dir / "t.exr").string());
    ASSERT_TRUE(exr.read());
    EXPECT_FLOAT_EQ(exr.getchannel(1, 1, 0, 0), 1.0f);
    // No temporary files are left behind.
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos) << entry.path();
}
