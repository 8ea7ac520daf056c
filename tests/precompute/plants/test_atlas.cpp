// The iris texture atlas (precompute/plants/atlas.h): determinism, layout, colours, and the
// round trip through OpenImageIO.
#include "core/error.h"
#include "library/mesh.h"
#include "plants/atlas.h"
#include "scratch_dir.h"

#include <OpenImageIO/imageio.h>
#include <filesystem>
#include <gtest/gtest.h>

namespace meadow {
namespace {

constexpr PartKind kParts[] = {PartKind::Leaf,     PartKind::Stem,     PartKind::Fall,
                               PartKind::Standard, PartKind::StyleArm, PartKind::Other};

const TextureAtlas& atlas() {
    static const TextureAtlas a = makeIrisAtlas(256, 11);
    return a;
}

// The sRGB colour at a part's local (u across, v along) coordinates, nearest texel.
glm::vec3 colourAt(const TextureAtlas& a, PartKind part, float u, float v) {
    glm::vec2 uv = a.region(part).map(glm::vec2(u, v));
    uint32_t x = std::min(static_cast<uint32_t>(uv.x * static_cast<float>(a.width)), a.width - 1);
    uint32_t y = std::min(static_cast<uint32_t>(uv.y * static_cast<float>(a.height)), a.height - 1);
    const uint8_t* p = &a.rgba[(static_cast<size_t>(y) * a.width + x) * 4];
    return glm::vec3(p[0], p[1], p[2]);
}

// Mean sRGB colour over a part's whole region.
glm::vec3 meanColour(const TextureAtlas& a, PartKind part) {
    glm::vec3 sum(0.0f);
    int n = 0;
    for (float v = 0.02f; v < 1.0f; v += 0.04f)
        for (float u = 0.02f; u < 1.0f; u += 0.04f, ++n)
            sum += colourAt(a, part, u, v);
    return sum / static_cast<float>(n);
}

TEST(Atlas, SameSeedSameBytesOtherSeedOtherBytes) {
    TextureAtlas again = makeIrisAtlas(256, 11);
    EXPECT_EQ(again.rgba, atlas().rgba);
    EXPECT_NE(makeIrisAtlas(256, 12).rgba, atlas().rgba);
    EXPECT_EQ(atlas().rgba.size(), 256u * 256u * 4u);
}

TEST(Atlas, RejectsBadSizes) {
    EXPECT_THROW(makeIrisAtlas(100, 1), Error);
    EXPECT_THROW(makeIrisAtlas(32, 1), Error);
}

TEST(Atlas, RegionsAreInsideAndDisjoint) {
    for (PartKind a : kParts) {
        AtlasRegion ra = irisAtlasRegion(a);
        EXPECT_GE(ra.min.x, 0.0f);
        EXPECT_GE(ra.min.y, 0.0f);
        EXPECT_LE(ra.max.x, 1.0f);
        EXPECT_LE(ra.max.y, 1.0f);
        EXPECT_LT(ra.min.x, ra.max.x);
        EXPECT_LT(ra.min.y, ra.max.y);
        for (PartKind b : kParts) {
            if (a == b)
                continue;
            AtlasRegion rb = irisAtlasRegion(b);
            bool overlap = ra.min.x < rb.max.x && rb.min.x < ra.max.x && ra.min.y < rb.max.y && rb.min.y < ra.max.y;
            EXPECT_FALSE(overlap) << static_cast<int>(a) << " and " << static_cast<int>(b);
        }
    }
}

TEST(Atlas, OpaqueEverywhere) {
    for (size_t i = 3; i < atlas().rgba.size(); i += 4)
        ASSERT_EQ(atlas().rgba[i], 255) << "texel " << i / 4;
}

// The part whose cell holds mip-0 texel (x, y): the region that, widened by its inset of 1/128 of
// the atlas, holds the texel's centre; -1 for none.
int cellOf(const TextureAtlas& a, uint32_t x, uint32_t y) {
    const glm::vec2 uv((float(x) + 0.5f) / float(a.width), (float(y) + 0.5f) / float(a.height));
    for (int i = 0; i < int(std::size(kParts)); ++i) {
        const AtlasRegion r = a.region(kParts[i]);
        if (uv.x >= r.min.x - 1.0f / 128.0f && uv.x <= r.max.x + 1.0f / 128.0f && uv.y >= r.min.y - 1.0f / 128.0f &&
            uv.y <= r.max.y + 1.0f / 128.0f)
            return i;
    }
    return -1;
}

// Whether mip level `level` (2 x 2 boxes down from the atlas) keeps the parts apart under trilinear
// filtering: each of its texels averages one cell's texels, and the regions' inset is at least half
// a texel of the level, so bilinear reads inside a region stay in its cell.
bool levelKeepsPartsApart(const TextureAtlas& a, uint32_t level) {
    const uint32_t block = 1u << level;
    for (uint32_t by = 0; by < a.height / block; ++by)
        for (uint32_t bx = 0; bx < a.width / block; ++bx) {
            const int cell = cellOf(a, bx * block, by * block);
            for (uint32_t y = by * block; y < (by + 1) * block; ++y)
                for (uint32_t x = bx * block; x < (bx + 1) * block; ++x)
                    if (cellOf(a, x, y) != cell)
                        return false;
        }
    return float(a.width) / 128.0f / float(block) >= 0.5f;
}

// The run time reads the atlas's mipmaps down to atlasMaxLod (library/mesh.h), where the parts
// still keep their own colours, and no coarser: the next level would mix them.
TEST(Atlas, MipLevelsTheRunTimeReadsKeepThePartsApart) {
    for (uint32_t size : {256u, 1024u}) {
        const TextureAtlas a = makeIrisAtlas(size, 11);
        const uint32_t last = uint32_t(atlasMaxLod(size));
        for (uint32_t level = 0; level <= last; ++level)
            EXPECT_TRUE(levelKeepsPartsApart(a, level)) << size << " " << level;
        EXPECT_FALSE(levelKeepsPartsApart(a, last + 1)) << size;
    }
    EXPECT_EQ(atlasMaxLod(256), 2.0f);
}

TEST(Atlas, PartsHaveTheirColours) {
    // Leaves and stems are green; the leaf tip is lighter than its base.
    glm::vec3 leaf = meanColour(atlas(), PartKind::Leaf);
    EXPECT_GT(leaf.g, leaf.r);
    EXPECT_GT(glm::dot(colourAt(atlas(), PartKind::Leaf, 0.3f, 0.85f), glm::vec3(1.0f)),
              glm::dot(colourAt(atlas(), PartKind::Leaf, 0.3f, 0.1f), glm::vec3(1.0f)));
    glm::vec3 stem = meanColour(atlas(), PartKind::Stem);
    EXPECT_GT(stem.g, stem.r);
    EXPECT_GT(stem.g, stem.b);
    // Falls and standards are violet-blue (blue above green), standards lighter than falls.
    glm::vec3 fall = colourAt(atlas(), PartKind::Fall, 0.3f, 0.75f);
    glm::vec3 standard = colourAt(atlas(), PartKind::Standard, 0.3f, 0.6f);
    EXPECT_GT(fall.b, fall.g + 30.0f);
    EXPECT_GT(standard.b, standard.g + 30.0f);
    EXPECT_GT(glm::dot(meanColour(atlas(), PartKind::Standard), glm::vec3(1.0f)),
              glm::dot(meanColour(atlas(), PartKind::Fall), glm::vec3(1.0f)));
    // The beard down the fall's haft is yellow-orange.
    glm::vec3 beard = colourAt(atlas(), PartKind::Fall, 0.5f, 0.25f);
    EXPECT_GT(beard.r, 180.0f);
    EXPECT_GT(beard.r, beard.b + 80.0f);
    EXPECT_GT(beard.g, beard.b + 40.0f);
}

TEST(Atlas, WritesAPngThatReadsBack) {
    const test::ScratchDir scratch("meadow-plants-test");
    const std::filesystem::path& dir = scratch.path();
    auto path = dir / "atlas.png";
    writeAtlas(path, atlas());
    auto in = OIIO::ImageInput::open(path.string());
    ASSERT_TRUE(in) << OIIO::geterror();
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.width, 256);
    EXPECT_EQ(spec.height, 256);
    ASSERT_EQ(spec.nchannels, 4);
    std::vector<uint8_t> pixels(atlas().rgba.size());
    ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, pixels.data()));
    in->close();
    EXPECT_EQ(pixels, atlas().rgba);
    // Only the finished file is left behind: the temporary was renamed.
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);
}

TEST(Atlas, UnwritablePathNamesTheFile) {
    try {
        writeAtlas("/nonexistent-meadow-dir/atlas.png", atlas());
        FAIL() << "writing into a missing folder succeeded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent-meadow-dir/atlas.png"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace meadow
