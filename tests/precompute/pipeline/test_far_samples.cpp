// The far field's surface samples (pipeline/far_samples.h, library/far_samples.h): on LOD 0's
// surface with its normals, the atlas's colour and cut-outs, uniform by area, every prefix
// unbiased, each playing a far-LOD vertex of its own rod, deterministic for any thread count; the
// octahedral normal encoding; the FARS section's round trip and its checks.
#include "core/error.h"
#include "library/far_samples.h"
#include "library/sections.h"
#include "pipeline/far_samples.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <limits>
#include <numbers>
#include <tbb/global_control.h>

using namespace meadow;

namespace {

constexpr uint32_t kGrid = 12; // cells per side of the test sheet

glm::vec3 sheetPoint(float x, float z) {
    return {x, 0.3f * std::sin(2.0f * x) + 0.2f * z * z, z};
}

glm::vec3 sheetNormal(float x, float z) {
    return glm::normalize(glm::vec3(-0.6f * std::cos(2.0f * x), 1.0f, -0.4f * z));
}

// A curved sheet over x in [0, 2], z in [0, 1], UV (x / 2, z); in thirds along x the rods
// (blocks) 0, 1 and 2, and the far LOD every third vertex of rods 0 and 1 (none of rod 2).
FarSurface sheet(const RgbaImage* atlas) {
    FarSurface s;
    for (uint32_t j = 0; j <= kGrid; ++j)
        for (uint32_t i = 0; i <= kGrid; ++i) {
            const float u = float(i) / float(kGrid), v = float(j) / float(kGrid);
            const float x = 2.0f * u, z = v;
            s.positions.push_back(sheetPoint(x, z));
            s.normals.push_back(sheetNormal(x, z));
            s.uvs.emplace_back(u, v);
            const uint32_t block = i * 3 < kGrid ? 0 : i * 3 < 2 * kGrid ? 1 : 2;
            s.vertexBlock.push_back(block);
            if ((i + j) % 3 == 0 && block != 2)
                s.farVertices.push_back(j * (kGrid + 1) + i);
        }
    for (uint32_t j = 0; j < kGrid; ++j)
        for (uint32_t i = 0; i < kGrid; ++i) {
            const uint32_t a = j * (kGrid + 1) + i, b = a + 1, c = a + kGrid + 1, d = c + 1;
            s.indices.insert(s.indices.end(), {a, c, b, b, c, d});
        }
    s.atlas = atlas;
    return s;
}

// 16 x 16 texels, each its own colour; with `cutLeftHalf` the texels of u < 0.5 have alpha 0
// (and those of u >= 0.5 alternate alpha 128 and 255: both are surface).
RgbaImage testAtlas(bool cutLeftHalf) {
    RgbaImage atlas{16, 16, {}};
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 16; ++x) {
            const uint8_t alpha = cutLeftHalf ? (x < 8 ? (x % 2 ? 127 : 0) : ((x + y) % 2 ? 128 : 255)) : 255;
            atlas.rgba.insert(atlas.rgba.end(),
                              {uint8_t(16 * x + 8), uint8_t(16 * y + 8), uint8_t((x * 37 + y * 11) % 256), alpha});
        }
    return atlas;
}

glm::vec3 unpackRgb(uint32_t rgba) {
    return {float(rgba & 0xff), float((rgba >> 8) & 0xff), float((rgba >> 16) & 0xff)};
}

// The point of triangle (a, b, c) nearest p, as barycentrics (Ericson, Real-Time Collision
// Detection, 5.1.5).
glm::vec3 nearestBarycentrics(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0)
        return {1, 0, 0};
    const glm::vec3 bp = p - b;
    const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3)
        return {0, 1, 0};
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const float v = d1 / (d1 - d3);
        return {1 - v, v, 0};
    }
    const glm::vec3 cp = p - c;
    const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6)
        return {0, 0, 1};
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const float w = d2 / (d2 - d6);
        return {1 - w, 0, w};
    }
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        const float w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {0, 1 - w, w};
    }
    const float denom = 1.0f / (va + vb + vc);
    const float v = vb * denom, w = vc * denom;
    return {1 - v - w, v, w};
}

// The triangles of `s` within `tolerance` of p, with the barycentrics of p's nearest point on each.
std::vector<std::pair<uint32_t, glm::vec3>> trianglesNear(const FarSurface& s, glm::vec3 p, float tolerance) {
    std::vector<std::pair<uint32_t, glm::vec3>> near;
    for (uint32_t t = 0; t < s.indices.size() / 3; ++t) {
        const glm::vec3 a = s.positions[s.indices[3 * t]], b = s.positions[s.indices[3 * t + 1]],
                        c = s.positions[s.indices[3 * t + 2]];
        const glm::vec3 bary = nearestBarycentrics(p, a, b, c);
        if (glm::length(bary.x * a + bary.y * b + bary.z * c - p) < tolerance)
            near.emplace_back(t, bary);
    }
    return near;
}

bool sameBytes(const FarSamples& a, const FarSamples& b) {
    static_assert(sizeof(FarSample) == kFarSampleBytes, "FarSample has no padding");
    return a.area == b.area && a.gain == b.gain && a.samples.size() == b.samples.size() &&
           std::memcmp(a.samples.data(), b.samples.data(), a.samples.size() * sizeof(FarSample)) == 0;
}

} // namespace

