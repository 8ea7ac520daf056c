#include "rock.h"

#include "core/error.h"
#include "core/random.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <map>
#include <utility>

namespace meadow {
namespace {

// ---- Icosphere --------------------------------------------------------------------------------

struct TriangleMesh {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
};

// The unit icosahedron, faces counter-clockwise seen from outside.
TriangleMesh icosahedron() {
    const float t = (1.0f + std::sqrt(5.0f)) * 0.5f;
    TriangleMesh mesh;
    mesh.positions = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                      {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    for (glm::vec3& p : mesh.positions)
        p = glm::normalize(p);
    mesh.indices = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,  11, 10, 2,  10, 7, 6, 7, 1, 8,
                    3, 9,  4, 3, 4, 2, 3, 2, 6, 3, 6, 8,  3, 8,  9,  4, 9, 5, 2, 4,  11, 6,  2,  10, 8,  6, 7, 9, 8, 1};
    return mesh;
}

// Each triangle split in four; edge midpoints shared through a cache so the sphere stays closed.
TriangleMesh subdivide(const TriangleMesh& mesh) {
    TriangleMesh out{mesh.positions, {}};
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
    auto midpoint = [&](uint32_t a, uint32_t b) {
        const std::pair<uint32_t, uint32_t> key{std::min(a, b), std::max(a, b)};
        const auto found = midpoints.find(key);
        if (found != midpoints.end())
            return found->second;
        out.positions.push_back(glm::normalize(out.positions[a] + out.positions[b]));
        const uint32_t index = uint32_t(out.positions.size() - 1);
        midpoints.emplace(key, index);
        return index;
    };
    for (size_t i = 0; i < mesh.indices.size(); i += 3) {
        const uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
        const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
        out.indices.insert(out.indices.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    return out;
}

// ---- Noise ------------------------------------------------------------------------------------

// Smooth 3D value noise in [-1, 1]: hashed lattice values blended with the quintic fade.
float valueNoise(const glm::vec3& p, uint64_t seed) {
    const glm::vec3 cell = glm::floor(p);
    const glm::vec3 t = p - cell;
    const glm::vec3 f = t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
    auto lattice = [&](int dx, int dy, int dz) {
        uint64_t h = splitMix64(seed ^ uint64_t(int64_t(cell.x) + dx));
        h = splitMix64(h ^ uint64_t(int64_t(cell.y) + dy));
        h = splitMix64(h ^ uint64_t(int64_t(cell.z) + dz));
        return float(h >> 40) * (2.0f / 16777216.0f) - 1.0f;
    };
    const float x00 = glm::mix(lattice(0, 0, 0), lattice(1, 0, 0), f.x);
    const float x10 = glm::mix(lattice(0, 1, 0), lattice(1, 1, 0), f.x);
    const float x01 = glm::mix(lattice(0, 0, 1), lattice(1, 0, 1), f.x);
    const float x11 = glm::mix(lattice(0, 1, 1), lattice(1, 1, 1), f.x);
    return glm::mix(glm::mix(x00, x10, f.y), glm::mix(x01, x11, f.y), f.z);
}

// ---- The cut at the ground ---------------------------------------------------------------------

struct Surface {
    std::vector<glm::vec3> positions, normals;
    std::vector<uint32_t> indices;
};

// Keeps the part with y > 0. A triangle crossing the ground is cut along y = 0; the cut vertex of
// each crossing edge is shared by the triangles on both sides of that edge, so the surface stays
// closed along every edge that is not on the ground.
Surface cutAtGround(const Surface& in) {
    Surface out;
    std::vector<int64_t> kept(in.positions.size(), -1);
    auto keep = [&](uint32_t v) {
        if (kept[v] < 0) {
            kept[v] = int64_t(out.positions.size());
            out.positions.push_back(in.positions[v]);
            out.normals.push_back(in.normals[v]);
        }
        return uint32_t(kept[v]);
    };
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> cuts;
    auto cut = [&](uint32_t above, uint32_t below) {
        const std::pair<uint32_t, uint32_t> key{std::min(above, below), std::max(above, below)};
        const auto found = cuts.find(key);
        if (found != cuts.end())
            return found->second;
        const glm::vec3 a = in.positions[above], b = in.positions[below];
        const float t = a.y / (a.y - b.y); // a.y > 0 >= b.y
        glm::vec3 p = glm::mix(a, b, t);
        p.y = 0.0f;
        out.positions.push_back(p);
        out.normals.push_back(glm::normalize(glm::mix(in.normals[above], in.normals[below], t)));
        const uint32_t index = uint32_t(out.positions.size() - 1);
        cuts.emplace(key, index);
        return index;
    };
    for (size_t i = 0; i < in.indices.size(); i += 3) {
        uint32_t v[3] = {in.indices[i], in.indices[i + 1], in.indices[i + 2]};
        const int above =
            int(in.positions[v[0]].y > 0.0f) + int(in.positions[v[1]].y > 0.0f) + int(in.positions[v[2]].y > 0.0f);
        if (above == 0)
            continue;
        if (above == 3) {
            out.indices.insert(out.indices.end(), {keep(v[0]), keep(v[1]), keep(v[2])});
            continue;
        }
        // Rotate (keeping the winding) so v[0] is the lone vertex above (1) or below (2) ground.
        const bool lonelyAbove = above == 1;
        while ((in.positions[v[0]].y > 0.0f) != lonelyAbove)
            std::rotate(v, v + 1, v + 3);
        if (lonelyAbove) {
            out.indices.insert(out.indices.end(), {keep(v[0]), cut(v[0], v[1]), cut(v[0], v[2])});
        } else {
            // v[0] below, v[1] and v[2] above: the quad v[1], v[2], cut(2-0), cut(1-0).
            const uint32_t c20 = cut(v[2], v[0]), c10 = cut(v[1], v[0]);
            out.indices.insert(out.indices.end(), {keep(v[1]), keep(v[2]), c20, keep(v[1]), c20, c10});
        }
    }
    return out;
}

RockMesh makeRock(uint64_t seed, uint32_t index, const RockParams& params) {
    Random random(splitMix64(seed ^ splitMix64(0x726f636bull + index))); // "rock"
    const float size = random.uniform(params.minSize, params.maxSize);
    const float stretch = random.uniform(1.0f, 1.4f); // horizontal elongation
    const float squash = random.uniform(0.45f, 0.8f); // height over width
    const float heading = random.uniform(0.0f, glm::two_pi<float>());
    const float buried = random.uniform(0.25f, 0.45f); // fraction of the height below ground
    const uint64_t noiseSeed = random.next();
    const glm::vec3 offset1(random.uniform(0.0f, 64.0f), random.uniform(0.0f, 64.0f), random.uniform(0.0f, 64.0f));
    const glm::vec3 offset2(random.uniform(0.0f, 64.0f), random.uniform(0.0f, 64.0f), random.uniform(0.0f, 64.0f));

    TriangleMesh sphere = icosahedron();
    for (uint32_t s = 0; s < params.subdivisions; ++s)
        sphere = subdivide(sphere);

    // Radial displacement by two low-frequency octaves (radius 0.7 .. 1.3: the rock stays star-
    // shaped about its centre, so its faces keep facing outward), then stretch, squash and turn.
    const float c = std::cos(heading), sn = std::sin(heading);
    Surface surface;
    for (const glm::vec3& d : sphere.positions) {
        const float radius = 1.0f + 0.22f * valueNoise(d * 1.3f + offset1, noiseSeed) +
                             0.08f * valueNoise(d * 3.1f + offset2, noiseSeed ^ 0x9e3779b97f4a7c15ull);
        const glm::vec3 p = d * radius * glm::vec3(stretch, squash, 1.0f / stretch);
        surface.positions.push_back({c * p.x + sn * p.z, p.y, -sn * p.x + c * p.z});
    }
    surface.indices = sphere.indices;

    // Area-weighted vertex normals of the whole displaced surface (the cut interpolates them).
    surface.normals.assign(surface.positions.size(), glm::vec3(0.0f));
    for (size_t i = 0; i < surface.indices.size(); i += 3) {
        const uint32_t a = surface.indices[i], b = surface.indices[i + 1], cIndex = surface.indices[i + 2];
        const glm::vec3 n =
            glm::cross(surface.positions[b] - surface.positions[a], surface.positions[cIndex] - surface.positions[a]);
        surface.normals[a] += n;
        surface.normals[b] += n;
        surface.normals[cIndex] += n;
    }
    for (glm::vec3& n : surface.normals)
        n = glm::normalize(n);

    // Half-bury: lower the rock so `buried` of its height is below y = 0, then cut there.
    float lowest = surface.positions[0].y, highest = lowest;
    for (const glm::vec3& p : surface.positions) {
        lowest = std::min(lowest, p.y);
        highest = std::max(highest, p.y);
    }
    const float drop = lowest + buried * (highest - lowest);
    for (glm::vec3& p : surface.positions)
        p.y -= drop;
    Surface above = cutAtGround(surface);

    // Centre the footprint on the origin and scale uniformly to the drawn size (normals keep).
    glm::vec3 lo = above.positions[0], hi = lo;
    for (const glm::vec3& p : above.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const glm::vec2 centre = 0.5f * glm::vec2(lo.x + hi.x, lo.z + hi.z);
    const float scale = size / std::max(hi.x - lo.x, hi.z - lo.z);
    RockMesh rock;
    rock.name = "rock-" + std::to_string(index);
    rock.size = size;
    for (const glm::vec3& p : above.positions) {
        const glm::vec3 q((p.x - centre.x) * scale, p.y * scale, (p.z - centre.y) * scale);
        rock.positions.push_back(q);
        rock.uvs.push_back(glm::clamp(glm::vec2(q.x, q.z) / size + 0.5f, glm::vec2(0.0f), glm::vec2(1.0f)));
    }
    rock.normals = std::move(above.normals);
    rock.indices = std::move(above.indices);
    return rock;
}

} // namespace

RockParams rockParamsForPreset(const std::string& preset) {
    RockParams params;
    if (preset == "ci")
        params.subdivisions = 2;
    else if (preset != "full")
        throw Error("unknown preset '" + preset + "' for rocks (expected ci or full)");
    return params;
}

std::vector<RockMesh> makeRocks(uint64_t seed, uint32_t count, const RockParams& params) {
    if (params.subdivisions < 1 || params.subdivisions > 6)
        throw Error("rocks: " + std::to_string(params.subdivisions) + " subdivisions is outside 1 .. 6");
    if (!std::isfinite(params.minSize) || !std::isfinite(params.maxSize) || !(params.minSize > 0.0f) ||
        !(params.minSize <= params.maxSize))
        throw Error("rocks: sizes " + std::to_string(params.minSize) + " .. " + std::to_string(params.maxSize) +
                    " m are not finite with 0 < min <= max");
    std::vector<RockMesh> rocks;
    for (uint32_t i = 0; i < count; ++i)
        rocks.push_back(makeRock(seed, i, params));
    return rocks;
}

} // namespace meadow
