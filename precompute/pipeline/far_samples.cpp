#include "pipeline/far_samples.h"

#include "core/error.h"
#include "core/random.h"
#include "plants/atlas.h"
#include "transfer/ray_scene.h"

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

// A direction towards the eye within visibility view (azimuth, elevation)'s cell, in clump space
// (far_splat.h): the view's azimuth +- 22.5 degrees and elevation +- 15 degrees (kept within 0 and
// 90), at (ja, je) in [0, 1)^2 across the cell. The calibration's views (CalibrationView) sit four
// to a cell in azimuth, at the bins' elevations.
glm::vec3 visibilityDirection(uint32_t azimuth, uint32_t elevation, float ja, float je) {
    constexpr float kPi = 3.14159265358979f;
    const float step = 0.5f * kPi / float(gpu::kFarGainElevations - 1);
    const float a = (float(azimuth) + ja) * (0.25f * kPi);
    const float e = std::clamp((float(elevation) + je - 0.5f) * step, 0.0f, 0.5f * kPi);
    return glm::vec3(-std::sin(a) * std::cos(e), std::sin(e), std::cos(a) * std::cos(e));
}

// Whether the atlas texel containing uv (nearest, mip 0) is kept: alpha >= 128.
bool texelOpaque(const RgbaImage& atlas, glm::vec2 uv) {
    const int tx = std::clamp(int(std::floor(uv.x * float(atlas.width))), 0, int(atlas.width) - 1);
    const int ty = std::clamp(int(std::floor(uv.y * float(atlas.height))), 0, int(atlas.height) - 1);
    return atlas.rgba[(size_t(ty) * atlas.width + size_t(tx)) * 4 + 3] >= 128;
}

// Whether the texel at the barycentrics (u, v) of triangle t is cut out of the surface.
bool cutOutAt(const FarSurface& surface, uint32_t t, float u, float v) {
    if (!surface.atlas)
        return false;
    const uint32_t* tri = &surface.indices[3 * size_t(t)];
    const glm::vec2 uv = (1.0f - u - v) * surface.uvs[tri[0]] + u * surface.uvs[tri[1]] + v * surface.uvs[tri[2]];
    return !texelOpaque(*surface.atlas, uv);
}

// How many eye directions each view's cell tries per sample (measureVisibility).
constexpr int kVisibilityTries = 8;

// Each sample's visibility bits: for each view, whether a ray from the sample towards one of
// kVisibilityTries eye directions drawn at random within the view's cell (their own for each
// sample and view, from `seed`), started 1 mm off the surface on the eye's side and 1 mm along the
// ray, reaches the outside without meeting an opaque texel of LOD 0 (a cut-out texel lets it
// through, at most 64 times). Random directions rather than the cell's centre keep the bits from
// switching along the cells' edges. Several rather than one: a sample that some of the cell sees
// through a gap is in sight there, and the splats' depth test hides it from the rest of the cell
// as LOD 0 would. With one direction such samples were dropped in proportion to the share of the
// cell that hides them, which left the inner, shadowed parts of a clump out and the far field 3-9 %
// too bright against the same clumps drawn at LOD 0 (docs/BENCHMARKS.md).
void measureVisibility(const FarSurface& surface, std::vector<FarSample>& samples, uint64_t seed) {
    transfer::RayScene scene(false);
    scene.setMesh(surface.positions, surface.indices);
    tbb::parallel_for(size_t(0), samples.size(), [&](size_t i) {
        FarSample& sample = samples[i];
        const glm::vec3 normal = unpackOctahedral(sample.normal);
        Random rng(splitMix64(seed ^ 0x7669736962696c69ull) + i);
        // Whether nothing opaque of LOD 0 lies between the sample and the outside along `direction`.
        const auto seenAlong = [&](glm::vec3 direction) {
            const glm::vec3 side = glm::dot(normal, direction) >= 0.0f ? normal : -normal;
            transfer::Ray ray;
            ray.origin = sample.position + 1e-3f * side + 1e-3f * direction;
            ray.direction = direction;
            for (int pass = 0; pass < 64; ++pass) {
                const transfer::RayHit hit = scene.intersect(ray);
                if (hit.triangle == transfer::kNoHit)
                    return true;
                if (!cutOutAt(surface, hit.triangle, hit.u, hit.v))
                    return false;
                ray.origin += (hit.t + 1e-4f) * direction;
            }
            return true;
        };
        uint32_t bits = 0;
        for (uint32_t e = 0; e < gpu::kFarGainElevations; ++e)
            for (uint32_t a = 0; a < (e + 1 < gpu::kFarGainElevations ? gpu::kFarVisibilityAzimuths : 1u); ++a) {
                // Straight down: one cell for every azimuth.
                const bool top = e + 1 == gpu::kFarGainElevations;
                for (int attempt = 0; attempt < kVisibilityTries; ++attempt) {
                    const float ja = top ? 8.0f * rng.uniform() : rng.uniform(),
                                je = top ? 0.5f * rng.uniform() : rng.uniform();
                    if (seenAlong(visibilityDirection(a, e, ja, je))) {
                        bits |= 1u << gpu::farVisibilityBit(a, e);
                        break;
                    }
                }
            }
        sample.visibility = bits;
    });
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
    s.closed = true;
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
    measureVisibility(surface, far.samples, seed);
    return far;
}