TEST(FarSamples, OctahedralRoundTripsEveryDirection) {
    // The encoding GLSL decodes: +z is (0, 0), +x is (32767, 0), -z folds to the corner (1, 1).
    EXPECT_EQ(packOctahedral({0, 0, 1}), 0u);
    EXPECT_EQ(packOctahedral({1, 0, 0}), 0x00007fffu);
    EXPECT_EQ(packOctahedral({0, -1, 0}), 0x80010000u); // -32767 in the high half
    EXPECT_EQ(packOctahedral({0, 0, -1}), 0x7fff7fffu);
    EXPECT_EQ(packOctahedral({0, 0, 0}), 0u);
    std::vector<glm::vec3> directions = {
        {1, 0, 0},    {-1, 0, 0},     {0, 1, 0},           {0, -1, 0},           {0, 0, 1}, {0, 0, -1}, {1, 1, -1},
        {-1, -1, -1}, {1e-7f, 0, -1}, {-1e-7f, 1e-7f, -1}, {0.5f, -0.5f, -1e-7f}};
    // A Fibonacci sphere: both hemispheres evenly.
    const uint32_t n = 20000;
    for (uint32_t i = 0; i < n; ++i) {
        const float z = 1.0f - 2.0f * (float(i) + 0.5f) / float(n);
        const float r = std::sqrt(1.0f - z * z), phi = float(i) * 2.39996323f;
        directions.push_back({r * std::cos(phi), r * std::sin(phi), z});
    }
    float worst = 0.0f;
    for (glm::vec3 d : directions) {
        d = glm::normalize(d);
        const glm::vec3 back = unpackOctahedral(packOctahedral(d));
        EXPECT_NEAR(glm::length(back), 1.0f, 1e-6f);
        worst = std::max(worst, glm::length(back - d));
    }
    EXPECT_LT(worst, 1e-4f);
    // Any 32-bit word decodes to a unit vector (a corrupt library cannot give NaN normals).
    for (uint32_t bits : {0x80008000u, 0xffffffffu, 0x80007fffu, 0x12345678u})
        EXPECT_NEAR(glm::length(unpackOctahedral(bits)), 1.0f, 1e-6f) << bits;
}

TEST(FarSamples, LieOnLod0WithItsInterpolatedNormals) {
    const RgbaImage atlas = testAtlas(false);
    const FarSurface s = sheet(&atlas);
    const FarSamples far = buildFarSamples(s, 2048, 7);
    ASSERT_EQ(far.samples.size(), 2048u);
    for (size_t i = 0; i < far.samples.size(); ++i) {
        const FarSample& sample = far.samples[i];
        const auto near = trianglesNear(s, sample.position, 1e-5f);
        ASSERT_FALSE(near.empty()) << "sample " << i << " is off the surface";
        const glm::vec3 normal = unpackOctahedral(sample.normal);
        bool agrees = false;
        for (const auto& [t, b] : near) {
            const glm::vec3 expected =
                glm::normalize(b.x * s.normals[s.indices[3 * t]] + b.y * s.normals[s.indices[3 * t + 1]] +
                               b.z * s.normals[s.indices[3 * t + 2]]);
            agrees |= glm::dot(normal, expected) > std::cos(2.0f * std::numbers::pi_v<float> / 180.0f);
        }
        EXPECT_TRUE(agrees) << "sample " << i << ": its normal is more than 2 degrees off the surface's";
    }
    // Without cut-outs the samples cover the whole area.
    double area = 0.0;
    for (size_t t = 0; t < s.indices.size(); t += 3)
        area += 0.5 * glm::length(glm::cross(s.positions[s.indices[t + 1]] - s.positions[s.indices[t]],
                                             s.positions[s.indices[t + 2]] - s.positions[s.indices[t]]));
    EXPECT_NEAR(far.area, area, area * 1e-5);
}

TEST(FarSamples, AlbedoIsTheAtlasTexelAndCutOutTexelsAreNotSurface) {
    const RgbaImage atlas = testAtlas(true);
    const FarSurface s = sheet(&atlas);
    const uint32_t n = 4096;
    const FarSamples far = buildFarSamples(s, n, 8);
    ASSERT_EQ(far.samples.size(), n);
    uint32_t checked = 0;
    for (size_t i = 0; i < far.samples.size(); ++i) {
        const FarSample& sample = far.samples[i];
        // The sheet's UV is (x / 2, z).
        const float tx = sample.position.x / 2.0f * 16.0f, ty = sample.position.z * 16.0f;
        EXPECT_GE(tx, 8.0f - 1e-3f) << "sample " << i << " lies in the cut-out half";
        EXPECT_EQ(sample.albedo >> 24, 255u) << i;
        if (std::abs(tx - std::round(tx)) < 1e-3f || std::abs(ty - std::round(ty)) < 1e-3f)
            continue; // on a texel border: either texel is right
        const uint32_t x = uint32_t(tx), y = uint32_t(ty);
        const uint8_t* texel = &atlas.rgba[(y * 16 + x) * 4];
        EXPECT_GE(texel[3], 128) << i;
        EXPECT_EQ(sample.albedo & 0xffffffu, uint32_t(texel[0]) | uint32_t(texel[1]) << 8 | uint32_t(texel[2]) << 16)
            << "sample " << i << " at texel " << x << ", " << y;
        ++checked;
    }
    EXPECT_GT(checked, n * 9 / 10);
    // Half the UV square is cut out, and the sheet's area splits nearly evenly in u (its x). The
    // accepted fraction is binomial over about 2n draws: 5 sigma.
    FarSamples whole = buildFarSamples(sheet(nullptr), 16, 8);
    double cutArea = 0.0; // the area of u < 0.5 (x < 1): the sheet's triangles there
    for (size_t t = 0; t < s.indices.size(); t += 3)
        if (s.positions[s.indices[t]].x + s.positions[s.indices[t + 1]].x + s.positions[s.indices[t + 2]].x < 3.0f)
            cutArea += 0.5 * glm::length(glm::cross(s.positions[s.indices[t + 1]] - s.positions[s.indices[t]],
                                                    s.positions[s.indices[t + 2]] - s.positions[s.indices[t]]));
    const double p = 1.0 - cutArea / whole.area;
    const double sigma = whole.area * std::sqrt(p * (1.0 - p) / (double(n) / p));
    EXPECT_NEAR(far.area, whole.area * p, 5.0 * sigma);
}

