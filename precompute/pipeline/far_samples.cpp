#include "pipeline/far_samples.h"

#include "core/error.h"
#include "core/random.h"
#include "plants/atlas.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tbb/parallel_for.h>

namespace meadow {
namespace {

// Uniform in [0, 1) with 53 bits: the triangle pick over thousands of triangles needs more than
// Random::uniform's 24.
double uniformDouble(Random& rng) {
    return double(rng.next() >> 11) * (1.0 / 9007199254740992.0);
}

uint32_t packRgba8(uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
    return uint32_t(r) | (uint32_t(g) << 8) | (uint32_t(b) << 16) | (uint32_t(a) << 24);
}

// The nearest of `candidates` to p (the first of equals).
uint32_t nearestVertex(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& candidates, glm::vec3 p) {
    uint32_t best = candidates.front();
    float bestDistance = std::numeric_limits<float>::infinity();
    for (uint32_t v : candidates) {
        const glm::vec3 d = positions[v] - p;
        const float distance = glm::dot(d, d);
        if (distance < bestDistance) {
            bestDistance = distance;
            best = v;
        }
    }
    return best;
}

void checkSurface(const FarSurface& s) {
    const size_t n = s.positions.size();
    if (s.normals.size() != n || (s.atlas && s.uvs.size() != n) ||
        (!s.vertexBlock.empty() && s.vertexBlock.size() != n))
        throw Error("far samples: the surface's per-vertex arrays disagree on the vertex count");
    if (s.indices.size() % 3 != 0)
        throw Error("far samples: LOD 0 is not a triangle list");
    for (uint32_t i : s.indices)
        if (i >= n)
            throw Error("far samples: a triangle index is out of range");
    if (s.farVertices.empty())
        throw Error("far samples: the last LOD has no vertices");
    for (uint32_t v : s.farVertices)
        if (v >= n)
            throw Error("far samples: a far-LOD vertex is out of range");
    if (s.atlas && (s.atlas->width == 0 || s.atlas->height == 0 ||
                    s.atlas->rgba.size() != size_t(s.atlas->width) * s.atlas->height * 4))
        throw Error("far samples: the atlas is empty or has the wrong size");
}

} // namespace

FarSurface farSurfaceOfClump(const LibraryClump& clump, const RgbaImage& atlas) {
    FarSurface s;
    for (const gpu::GpuVertex& v : clump.mesh.vertices) {
        s.positions.push_back(glm::vec3(v.positionU));
        s.normals.push_back(glm::vec3(v.normalV));
        s.uvs.emplace_back(v.positionU.w, v.normalV.w);
    }
    const ClumpLod& lod0 = clump.lods[0];
    s.indices.reserve(lod0.indices.size());
    for (uint32_t i : lod0.indices) {
        if (i >= lod0.vertices.size())
            throw Error("far samples: clump " + clump.name + ": LOD 0 has a triangle index out of range");
        s.indices.push_back(lod0.vertices[i]);
    }
    s.farVertices = clump.lods[kLodCount - 1].vertices;
    s.vertexBlock = clump.motion.vertexBlock;
    s.atlas = &atlas;
    return s;
}

FarSurface farSurfaceOfRock(const LibraryRock& rock) {
    FarSurface s;
    s.positions = rock.mesh.positions;
    s.normals = rock.mesh.normals;
    s.uvs = rock.mesh.uvs;
    const RockLod& lod0 = rock.lods[0];
    for (uint32_t i : lod0.indices) {
        if (i >= lod0.vertices.size())
            throw Error("far samples: " + rock.mesh.name + ": LOD 0 has a triangle index out of range");
        s.indices.push_back(lod0.vertices[i]);
    }
    s.farVertices = rock.lods[kLodCount - 1].vertices;
    s.constantAlbedo =
        packRgba8(linearToSrgb(kRockAlbedo.r), linearToSrgb(kRockAlbedo.g), linearToSrgb(kRockAlbedo.b), 255);
    return s;
}

FarSamples buildFarSamples(const FarSurface& surface, uint32_t count, uint64_t seed) {
    checkSurface(surface);
    const std::vector<glm::vec3>& p = surface.positions;
    const size_t triangles = surface.indices.size() / 3;

    // Cumulative areas: a triangle is picked where a uniform draw over the total falls.
    std::vector<double> cumulative(triangles);
    double total = 0.0;
    for (size_t t = 0; t < triangles; ++t) {
        const uint32_t* tri = &surface.indices[3 * t];
        total += 0.5 * double(glm::length(glm::cross(p[tri[1]] - p[tri[0]], p[tri[2]] - p[tri[0]])));
        cumulative[t] = total;
    }
    FarSamples far;
    if (!(total > 0.0) || count == 0)
        return far;

    // The far vertices of each block, so a sample plays a vertex of its own rod.
    std::vector<std::vector<uint32_t>> farOfBlock;
    if (!surface.vertexBlock.empty())
        for (uint32_t v : surface.farVertices) {
            const uint32_t block = surface.vertexBlock[v];
            if (block >= farOfBlock.size())
                farOfBlock.resize(size_t(block) + 1);
            farOfBlock[block].push_back(v);
        }

    Random rng(seed);
    const uint64_t maxDraws = 64ull * count + 1024ull;
    uint64_t draws = 0;
    far.samples.reserve(count);
    while (far.samples.size() < count && draws < maxDraws) {
        ++draws;
        const double x = uniformDouble(rng) * total;
        const size_t t = std::min(
            size_t(std::upper_bound(cumulative.begin(), cumulative.end(), x) - cumulative.begin()), triangles - 1);
        const float r1 = std::sqrt(rng.uniform()), r2 = rng.uniform();
        const float b[3] = {1.0f - r1, r1 * (1.0f - r2), r1 * r2};
        const uint32_t* tri = &surface.indices[3 * t];

        uint32_t albedo = surface.constantAlbedo;
        if (surface.atlas) {
            const RgbaImage& atlas = *surface.atlas;
            const glm::vec2 uv = b[0] * surface.uvs[tri[0]] + b[1] * surface.uvs[tri[1]] + b[2] * surface.uvs[tri[2]];
            const int tx = std::clamp(int(std::floor(uv.x * float(atlas.width))), 0, int(atlas.width) - 1);
            const int ty = std::clamp(int(std::floor(uv.y * float(atlas.height))), 0, int(atlas.height) - 1);
            const uint8_t* texel = &atlas.rgba[(size_t(ty) * atlas.width + size_t(tx)) * 4];
            if (texel[3] < 128)
                continue; // cut out of the surface
            albedo = packRgba8(texel[0], texel[1], texel[2], 255);
        }

        FarSample s;
        s.position = b[0] * p[tri[0]] + b[1] * p[tri[1]] + b[2] * p[tri[2]];
        glm::vec3 normal =
            b[0] * surface.normals[tri[0]] + b[1] * surface.normals[tri[1]] + b[2] * surface.normals[tri[2]];
        if (!(glm::length(normal) > 1e-6f)) {
            const glm::vec3 face = glm::cross(p[tri[1]] - p[tri[0]], p[tri[2]] - p[tri[0]]);
            const glm::vec3 sum = surface.normals[tri[0]] + surface.normals[tri[1]] + surface.normals[tri[2]];
            normal = glm::dot(face, sum) < 0.0f ? -face : face;
        }
        s.normal = packOctahedral(glm::normalize(normal));
        s.albedo = albedo;

        uint32_t nearest = tri[0];
        float nearestDistance = std::numeric_limits<float>::infinity();
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 d = p[tri[k]] - s.position;
            if (glm::dot(d, d) < nearestDistance) {
                nearestDistance = glm::dot(d, d);
                nearest = tri[k];
            }
        }
        s.lightVertex = nearest;
        const uint32_t block = surface.vertexBlock.empty() ? 0 : surface.vertexBlock[nearest];
        const bool ownBlock = block < farOfBlock.size() && !farOfBlock[block].empty();
        s.vertex = nearestVertex(p, ownBlock ? farOfBlock[block] : surface.farVertices, s.position);
        far.samples.push_back(s);
    }
    far.area = float(total * double(far.samples.size()) / double(draws));