namespace {

// One view of the calibration: the surface turned by `azimuth` about +y, seen along -z tilted
// down by `elevation`, at `pixelsPerMetre`, shifted by `offset` pixels; pixels in a square grid of
// side `grid` centred on the origin.
struct CalibrationView {
    float cosAzimuth, sinAzimuth, cosElevation, sinElevation;
    float pixelsPerMetre;
    glm::vec2 offset;
    int grid;

    glm::vec3 turn(glm::vec3 v) const {
        const glm::vec3 a(cosAzimuth * v.x + sinAzimuth * v.z, v.y, -sinAzimuth * v.x + cosAzimuth * v.z);
        // Rows of the view: right (1, 0, 0), up (0, cos e, -sin e), towards the eye (0, sin e, cos e).
        return glm::vec3(a.x, cosElevation * a.y - sinElevation * a.z, sinElevation * a.y + cosElevation * a.z);
    }
    // Continuous pixel coordinates (y down, as on screen) of a clump-space point.
    glm::vec2 pixel(glm::vec3 p) const {
        const glm::vec3 v = turn(p);
        return glm::vec2(v.x, -v.y) * pixelsPerMetre + offset + glm::vec2(0.5f * float(grid));
    }
    // The height above the clump's base of the centre of pixel row `row`, in the view's plane.
    float rowUp(int row) const { return -((float(row) + 0.5f) - offset.y - 0.5f * float(grid)) / pixelsPerMetre; }
    // Where the ray through the centre of row `row` meets the ground the clump stands on (the plane
    // y = 0): its view coordinate towards the eye. The eye must be above the plane.
    float groundTowardEye(int row) const { return -cosElevation * rowUp(row) / sinElevation; }
    // Whether that ground hides a point `towardEye` (its view coordinate towards the eye) at pixel
    // row `row`, by the resolve pass's own test (far_splat.h, farMeshDepthLimit): the view
    // coordinate towards the eye stands in for the reversed depth, as both grow towards the eye and
    // both are affine across a plane's pixels. The level ground reaches half a row's change behind
    // its row's centre. (Tested at the centre, a sample near the base lost the pixels whose centre
    // sees the ground just in front of it, where a mesh's fragment, which lies on the ray, loses
    // none.)
    bool groundHides(int row, float towardEye) const {
        // Seen level, what the test below gives as the eye rises from level: the ground hides the
        // rows wholly below its line, not the one it crosses (that row's ground reaches as far back
        // as the clump's base). Hiding every row whose centre lies below the line, the level view
        // took a row more from a clump a few pixels high than any view even a degree above it, and
        // the table's 0 degree gains, which the splat pass interpolates up to 30 degrees, came out
        // 1.6 times a rock's at 1 degree at 2 px (docs/BENCHMARKS.md, "The far field's footprints
        // off the optical axis").
        if (sinElevation < 1e-6f)
            return rowUp(row) < -0.5f / pixelsPerMetre;
        const float centre = groundTowardEye(row);
        return !(towardEye >
                 gpu::farMeshDepthLimit(centre, centre, centre, groundTowardEye(row - 1), groundTowardEye(row + 1)));
    }
};

// LOD 0's covered pixels in a view, as the mesh pass's expected coverage over where a pixel's centre
// may fall: points on a grid of `sub` x `sub` per pixel inside a triangle, alpha-tested, counted in
// pixels. In the field a clump lies anywhere on the pixel grid, so what its LOD 0 covers on average
// is that integral over the pixel, not the count of the calibration views' own pixel centres: for a
// clump a few pixels across, those were a few dozen over all 32 views, and which leaves met a
// centre was chance; the gains came out jagged in size (0.79 to 1.12 between 2 and 4 px) and,
// interpolated between the table's bins, a lone clump's splats covered up to 22 % too much or too
// little there (docs/BENCHMARKS.md, "The far field's footprints off the optical axis").
double rasterisedCoverage(const FarSurface& surface, const CalibrationView& view, int sub) {
    const int grid = view.grid * sub;
    const float scale = float(sub);
    std::vector<uint8_t> covered(size_t(grid) * size_t(grid), 0);
    for (size_t t = 0; t + 2 < surface.indices.size(); t += 3) {
        const uint32_t i0 = surface.indices[t], i1 = surface.indices[t + 1], i2 = surface.indices[t + 2];
        const glm::vec2 a = view.pixel(surface.positions[i0]) * scale, b = view.pixel(surface.positions[i1]) * scale,
                        c = view.pixel(surface.positions[i2]) * scale;
        const float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        if (!(std::abs(area) > 1e-12f))
            continue; // edge-on: covers no pixel centre
        const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}) - 0.5f)));
        const int x1 = std::min(grid - 1, int(std::ceil(std::max({a.x, b.x, c.x}) - 0.5f)));
        const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}) - 0.5f)));
        const int y1 = std::min(grid - 1, int(std::ceil(std::max({a.y, b.y, c.y}) - 0.5f)));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                uint8_t& cell = covered[size_t(y) * grid + size_t(x)];
                if (cell)
                    continue;
                const glm::vec2 q(float(x) + 0.5f, float(y) + 0.5f);
                const float w0 = ((b.x - q.x) * (c.y - q.y) - (b.y - q.y) * (c.x - q.x)) / area;
                const float w1 = ((c.x - q.x) * (a.y - q.y) - (c.y - q.y) * (a.x - q.x)) / area;
                const float w2 = 1.0f - w0 - w1;
                if (w0 < 0.0f || w1 < 0.0f || w2 < 0.0f)
                    continue;
                if (surface.atlas) {
                    const glm::vec2 uv = w0 * surface.uvs[i0] + w1 * surface.uvs[i1] + w2 * surface.uvs[i2];
                    if (!texelOpaque(*surface.atlas, uv))
                        continue;
                }
                cell = 1;
            }
    }
    size_t count = 0;
    for (uint8_t cell : covered)
        count += cell;
    return double(count) / double(sub * sub);
}