TEST(FarSamples, DensityIsUniformByArea) {
    // Two triangles apart, of areas 1 and 3.
    FarSurface s;
    s.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 2}, {5, 1, 0}, {8, 1, 0}, {5, 1, 2}};
    s.normals.assign(6, {0, 1, 0});
    s.indices = {0, 2, 1, 3, 5, 4};
    s.farVertices = {0, 3};
    const uint32_t n = 8192;
    const FarSamples far = buildFarSamples(s, n, 9);
    ASSERT_EQ(far.samples.size(), n);
    EXPECT_NEAR(far.area, 4.0f, 1e-5f);
    uint32_t first = 0;
    glm::dvec3 centroid[2]{glm::dvec3(0.0), glm::dvec3(0.0)};
    for (const FarSample& sample : far.samples) {
        const bool inFirst = sample.position.x < 2.0f;
        first += inFirst ? 1 : 0;
        centroid[inFirst ? 0 : 1] += glm::dvec3(sample.position);
        EXPECT_EQ(sample.vertex, inFirst ? 0u : 3u);
    }
    const double sigma = std::sqrt(n * 0.25 * 0.75);
    EXPECT_NEAR(double(first), n * 0.25, 5.0 * sigma);
    // Uniform inside each: the mean point is the centroid. A uniform point of a right triangle of
    // legs a (x) and b (z) has variance a^2 / 18 in x and b^2 / 18 in z.
    const glm::dvec3 expected[2] = {{1.0 / 3.0, 0.0, 2.0 / 3.0}, {6.0, 1.0, 2.0 / 3.0}};
    const double legs[2][2] = {{1.0, 2.0}, {3.0, 2.0}};
    const double counts[2] = {double(first), double(n - first)};
    for (int k = 0; k < 2; ++k) {
        const glm::dvec3 mean = centroid[k] / counts[k];
        EXPECT_NEAR(mean.x, expected[k].x, 5.0 * legs[k][0] / std::sqrt(18.0 * counts[k])) << k;
        EXPECT_NEAR(mean.z, expected[k].z, 5.0 * legs[k][1] / std::sqrt(18.0 * counts[k])) << k;
    }
}

TEST(FarSamples, EveryPrefixIsAnUnbiasedSubset) {
    const RgbaImage atlas = testAtlas(false);
    const uint32_t n = 4096, prefix = n / 8;
    const FarSamples far = buildFarSamples(sheet(&atlas), n, 10);
    ASSERT_EQ(far.samples.size(), n);
    // Six quantities: position x, y, z and albedo r, g, b.
    auto values = [](const FarSample& s) {
        const glm::vec3 c = unpackRgb(s.albedo);
        return std::array<double, 6>{s.position.x, s.position.y, s.position.z, c.x, c.y, c.z};
    };
    std::array<double, 6> sum{}, sumSq{}, prefixSum{};
    for (uint32_t i = 0; i < n; ++i) {
        const auto v = values(far.samples[i]);
        for (int k = 0; k < 6; ++k) {
            sum[k] += v[k];
            sumSq[k] += v[k] * v[k];
            if (i < prefix)
                prefixSum[k] += v[k];
        }
    }
    for (int k = 0; k < 6; ++k) {
        const double mean = sum[k] / n, variance = sumSq[k] / n - mean * mean;
        // The mean of a uniform subset of m of n values differs from theirs with this variance.
        const double sigma = std::sqrt(variance * (1.0 / prefix - 1.0 / n));
        EXPECT_NEAR(prefixSum[k] / prefix, mean, 5.0 * sigma) << "quantity " << k;
    }
    // And the list is not in the order it was drawn in triangle order: the prefix spans the sheet.
    float minX = 2.0f, maxX = 0.0f;
    for (uint32_t i = 0; i < 64; ++i) {
        minX = std::min(minX, far.samples[i].position.x);
        maxX = std::max(maxX, far.samples[i].position.x);
    }
    EXPECT_GT(maxX - minX, 1.0f);
}