    // Fisher-Yates: the draws are already independent, the shuffle makes any prefix a uniform
    // subset whatever produced the list.
    for (size_t i = far.samples.size(); i > 1; --i) {
        const size_t j = size_t(rng.next() % uint64_t(i));
        std::swap(far.samples[i - 1], far.samples[j]);
    }
    return far;
}

uint64_t farSampleSeed(uint64_t sceneSeed, uint32_t index, bool rock) {
    return splitMix64(splitMix64(sceneSeed ^ 0x6661722d73616d70ull) + (rock ? 0x100000000ull : 0ull) + index);
}

void buildLibraryFarSamples(Library& library, uint32_t samplesPerClump, uint64_t sceneSeed) {
    const size_t clumps = library.clumps.size(), rocks = library.field.rocks.size();
    tbb::parallel_for(size_t(0), clumps + rocks, [&](size_t i) {
        if (i < clumps) {
            LibraryClump& clump = library.clumps[i];
            clump.far = buildFarSamples(farSurfaceOfClump(clump, library.atlas), samplesPerClump,
                                        farSampleSeed(sceneSeed, uint32_t(i), false));
        } else {
            LibraryRock& rock = library.field.rocks[i - clumps];
            rock.far = buildFarSamples(farSurfaceOfRock(rock), samplesPerClump,
                                       farSampleSeed(sceneSeed, uint32_t(i - clumps), true));
        }
    });
}

} // namespace meadow