// A splat of the view: its continuous pixel coordinates (its square placed from them as
// far_splat.comp places it, farSplatCorner) and footprint.
struct CalibrationSplat {
    glm::vec2 at;
    float footprint;
    float towardEye; // the sample's view coordinate towards the eye (CalibrationView::groundHides)
};

// The splats' expected covered pixels at `gain` (far_splat.comp's keep test and square).
double splatCoverage(const std::vector<CalibrationSplat>& splats, const CalibrationView& view, float gain,
                     std::vector<double>& logMiss, std::vector<uint8_t>& certain) {
    const int grid = view.grid;
    std::fill(logMiss.begin(), logMiss.end(), 0.0);
    std::fill(certain.begin(), certain.end(), uint8_t(0));
    for (const CalibrationSplat& s : splats) {
        const float f = s.footprint * gain;
        const int side = int(gpu::farSplatSide(f));
        const float keep = std::min(f, 1.0f);
        const int cx = gpu::farSplatCorner(s.at.x, uint32_t(side)), cy = gpu::farSplatCorner(s.at.y, uint32_t(side));
        for (int j = 0; j < side; ++j)
            for (int i = 0; i < side; ++i) {
                const int x = cx + i, y = cy + j;
                if (x < 0 || y < 0 || x >= grid || y >= grid || view.groundHides(y, s.towardEye))
                    continue;
                const size_t cell = size_t(y) * grid + size_t(x);
                if (keep >= 1.0f)
                    certain[cell] = 1;
                else
                    logMiss[cell] += std::log1p(-double(keep));
            }
    }
    double covered = 0.0;
    for (size_t cell = 0; cell < logMiss.size(); ++cell)
        covered += certain[cell] ? 1.0 : 1.0 - std::exp(logMiss[cell]);
    return covered;
}

} // namespace