TEST(FarSamples, EachPlaysAFarLodVertexOfItsOwnRodAndIsLitByItsNearestVertex) {
    const RgbaImage atlas = testAtlas(false);
    const FarSurface s = sheet(&atlas);
    const FarSamples far = buildFarSamples(s, 2048, 11);
    ASSERT_EQ(far.samples.size(), 2048u);
    uint32_t ownRod = 0, fallback = 0;
    for (size_t i = 0; i < far.samples.size(); ++i) {
        const FarSample& sample = far.samples[i];
        ASSERT_NE(std::find(s.farVertices.begin(), s.farVertices.end(), sample.vertex), s.farVertices.end())
            << "sample " << i << " plays vertex " << sample.vertex << ", not one of the far LOD";
        const float played = glm::length(s.positions[sample.vertex] - sample.position);
        // Of the triangles the sample lies on (more than one only on an edge), one must explain the
        // choice: the nearest far vertex of its nearest vertex's rod, or of all where that rod has none.
        bool explained = false;
        for (const auto& [t, b] : trianglesNear(s, sample.position, 1e-5f)) {
            uint32_t nearest = s.indices[3 * t];
            for (int k = 1; k < 3; ++k)
                if (glm::length(s.positions[s.indices[3 * t + k]] - sample.position) <
                    glm::length(s.positions[nearest] - sample.position))
                    nearest = s.indices[3 * t + k];
            // Lit by the triangle's nearest vertex (ties between equally near vertices aside).
            if (sample.lightVertex != nearest && glm::length(s.positions[sample.lightVertex] - sample.position) >
                                                     glm::length(s.positions[nearest] - sample.position) + 1e-6f)
                continue;
            const uint32_t block = s.vertexBlock[nearest];
            float best = std::numeric_limits<float>::infinity();
            for (uint32_t v : s.farVertices)
                if (block == 2 || s.vertexBlock[v] == block)
                    best = std::min(best, glm::length(s.positions[v] - sample.position));
            if ((block == 2 || s.vertexBlock[sample.vertex] == block) && played <= best + 1e-6f) {
                explained = true;
                (block == 2 ? fallback : ownRod) += 1;
                break;
            }
        }
        EXPECT_TRUE(explained) << "sample " << i << " plays vertex " << sample.vertex;
    }
    // Both cases occur: rods 0 and 1 have far vertices, rod 2 none.
    EXPECT_GT(ownRod, 1000u);
    EXPECT_GT(fallback, 300u);
}

TEST(FarSamples, DeterministicForASeedWhateverTheThreads) {
    // A library of three clumps (the test tuft, its LOD 0 the whole mesh, the far LOD every other
    // vertex, a rod per blade) and one rock (a tetrahedron), as the pipeline fills it.
    Library library;
    library.atlas = testAtlas(false);
    for (uint32_t c = 0; c < 3; ++c) {
        LibraryClump clump;
        clump.name = "tuft-" + std::to_string(c);
        clump.mesh = makeTuftMesh(5 + c, 4);
        const uint32_t vertices = uint32_t(clump.mesh.vertices.size());
        for (uint32_t l = 0; l < kLodCount; ++l) {
            for (uint32_t v = 0; v < vertices; ++v)
                clump.lods[l].vertices.push_back(v);
            clump.lods[l].indices = clump.mesh.indices;
        }
        clump.lods[kLodCount - 1].vertices.clear();
        for (uint32_t v = 0; v < vertices; v += 2)
            clump.lods[kLodCount - 1].vertices.push_back(v);
        for (uint32_t v = 0; v < vertices; ++v)
            clump.motion.vertexBlock.push_back(v * (5 + c) / vertices);
        library.clumps.push_back(std::move(clump));
    }
    LibraryRock rock;
    rock.mesh.name = "rock-0";
    rock.mesh.positions = {{0, 0, 0}, {0.3f, 0, 0}, {0, 0, 0.3f}, {0.1f, 0.2f, 0.1f}};
    for (const glm::vec3& p : rock.mesh.positions)
        rock.mesh.normals.push_back(glm::normalize(p - glm::vec3(0.1f, 0.05f, 0.1f)));
    rock.mesh.uvs.assign(4, glm::vec2(0.5f));
    rock.mesh.indices = {0, 1, 2, 0, 3, 1, 1, 3, 2, 2, 3, 0};
    for (RockLod& lod : rock.lods) {
        lod.vertices = {0, 1, 2, 3};
        lod.indices = rock.mesh.indices;
    }
    library.field.rocks.push_back(rock);

    auto build = [&](int threads, uint64_t seed) {
        Library copy = library;
        if (threads > 0) {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
            buildLibraryFarSamples(copy, 1024, seed);
        } else {
            buildLibraryFarSamples(copy, 1024, seed);
        }
        return copy;
    };
    const Library one = build(1, 5), two = build(2, 5), all = build(0, 5), other = build(0, 6);
    for (size_t c = 0; c < library.clumps.size(); ++c) {
        EXPECT_EQ(one.clumps[c].far.samples.size(), 1024u);
        EXPECT_TRUE(sameBytes(one.clumps[c].far, two.clumps[c].far)) << c;
        EXPECT_TRUE(sameBytes(one.clumps[c].far, all.clumps[c].far)) << c;
        EXPECT_FALSE(sameBytes(one.clumps[c].far, other.clumps[c].far)) << c;
    }
    // Each clump has its own stream.
    EXPECT_NE(one.clumps[0].far.samples[0].position, one.clumps[1].far.samples[0].position);
    EXPECT_TRUE(sameBytes(one.field.rocks[0].far, all.field.rocks[0].far));
    ASSERT_EQ(one.field.rocks[0].far.samples.size(), 1024u);
    // Rocks: the constant albedo, sRGB-encoded.
    for (const FarSample& sample : one.field.rocks[0].far.samples)
        EXPECT_EQ(sample.albedo, one.field.rocks[0].far.samples[0].albedo);
    EXPECT_EQ(one.field.rocks[0].far.samples[0].albedo >> 24, 255u);
}

