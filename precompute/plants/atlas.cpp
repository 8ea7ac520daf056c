#include "atlas.h"

#include "core/error.h"
#include "core/random.h"

#include <OpenImageIO/imageio.h>
#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <unistd.h>

namespace meadow {
namespace {

// Each part's cell, in eighths of the atlas. Leaves and stems are long and thin, so their cells
// run the full height; the broad falls get the largest square.
struct Cell {
    PartKind part;
    float x0, y0, x1, y1;
};
constexpr Cell kCells[kPartKindCount] = {
    {PartKind::Leaf, 0, 0, 3, 8},     {PartKind::Stem, 3, 0, 4, 8},     {PartKind::Fall, 4, 0, 8, 4},
    {PartKind::Standard, 4, 4, 6, 8}, {PartKind::StyleArm, 6, 4, 7, 8}, {PartKind::Other, 7, 4, 8, 8},
};
// The region sits this far (UV) inside its cell; the gap is painted with the region's edge
// colours so filtering and the first mip levels stay within the part.
constexpr float kInset = 1.0f / 128.0f; // library/mesh.h, kAtlasGrid

const Cell& cellOf(PartKind part) {
    return kCells[static_cast<uint32_t>(part)];
}

// sRGB-encoded 0xRRGGBB to linear colour, so blends happen in linear light.
glm::vec3 srgb(uint32_t hex) {
    return {srgbToLinear(uint8_t(hex >> 16)), srgbToLinear(uint8_t(hex >> 8)), srgbToLinear(uint8_t(hex))};
}

uint8_t encodeSrgb(float linear) {
    return linearToSrgb(linear);
}

float smoothStep(float edge0, float edge1, float x) {
    float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// Value noise on an integer lattice hashed with SplitMix64: the same on every machine.
class Noise {
  public:
    explicit Noise(uint64_t seed) : seed_(splitMix64(seed)) {}
    float lattice(int64_t x, int64_t y) const {
        uint64_t h = splitMix64(seed_ ^ (static_cast<uint64_t>(x) * 0x9e3779b97f4a7c15ull) ^
                                (static_cast<uint64_t>(y) * 0xc2b2ae3d27d4eb4full));
        return static_cast<float>(h >> 40) * (1.0f / 16777216.0f);
    }
    // Smoothly interpolated, in [0, 1).
    float value(float x, float y) const {
        float fx = std::floor(x), fy = std::floor(y);
        auto ix = static_cast<int64_t>(fx), iy = static_cast<int64_t>(fy);
        float tx = x - fx, ty = y - fy;
        tx = tx * tx * (3.0f - 2.0f * tx);
        ty = ty * ty * (3.0f - 2.0f * ty);
        float a = lattice(ix, iy), b = lattice(ix + 1, iy), c = lattice(ix, iy + 1), d = lattice(ix + 1, iy + 1);
        return (a + (b - a) * tx) + ((c + (d - c) * tx) - (a + (b - a) * tx)) * ty;
    }
    // Three octaves, in [0, 1).
    float fbm(float x, float y) const {
        return (value(x, y) * 4.0f + value(2.03f * x, 2.03f * y) * 2.0f + value(4.07f * x, 4.07f * y)) / 7.0f;
    }

  private:
    uint64_t seed_;
};

// Parallel veins: thin dark lines `count` across the unit interval.
float parallelVeins(float u, float count, float sharpness) {
    float c = 0.5f + 0.5f * std::cos(2.0f * glm::pi<float>() * u * count);
    return std::pow(c, sharpness);
}

// Veins fanning out from a point below the petal's base, as in iris falls and standards.
float radialVeins(float u, float v, float count, float sharpness, float wobble) {
    float angle = std::atan2(u - 0.5f, v + 0.18f) + wobble;
    return parallelVeins(angle / glm::pi<float>(), count, sharpness);
}

struct Painter {
    Noise noise;
    Noise detail;
    float hueShift; // a per-seed nudge of the petal violet, so seeds differ visibly

    glm::vec3 leaf(float u, float v) const {
        // Darker at the clasping base, lighter and bluer (glaucous) towards the tip.
        glm::vec3 colour = glm::mix(srgb(0x3e5f3a), srgb(0x5d8a72), smoothStep(0.0f, 0.35f, v));
        colour = glm::mix(colour, srgb(0x86a99a), smoothStep(0.35f, 1.0f, v));
        colour = glm::mix(colour, srgb(0x7a6072), 0.55f * (1.0f - smoothStep(0.0f, 0.06f, v)));
        float veins = parallelVeins(u, 28.0f, 10.0f);
        colour *= 1.0f - 0.14f * veins;
        colour *= 1.0f + 0.12f * std::exp(-(u - 0.5f) * (u - 0.5f) / 0.0003f);
        colour = glm::mix(colour, srgb(0x9aac6a), 0.25f * smoothStep(0.42f, 0.5f, std::abs(u - 0.5f)));
        colour = glm::mix(colour, srgb(0x9c8656), 0.6f * smoothStep(0.93f, 1.0f, v));
        colour *= 0.92f + 0.16f * noise.fbm(u * 6.0f, v * 40.0f);
        return colour;
    }
    glm::vec3 stem(float u, float v) const {
        glm::vec3 colour = glm::mix(srgb(0x52703e), srgb(0x6e9460), smoothStep(0.0f, 0.5f, v));
        colour = glm::mix(colour, srgb(0x6e5866), 0.4f * (1.0f - smoothStep(0.0f, 0.05f, v)));
        colour *= 1.0f - 0.1f * parallelVeins(u, 10.0f, 6.0f);
        colour *= 0.92f + 0.16f * noise.fbm(u * 10.0f + 31.0f, v * 80.0f);
        return colour;
    }
    glm::vec3 fall(float u, float v) const {
        float d = std::abs(u - 0.5f) * 2.0f;
        glm::vec3 blade = glm::mix(srgb(0x43207e), srgb(0x6a46b2), smoothStep(0.2f, 1.0f, d));
        blade = glm::mix(blade, srgb(0x3b1d75), 0.3f * smoothStep(0.5f, 1.0f, v));
        blade = hue(blade);
        // The haft is pale with dense brown-violet veining (the "signal").
        glm::vec3 haft = srgb(0xeee4cc);
        float haftMix = 1.0f - smoothStep(0.18f, 0.42f, v);
        glm::vec3 colour = glm::mix(blade, haft, haftMix);
        float wobble = 0.03f * (noise.value(u * 8.0f, v * 8.0f) - 0.5f);
        float veins = radialVeins(u, v, 22.0f, 6.0f, wobble);
        float veinStrength = glm::mix(0.35f, 0.85f, haftMix) * (1.0f - 0.6f * smoothStep(0.6f, 1.0f, v));
        colour = glm::mix(colour, hue(srgb(0x2a0f4e)), veinStrength * veins);
        colour *= 0.9f + 0.2f * noise.fbm(u * 12.0f, v * 12.0f);
        // The beard: a strip of yellow-orange hairs down the haft's midline.
        float beardHalfWidth = 0.085f * (1.0f - 0.5f * smoothStep(0.25f, 0.5f, v));
        float hairs = detail.value(u * 180.0f, v * 40.0f);
        float edge = beardHalfWidth * (0.8f + 0.4f * detail.value(u * 40.0f + 7.0f, v * 90.0f));
        float beard = (1.0f - smoothStep(edge * 0.7f, edge, std::abs(u - 0.5f))) * smoothStep(0.03f, 0.07f, v) *
                      (1.0f - smoothStep(0.42f, 0.5f, v));
        glm::vec3 beardColour = glm::mix(srgb(0xe27a10), srgb(0xffd23c), hairs);
        beardColour = glm::mix(beardColour, srgb(0xfff0b0), 0.25f * smoothStep(0.3f, 0.45f, v));
        return glm::mix(colour, beardColour, beard);
    }
    glm::vec3 standard(float u, float v) const {
        float d = std::abs(u - 0.5f) * 2.0f;
        glm::vec3 colour = hue(glm::mix(srgb(0x8a78d0), srgb(0xb4a8ea), smoothStep(0.3f, 1.0f, d)));
        colour = glm::mix(colour, srgb(0xe6dcb8), 0.8f * (1.0f - smoothStep(0.05f, 0.2f, v)));
        float veins = radialVeins(u, v, 18.0f, 5.0f, 0.03f * (noise.value(u * 6.0f + 3.0f, v * 6.0f) - 0.5f));
        colour = glm::mix(colour, hue(srgb(0x5a44a6)), 0.25f * veins * (1.0f - smoothStep(0.5f, 1.0f, v)));
        colour *= 0.92f + 0.16f * noise.fbm(u * 10.0f + 50.0f, v * 10.0f);
        return colour;
    }
    glm::vec3 styleArm(float u, float v) const {
        glm::vec3 colour = hue(srgb(0xb6a6e2));
        colour = glm::mix(colour, hue(srgb(0x7a66c0)), 0.6f * std::exp(-(u - 0.5f) * (u - 0.5f) / 0.01f));
        colour = glm::mix(colour, srgb(0xd8d0f0), 0.5f * smoothStep(0.75f, 1.0f, v));
        colour *= 0.94f + 0.12f * noise.fbm(u * 8.0f + 90.0f, v * 8.0f);
        return colour;
    }
    glm::vec3 other(float u, float v) const {
        return srgb(0x5a7a48) * (0.9f + 0.2f * noise.fbm(u * 8.0f + 120.0f, v * 8.0f));
    }
    glm::vec3 hue(glm::vec3 c) const {
        // Moves the violet between bluer and redder by trading red against blue.
        return glm::vec3(c.r * (1.0f + hueShift), c.g, c.b * (1.0f - 0.5f * hueShift));
    }
    glm::vec3 paint(PartKind part, float u, float v) const {
        switch (part) {
        case PartKind::Leaf: return leaf(u, v);
        case PartKind::Stem: return stem(u, v);
        case PartKind::Fall: return fall(u, v);
        case PartKind::Standard: return standard(u, v);
        case PartKind::StyleArm: return styleArm(u, v);
        case PartKind::Other: return other(u, v);
        }
        return glm::vec3(0.0f);
    }
};

} // namespace

AtlasCell importAtlasCell(uint32_t size) {
    const Cell& cell = cellOf(PartKind::Fall);
    auto at = [&](float eighths) { return static_cast<uint32_t>(eighths / 8.0f * static_cast<float>(size)); };
    return AtlasCell{at(cell.x0), at(cell.y0), at(cell.x1), at(cell.y1)};
}

AtlasRegion irisAtlasRegion(PartKind part) {
    const Cell& cell = cellOf(part);
    return AtlasRegion{glm::vec2(cell.x0, cell.y0) / 8.0f + kInset, glm::vec2(cell.x1, cell.y1) / 8.0f - kInset};
}

TextureAtlas makeIrisAtlas(uint32_t size, uint64_t seed) {
    if (size < 64 || size > 8192 || (size & (size - 1)) != 0)
        throw Error("atlas size " + std::to_string(size) + " is not a power of two from 64 to 8192");
    Random rng(splitMix64(seed ^ 0xa71a5ull));
    Painter painter{Noise(rng.next()), Noise(rng.next()), rng.uniform(-0.25f, 0.25f)};
    TextureAtlas atlas;
    atlas.width = size;
    atlas.height = size;
    atlas.rgba.assign(static_cast<size_t>(size) * size * 4, 255);
    float texel = 1.0f / static_cast<float>(size);
    for (const Cell& cell : kCells) {
        AtlasRegion region = irisAtlasRegion(cell.part);
        uint32_t x0 = static_cast<uint32_t>(cell.x0 / 8.0f * static_cast<float>(size));
        uint32_t x1 = static_cast<uint32_t>(cell.x1 / 8.0f * static_cast<float>(size));
        uint32_t y0 = static_cast<uint32_t>(cell.y0 / 8.0f * static_cast<float>(size));
        uint32_t y1 = static_cast<uint32_t>(cell.y1 / 8.0f * static_cast<float>(size));
        for (uint32_t y = y0; y < y1; ++y) {
            for (uint32_t x = x0; x < x1; ++x) {
                // Texel centres outside the region take the colour of its nearest edge.
                glm::vec2 uv((static_cast<float>(x) + 0.5f) * texel, (static_cast<float>(y) + 0.5f) * texel);
                glm::vec2 local = glm::clamp((uv - region.min) / (region.max - region.min), 0.0f, 1.0f);
                glm::vec3 colour = painter.paint(cell.part, local.x, local.y);
                uint8_t* pixel = &atlas.rgba[(static_cast<size_t>(y) * size + x) * 4];
                pixel[0] = encodeSrgb(colour.r);
                pixel[1] = encodeSrgb(colour.g);
                pixel[2] = encodeSrgb(colour.b);
                pixel[3] = 255;
            }
        }
    }
    return atlas;
}

void writeAtlas(const std::filesystem::path& path, const TextureAtlas& atlas) {
    if (atlas.rgba.size() != static_cast<size_t>(atlas.width) * atlas.height * 4 || atlas.width == 0)
        throw Error("cannot write atlas " + path.string() + ": the atlas has no or inconsistent pixels");
    // Keep the extension so OpenImageIO picks the same format for the temporary file.
    std::filesystem::path tmp = path;
    tmp.replace_filename("." + path.stem().string() + ".partial-" + std::to_string(getpid()) +
                         path.extension().string());
    auto out = OIIO::ImageOutput::create(tmp.string());
    if (!out)
        throw Error("cannot write atlas " + path.string() + ": " + OIIO::geterror());
    OIIO::ImageSpec spec(static_cast<int>(atlas.width), static_cast<int>(atlas.height), 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    spec.attribute("oiio:UnassociatedAlpha", 1);
    spec.attribute("Software", "meadow");
    bool ok =
        out->open(tmp.string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, atlas.rgba.data()) && out->close();
    if (!ok) {
        std::string message = out->geterror();
        out.reset();
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        throw Error("cannot write atlas " + path.string() + ": " + message);
    }
    out.reset();
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw Error("cannot write atlas " + path.string() + ": " + ec.message());
    }
}

} // namespace meadow