float farCoverageGainAt(const FarSurface& surface, const FarSamples& far, float size, float elevationUnits) {
    if (far.samples.empty() || !(far.area > 0.0f))
        return 1.0f;
    float reach = 0.0f; // the surface's farthest point from the clump's origin
    for (const glm::vec3& p : surface.positions)
        reach = std::max(reach, glm::length(p));
    // Four views per visibility view's cell, a quarter of a cell apart: a field turns its clumps
    // only a little (their wind must stay in the plane it was simulated in), so the splat pass
    // meets a clump from a few azimuths anywhere within the cells, where it takes each sample's bit
    // from one of the two views around the eye (farVisibilityBitAt). Eight views at the cells'
    // centres left the far field 3-7 % short of LOD 0's plant coverage in the field
    // (docs/BENCHMARKS.md).
    constexpr int kViewsPerCell = 4;
    constexpr int kAzimuths = int(gpu::kFarVisibilityAzimuths) * kViewsPerCell;
    constexpr float kPi = 3.14159265358979f;
    const float pixelsPerMetre = size / std::sqrt(far.area);
    const uint32_t count =
        gpu::farSampleCount(far.area, pixelsPerMetre, gpu::kFarDefaultDensity, uint32_t(far.samples.size()));
    const float areaPerSample = far.area / float(count);
    const int grid = int(std::ceil(2.0f * reach * pixelsPerMetre)) + 12;
    // LOD 0's points per pixel side (rasterisedCoverage): 16 at 2 px, 1 from 32 px on, so that
    // every size's truth is counted over about as many points as a clump 32 px across.
    const int sub = std::max(1, int(std::ceil(32.0f / size)));
    const float elevation = elevationUnits * (0.5f * kPi / float(gpu::kFarGainElevations - 1));
    double truth = 0.0;
    std::vector<std::pair<CalibrationView, std::vector<CalibrationSplat>>> views;
    for (int a = 0; a < kAzimuths; ++a) {
        // The eye's azimuth in farEyeAzimuth's units (cells, from view 0's centre), and in radians
        // about +y as CalibrationView takes it. The first view sits a 64th of a cell past view 0's
        // centre; any even spacing would do.
        const float eyeAzimuth = (float(a) + 0.0625f) / float(kViewsPerCell);
        const float azimuth = (eyeAzimuth + 0.5f) * (2.0f * kPi / float(gpu::kFarVisibilityAzimuths));
        // Sub-pixel offsets from the plastic sequence, so the views sample the pixel grid evenly.
        const glm::vec2 offset(std::fmod(0.5f + 0.7548776662f * float(a + 1), 1.0f),
                               std::fmod(0.5f + 0.5698402910f * float(a + 1), 1.0f));
        const CalibrationView view{std::cos(azimuth),
                                   std::sin(azimuth),
                                   std::cos(elevation),
                                   std::sin(elevation),
                                   pixelsPerMetre,
                                   offset,
                                   grid};
        truth += rasterisedCoverage(surface, view, sub);
        std::vector<CalibrationSplat> splats;
        splats.reserve(count);
        // Each view draws its own run of the shuffled samples, as far instances do
        // (farSampleSlot), from starts spread evenly over the list: the gain fits the runs'
        // average, not one prefix.
        const uint32_t available = uint32_t(far.samples.size());
        const uint32_t start = uint32_t(uint64_t(a) * available / kAzimuths);
        for (uint32_t k = 0; k < count; ++k) {
            const FarSample& sample = far.samples[gpu::farSampleSlot(start, k, available)];
            const uint32_t bit = gpu::farVisibilityBitAt(
                eyeAzimuth, elevationUnits, gpu::farSampleRandom(uint32_t(a), k + gpu::kFarAzimuthStream),
                gpu::farSampleRandom(uint32_t(a), k + gpu::kFarElevationStream));
            if (!(sample.visibility >> bit & 1u))
                continue; // hidden by its own clump from this view: the splat pass skips it
            const glm::vec3 normal = unpackOctahedral(sample.normal);
            const float cosine = view.turn(normal).z; // towards the eye: +z of the view
            if (cosine < 0.0f && surface.closed)
                continue;
            const glm::vec2 at = view.pixel(sample.position);
            splats.push_back(
                {at, gpu::farSampleFootprint(areaPerSample, pixelsPerMetre, cosine), view.turn(sample.position).z});
        }
        views.emplace_back(view, std::move(splats));
    }
    std::vector<double> logMiss(size_t(grid) * size_t(grid));
    std::vector<uint8_t> certain(logMiss.size());
    auto coverage = [&](float gain) {
        double sum = 0.0;
        for (const auto& [view, splats] : views)
            sum += splatCoverage(splats, view, gain, logMiss, certain);
        return sum;
    };
    // Bisection in log2(gain) over [-2, 3]: coverage grows with the gain.
    float lo = -2.0f, hi = 3.0f;
    if (coverage(std::exp2(lo)) >= truth)
        hi = lo;
    else if (coverage(std::exp2(hi)) <= truth)
        lo = hi;
    for (int step = 0; step < 24 && hi - lo > 1e-4f; ++step) {
        const float mid = 0.5f * (lo + hi);
        (coverage(std::exp2(mid)) < truth ? lo : hi) = mid;
    }
    return std::exp2(0.5f * (lo + hi));
}