TEST(FarSamples, SectionRoundTripsAndRefusesABadVertex) {
    Library library;
    LibraryClump clump;
    clump.name = "tuft";
    clump.mesh = makeTuftMesh(4, 3);
    for (uint32_t l = 0; l < kLodCount; ++l) {
        for (uint32_t v = 0; v < clump.mesh.vertices.size(); ++v)
            clump.lods[l].vertices.push_back(v);
        clump.lods[l].indices = clump.mesh.indices;
    }
    // The last LOD keeps every vertex but the first, which no sample may play.
    const uint32_t dropped = 0;
    clump.lods[kLodCount - 1].vertices.erase(clump.lods[kLodCount - 1].vertices.begin());
    clump.motion.vertexBlock.assign(clump.mesh.vertices.size(), 0);
    library.atlas = testAtlas(false);
    library.clumps.push_back(clump);
    LibraryRock rock;
    rock.mesh.name = "rock-0";
    rock.mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    rock.mesh.normals.assign(3, {0, 0, 1});
    rock.mesh.uvs.assign(3, glm::vec2(0.0f));
    rock.mesh.indices = {0, 1, 2};
    for (RockLod& lod : rock.lods) {
        lod.vertices = {0, 1, 2};
        lod.indices = {0, 1, 2};
    }
    library.field.rocks.push_back(rock);
    buildLibraryFarSamples(library, 300, 1);

    auto roundTrip = [](const Library& written, Library& read) {
        ByteWriter w;
        writeFarSamplesSection(w, written);
        const std::vector<uint8_t> bytes = w.take();
        ByteReader r(bytes, "test");
        readFarSamplesSection(r, "library x: section 'FARS'", read);
        return bytes.size();
    };
    Library back = library;
    back.clumps[0].far = {};
    back.field.rocks[0].far = {};
    const size_t bytes = roundTrip(library, back);
    const size_t gainBytes = library.clumps[0].far.gain.size() * 4u;
    EXPECT_EQ(bytes, 4u + (8u + gainBytes + 300u * kFarSampleBytes) + 4u + (8u + gainBytes + 300u * kFarSampleBytes));
    // The library's gains were measured (buildLibraryFarSamples): not all 1.
    EXPECT_NE(library.clumps[0].far.gain, FarSamples{}.gain);
    EXPECT_TRUE(sameBytes(back.clumps[0].far, library.clumps[0].far));
    EXPECT_TRUE(sameBytes(back.field.rocks[0].far, library.field.rocks[0].far));

    auto refusal = [&](Library bad) {
        try {
            Library read = library;
            roundTrip(bad, read);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    Library bad = library;
    const uint32_t vertices = uint32_t(clump.mesh.vertices.size());
    bad.clumps[0].far.samples[5].vertex = vertices;
    EXPECT_EQ(refusal(bad), "library x: section 'FARS': clump tuft: far-field sample 5 names vertex " +
                                std::to_string(vertices) + " of " + std::to_string(vertices));
    bad = library;
    bad.clumps[0].far.samples[9].vertex = dropped;
    EXPECT_EQ(refusal(bad), "library x: section 'FARS': clump tuft: far-field sample 9 plays vertex " +
                                std::to_string(dropped) + ", which the last LOD does not keep");
    bad = library;
    bad.field.rocks[0].far.samples[7].vertex = 3;
    EXPECT_EQ(refusal(bad), "library x: section 'FARS': rock-0: far-field sample 7 names vertex 3 of 3");
    bad = library;
    bad.clumps[0].far.samples[2].position.y = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(refusal(bad), "library x: section 'FARS': clump tuft: far-field sample 2 has a non-finite position");
    bad = library;
    bad.clumps[0].far.samples[4].visibility = 1u << 25;
    EXPECT_EQ(refusal(bad), "library x: section 'FARS': clump tuft: far-field sample 4 has visibility bits 33554432 "
                            "outside the 25 views");
    bad = library;
    bad.field.rocks[0].far.area = -1.0f;
    EXPECT_EQ(refusal(bad), "library x: section 'FARS': rock-0: its far-field samples cover a non-finite or negative "
                            "area");
    bad = library;
    bad.clumps[0].far.gain[3] = 0.0f;
    EXPECT_EQ(refusal(bad), "library x: section 'FARS': clump tuft: its far-field coverage gain 0.000000 is not a "
                            "positive finite number");
    bad = library;
    bad.field.rocks.clear();
    EXPECT_EQ(refusal(bad), "library x: section 'FARS' does not hold one entry per rock");
}

namespace {

// Quads as a far surface (no atlas, one block, every vertex in the far LOD): each quad is corner
// `origin` spanned by `u` and `v`, its normal u x v.
FarSurface quads(const std::vector<std::array<glm::vec3, 3>>& spans, bool closed = false) {
    FarSurface s;
    for (const auto& [origin, u, v] : spans) {
        const uint32_t base = uint32_t(s.positions.size());
        const glm::vec3 n = glm::normalize(glm::cross(u, v));
        for (const glm::vec3& p : {origin, origin + u, origin + v, origin + u + v}) {
            s.positions.push_back(p);
            s.normals.push_back(n);
            s.uvs.emplace_back(0.0f);
        }
        s.indices.insert(s.indices.end(), {base, base + 1, base + 2, base + 1, base + 3, base + 2});
    }
    for (uint32_t v = 0; v < uint32_t(s.positions.size()); ++v)
        s.farVertices.push_back(v);
    s.closed = closed;
    return s;
}

// Two upright 1 m sheets facing +z, x in [-0.5, 0.5], y in [0, 1]: one at z = 0, one `gap` behind it.
FarSurface sheetPair(float gap) {
    return quads(
        {{glm::vec3(-0.5f, 0.0f, 0.0f), {1, 0, 0}, {0, 1, 0}}, {glm::vec3(-0.5f, 0.0f, -gap), {1, 0, 0}, {0, 1, 0}}});
}

float gainAt(const FarSamples& far, uint32_t size, uint32_t elevation) {
    return far.gain[size * gpu::kFarGainElevations + elevation];
}

FarSamples measured(const FarSurface& surface) {
    FarSamples far = buildFarSamples(surface, 4096, 7);
    far.gain = farCoverageGains(surface, far);
    return far;
}

} // namespace

// Independent splats cover a solid surface's pixels with probability 1 - exp(-d), not 1: the gain
// that restores an opaque sheet's coverage is well above 1 once it spans pixels, while sparse thin
// blades, each far narrower than a pixel, need about none (their splats rarely share a pixel).
TEST(FarSamples, CoverageGainRestoresSolidSurfacesAndLeavesThinBladesAlone) {
    // A vertical sheet 1 m square standing on the ground, facing +z.
    const FarSamples sheet = measured(quads({{glm::vec3(-0.5f, 0.0f, 0.0f), {1, 0, 0}, {0, 1, 0}}}));
    for (uint32_t size = 2; size < gpu::kFarGainSizes; ++size) // 8 px and more
        for (uint32_t elevation = 0; elevation < 3; ++elevation)
            EXPECT_GT(gainAt(sheet, size, elevation), 1.5f) << size << " " << elevation;

    // Twelve blades 4 mm wide and 0.8 m tall on a 0.6 m circle, turned every way and leaning by
    // 0.25 m. (Upright, a blade narrower than a pixel covers a whole column of pixel centres or
    // none, so LOD 0's coverage of twelve of them is chance: their gain came out 0.65 at 8 px.)
    std::vector<std::array<glm::vec3, 3>> spans;
    for (int i = 0; i < 12; ++i) {
        const float a = float(i) * 0.5236f;
        const glm::vec3 at(0.3f * std::cos(a), 0.0f, 0.3f * std::sin(a));
        const glm::vec3 across(0.004f * std::cos(2.0f * a), 0.0f, 0.004f * std::sin(2.0f * a));
        spans.push_back({at, across, {0.25f * std::cos(a + 1.0f), 0.8f, 0.25f * std::sin(a + 1.0f)}});
    }
    const FarSamples blades = measured(quads(spans));
    // 8 and 16 px (sqrt of the 0.04 m^2 in pixels): the blades are 0.2 to 0.4 px wide there.
    for (uint32_t size = 2; size < 4; ++size)
        for (uint32_t elevation = 0; elevation < 3; ++elevation) {
            EXPECT_GT(gainAt(blades, size, elevation), 0.7f) << size << " " << elevation;
            EXPECT_LT(gainAt(blades, size, elevation), 1.4f) << size << " " << elevation;
        }
}

// LOD 0's coverage is measured as the field meets it on average, wherever the pixel grid falls
// (rasterisedCoverage's points per pixel), not as the calibration views' own pixel centres happen
// to meet it. Upright blades narrower than a pixel each cover a whole column of centres or none,
// and which of twelve do in 32 views is chance: counted at the centres, their gains came out
// 0.64-0.65 at 8 px and 0.84-0.86 at 16 px; over the pixel, 0.92-1.13 from 2 to 16 px, about none
// as for the leaning ones above.
TEST(FarSamples, CoverageGainsMeasureLod0WhereverThePixelGridFalls) {
    std::vector<std::array<glm::vec3, 3>> spans;
    for (int i = 0; i < 12; ++i) {
        const float a = float(i) * 0.5236f;
        const glm::vec3 at(0.3f * std::cos(a), 0.0f, 0.3f * std::sin(a));
        const glm::vec3 across(0.004f * std::cos(2.0f * a), 0.0f, 0.004f * std::sin(2.0f * a));
        spans.push_back({at, across, {0.0f, 0.8f, 0.0f}});
    }
    const FarSamples blades = measured(quads(spans));
    for (uint32_t size = 0; size < 4; ++size) // 2 to 16 px
        for (uint32_t elevation = 0; elevation < 3; ++elevation) {
            EXPECT_GT(gainAt(blades, size, elevation), 0.8f) << size << " " << elevation;
            EXPECT_LT(gainAt(blades, size, elevation), 1.25f) << size << " " << elevation;
        }
}

// The resolve pass tests samples against the meshes' depth, which holds the ground, as far as the
// ground reaches within the pixel: half a pixel's change of its depth behind the pixel's centre
// (far_splat.h, farMeshDepthLimit). The gains count the ground as that test does: a sheet lying
// 2 mm above the ground, seen from 30 degrees, keeps its pixels and needs the gain of the same
// sheet raised 0.3 m. (Tested at the centre, it lost the pixels whose centre sees the ground just in
// front of its samples, and needed twice the gain.)
TEST(FarSamples, CoverageGainCountsTheGroundAsTheResolveTestsIt) {
    const FarSamples lying = measured(quads({{glm::vec3(-0.5f, 0.002f, -0.5f), {0, 0, 1}, {1, 0, 0}}}));
    const FarSamples raised = measured(quads({{glm::vec3(-0.5f, 0.3f, -0.5f), {0, 0, 1}, {1, 0, 0}}}));
    for (uint32_t size = 0; size < gpu::kFarGainSizes; ++size) {
        const float ratio = gainAt(lying, size, 1) / gainAt(raised, size, 1);
        EXPECT_GT(ratio, 0.95f) << size;
        EXPECT_LT(ratio, 1.05f) << size;
    }
}

// The level view is the limit of the views just above it: the ground hides the rows wholly below
// its line, not the row it crosses, whose ground reaches back to the base as the resolve pass's
// test gives for any eye above level (far_samples.cpp, CalibrationView::groundHides). The splat pass
// interpolates the gains from 0 degrees up to 30, and the field's eye is never quite level: with
// the row the line crosses hidden as well, a rock's gains at 0 degrees came out 1.6 times those a
// degree higher at 2 px, and the far field's rocks near the horizon covered 5-7 % too much.
TEST(FarSamples, CoverageGainSeenLevelIsTheLimitOfTheViewsAboveIt) {
    // A closed cube 0.6 m on a side standing on the ground, its faces outward.
    const FarSurface cube = quads({{glm::vec3(-0.3f, 0.0f, -0.3f), {0.6f, 0, 0}, {0, 0, 0.6f}},
                                   {glm::vec3(-0.3f, 0.6f, -0.3f), {0, 0, 0.6f}, {0.6f, 0, 0}},
                                   {glm::vec3(-0.3f, 0.0f, 0.3f), {0.6f, 0, 0}, {0, 0.6f, 0}},
                                   {glm::vec3(-0.3f, 0.0f, -0.3f), {0, 0.6f, 0}, {0.6f, 0, 0}},
                                   {glm::vec3(0.3f, 0.0f, -0.3f), {0, 0.6f, 0}, {0, 0, 0.6f}},
                                   {glm::vec3(-0.3f, 0.0f, -0.3f), {0, 0, 0.6f}, {0, 0.6f, 0}}},
                                  true);
    const FarSamples far = buildFarSamples(cube, 4096, 7);
    for (float size : {2.0f, 4.0f, 8.0f}) {
        const float level = farCoverageGainAt(cube, far, size, 0.0f);
        const float degree = farCoverageGainAt(cube, far, size, 1.0f / 30.0f);
        EXPECT_NEAR(level / degree, 1.0f, 0.05f) << size << " px: " << level << " level, " << degree << " at 1 degree";
    }
}

// Each sample knows the views from which its own clump hides it (far_splat.h): of two upright
// sheets one behind the other (both facing +z, 0.2 m apart), the hind one's samples are hidden from
// the views in front (their eye towards +z), seen from behind and from straight above, and so are
// the front one's from behind; a cut-out texel lets the rays through.
TEST(FarSamples, VisibilityBitsAreTheViewsNothingOfTheClumpHidesASampleFrom) {
    const auto pair = [](const RgbaImage* atlas) {
        FarSurface s = sheetPair(0.2f);
        s.atlas = atlas;
        return s;
    };
    const FarSurface solid = pair(nullptr);
    const FarSamples far = buildFarSamples(solid, 2048, 3);
    // The views' eye directions are (-sin A cos E, sin E, cos A cos E), A = (a + 1/2) x 45 degrees.
    const auto eyeTowardsFront = [](uint32_t a) { return std::cos((float(a) + 0.5f) * 0.785398f) > 0.0f; };
    uint32_t inFront = 0, behind = 0, checked = 0;
    for (const FarSample& sample : far.samples) {
        EXPECT_EQ(sample.visibility & ~gpu::kFarAllVisible, 0u);
        // From 75 to 90 degrees up, the front sheet (1 m tall, 0.2 m in front) hides the hind
        // one's samples below 0.75 m at most.
        if (sample.position.y > 0.8f) {
            EXPECT_TRUE(sample.visibility >> gpu::kFarVisibilityTopBit & 1u)
                << "nothing hides the sheets' tops from above";
        }
        const bool hind = sample.position.z < -0.1f;
        // The views nearest the sheets' normal (their cells 0 to 45 degrees off it, up to 45
        // degrees up) cross the 0.2 m between the sheets within 0.2 m sideways and 0.29 m up: a
        // point farther than that from the edges is hidden by its neighbour from one side.
        if (std::abs(sample.position.x) > 0.28f || sample.position.y > 0.7f)
            continue;
        ++checked;
        for (uint32_t e = 0; e < 2; ++e)
            for (uint32_t a : {0u, 3u, 4u, 7u}) {
                const bool seen = sample.visibility >> gpu::farVisibilityBit(a, e) & 1u;
                const bool expected = hind ? !eyeTowardsFront(a) : eyeTowardsFront(a);
                EXPECT_EQ(seen, expected) << "sample at " << sample.position.x << ", " << sample.position.y << ", "
                                          << sample.position.z << ", view " << a << ", " << e;
                (hind ? behind : inFront) += seen;
            }
    }
    EXPECT_GT(checked, 200u);
    EXPECT_GT(inFront, 0u);
    EXPECT_GT(behind, 0u);

    // Cut the front sheet out (texels of u < 0.5 have alpha 0; its UVs are 0, the hind one's 0.75):
    // the hind sheet is seen from the front too.
    FarSurface cut = pair(nullptr);
    RgbaImage atlas = testAtlas(true);
    for (size_t v = 0; v < cut.uvs.size(); ++v)
        cut.uvs[v] = cut.positions[v].z < -0.1f ? glm::vec2(0.75f, 0.5f) : glm::vec2(0.25f, 0.5f);
    cut.atlas = &atlas;
    // Every sample lies on the hind sheet now: the front one is all cut out.
    const FarSamples through = buildFarSamples(cut, 512, 3);
    for (const FarSample& sample : through.samples) {
        ASSERT_LT(sample.position.z, -0.1f);
        for (uint32_t a = 0; a < gpu::kFarVisibilityAzimuths; ++a)
            EXPECT_TRUE(sample.visibility >> gpu::farVisibilityBit(a, 1) & 1u) << a;
    }
}

// A sample that part of a view's cell sees through a gap keeps that view's bit (far_samples.cpp,
// kVisibilityTries): of two upright sheets 1 m wide, 0.2 m apart, the hind one's samples 0.05 to
// 0.15 m in from its right edge are seen past the front sheet's edge from 14-37 to 45 degrees of view
// 7's cell (azimuths 315 to 360 degrees, eye towards +z and +x), a fifth to two thirds of it, and from
// none of view 0's (eye towards +z and -x). One ray per cell kept view 7's bit for about 45 % of them.
TEST(FarSamples, VisibilityBitsKeepASampleThatPartOfTheCellSees) {
    const FarSurface pair = sheetPair(0.2f);
    const FarSamples far = buildFarSamples(pair, 2048, 5);
    uint32_t nearEdge = 0, seenPastEdge = 0;
    for (const FarSample& sample : far.samples) {
        if (sample.position.z > -0.1f || sample.position.x < 0.35f || sample.position.x > 0.45f ||
            sample.position.y > 0.8f)
            continue;
        ++nearEdge;
        seenPastEdge += sample.visibility >> gpu::farVisibilityBit(7, 0) & 1u;
        EXPECT_FALSE(sample.visibility >> gpu::farVisibilityBit(0, 0) & 1u)
            << "the front sheet hides " << sample.position.x << ", " << sample.position.y << " from all of view 0";
    }
    ASSERT_GT(nearEdge, 40u);
    EXPECT_GT(double(seenPastEdge), 0.85 * double(nearEdge)) << seenPastEdge << " of " << nearEdge;
}

// The coverage gains are measured on the samples each view sees: of two sheets one behind the
// other, the hind one's samples add nothing to the splats' coverage from the front, so the pair
// needs a larger gain than the same samples all counted as in sight.
TEST(FarSamples, CoverageGainCountsOnlyTheSamplesAViewSees) {
    const FarSurface pair = sheetPair(0.05f);
    const FarSamples far = buildFarSamples(pair, 4096, 7);
    FarSamples blind = far;
    for (FarSample& sample : blind.samples)
        sample.visibility = gpu::kFarAllVisible;
    const auto seen = farCoverageGains(pair, far), all = farCoverageGains(pair, blind);
    // From 0 and 30 degrees up. (From 60 degrees, the views' cells that look along the sheets see
    // into the 5 cm between them, from above or past their ends, so most of the hind one's samples
    // are in sight from part of those cells and keep their bits; straight above, the upright sheets
    // cover nothing either way.) Up to 16 px: at 32 px the density is tapered (farDensityShare)
    // and this opaque pair's gains, 3.7 seen and 4.4 all, both take its facing samples past 2.25
    // px, where each covers a square of 2x2 pixels and the coverage jumps with the gain: both
    // bisections end at that jump, whatever the samples in sight.
    for (uint32_t size = 0; size + 1 < gpu::kFarGainSizes; ++size)
        for (uint32_t elevation = 0; elevation < 2; ++elevation) {
            const uint32_t at = size * gpu::kFarGainElevations + elevation;
            EXPECT_GT(seen[at], 1.3f * all[at]) << size << " " << elevation;
        }
}