std::array<float, gpu::kFarGainSizes * gpu::kFarGainElevations> farCoverageGains(const FarSurface& surface,
                                                                                 const FarSamples& far) {
    std::array<float, gpu::kFarGainSizes * gpu::kFarGainElevations> gains;
    for (uint32_t si = 0; si < gpu::kFarGainSizes; ++si)
        for (uint32_t ei = 0; ei < gpu::kFarGainElevations; ++ei)
            gains[si * gpu::kFarGainElevations + ei] =
                farCoverageGainAt(surface, far, gpu::kFarGainFirstSize * float(1u << si), float(ei));
    return gains;
}

uint64_t farSampleSeed(uint64_t sceneSeed, uint32_t index, bool rock) {
    return splitMix64(splitMix64(sceneSeed ^ 0x6661722d73616d70ull) + (rock ? 0x100000000ull : 0ull) + index);
}

void buildLibraryFarSamples(Library& library, uint32_t samplesPerClump, uint64_t sceneSeed) {
    const size_t clumps = library.clumps.size(), rocks = library.field.rocks.size();
    tbb::parallel_for(size_t(0), clumps + rocks, [&](size_t i) {
        if (i < clumps) {
            LibraryClump& clump = library.clumps[i];
            const FarSurface surface = farSurfaceOfClump(clump, library.atlas);
            clump.far = buildFarSamples(surface, samplesPerClump, farSampleSeed(sceneSeed, uint32_t(i), false));
            clump.far.gain = farCoverageGains(surface, clump.far);
        } else {
            LibraryRock& rock = library.field.rocks[i - clumps];
            const FarSurface surface = farSurfaceOfRock(rock);
            rock.far = buildFarSamples(surface, samplesPerClump, farSampleSeed(sceneSeed, uint32_t(i - clumps), true));
            rock.far.gain = farCoverageGains(surface, rock.far);
        }
    });
}

} // namespace meadow
