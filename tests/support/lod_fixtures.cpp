#include "lod_fixtures.h"

#include "plants/iris.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

namespace meadow::test {

SimplifyInput TestMesh::input() const {
    SimplifyInput in;
    in.positions = positions;
    in.normals = normals;
    in.uvs = uvs;
    in.indices = indices;
    return in;
}

TestMesh makeGrid(uint32_t cellsX, uint32_t cellsY, float sizeX, float sizeY) {
    TestMesh mesh;
    for (uint32_t y = 0; y <= cellsY; ++y)
        for (uint32_t x = 0; x <= cellsX; ++x) {
            const glm::vec2 uv(float(x) / float(cellsX), float(y) / float(cellsY));
            mesh.positions.emplace_back(uv.x * sizeX, uv.y * sizeY, 0.0f);
            mesh.normals.emplace_back(0.0f, 0.0f, 1.0f);
            mesh.uvs.push_back(uv);
        }
    auto at = [&](uint32_t x, uint32_t y) { return y * (cellsX + 1) + x; };
    for (uint32_t y = 0; y < cellsY; ++y)
        for (uint32_t x = 0; x < cellsX; ++x)
            mesh.indices.insert(mesh.indices.end(),
                                {at(x, y), at(x + 1, y), at(x + 1, y + 1), at(x, y), at(x + 1, y + 1), at(x, y + 1)});
    return mesh;
}

TestMesh makeIcosphere(uint32_t subdivisions) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<glm::vec3> p = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    for (glm::vec3& v : p)
        v = glm::normalize(v);
    std::vector<uint32_t> tri = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                                 4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                                 6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
    for (uint32_t s = 0; s < subdivisions; ++s) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> middle;
        auto mid = [&](uint32_t a, uint32_t b) {
            const auto key = std::minmax(a, b);
            auto it = middle.find(key);
            if (it != middle.end())
                return it->second;
            p.push_back(glm::normalize(p[a] + p[b]));
            return middle[key] = uint32_t(p.size() - 1);
        };
        std::vector<uint32_t> next;
        for (size_t i = 0; i < tri.size(); i += 3) {
            const uint32_t a = tri[i], b = tri[i + 1], c = tri[i + 2];
            const uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
            next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        tri = std::move(next);
    }
    TestMesh mesh;
    mesh.positions = p;
    mesh.normals = p;
    mesh.indices = tri;
    return mesh;
}

TestMesh makeTube(uint32_t sides, uint32_t rings) {
    TestMesh mesh;
    for (uint32_t r = 0; r < rings; ++r)
        for (uint32_t c = 0; c <= sides; ++c) {
            const float angle = 2.0f * 3.14159265f * float(c % sides) / float(sides);
            const glm::vec3 n(std::cos(angle), 0.0f, std::sin(angle));
            mesh.positions.push_back(n * 0.05f + glm::vec3(0.0f, float(r) / float(rings - 1), 0.0f));
            mesh.normals.push_back(n);
            mesh.uvs.emplace_back(float(c) / float(sides), float(r) / float(rings - 1));
        }
    auto at = [&](uint32_t r, uint32_t c) { return r * (sides + 1) + c; };
    for (uint32_t r = 0; r + 1 < rings; ++r)
        for (uint32_t c = 0; c < sides; ++c)
            mesh.indices.insert(mesh.indices.end(),
                                {at(r, c), at(r + 1, c), at(r, c + 1), at(r, c + 1), at(r + 1, c), at(r + 1, c + 1)});
    return mesh;
}

namespace {

IrisCase makeIrisCase(const std::string& preset) {
    IrisCase result;
    std::vector<PlantClump> clumps = makeIrisClumps(1, 3, irisParamsForPreset(preset));
    auto largest = std::max_element(clumps.begin(), clumps.end(), [](const PlantClump& a, const PlantClump& b) {
        return a.mesh.vertexCount() < b.mesh.vertexCount();
    });
    result.clump = std::move(*largest);
    const PlantMesh& mesh = result.clump.mesh;
    result.groups = rodGroups(mesh);

    // Irradiance of a unit directional light in 9-coefficient SH (docs/ARCHITECTURE.md, Light
    // transfer: 3/32 + x/2 + 15x^2/32, x the cosine to the light), darker low in the clump as if
    // shaded.
    const glm::vec3 sun = glm::normalize(glm::vec3(0.3f, 0.9f, 0.2f));
    for (size_t v = 0; v < mesh.vertexCount(); ++v) {
        const float x = glm::dot(mesh.normals[v], sun);
        const float shade = 0.4f + 0.6f * std::min(1.0f, std::max(0.0f, mesh.positions[v].y) / 0.8f);
        result.light.push_back((3.0f / 32.0f + x / 2.0f + 15.0f * x * x / 32.0f) * shade);
    }

    // Each rod sways in its own direction and phase, bending quadratically with height: vertices
    // of different rods move independently, as the simulated clumps do.
    const uint32_t frames = 8;
    const float amplitude = 0.08f;
    for (uint32_t f = 0; f < frames; ++f) {
        std::vector<glm::vec3> frame(mesh.vertexCount());
        for (size_t v = 0; v < mesh.vertexCount(); ++v) {
            const uint32_t rodIndex = mesh.skin[v].rod;
            const Rod& rod = result.clump.rods[rodIndex];
            const float heading = 2.39996f * float(rodIndex), phase = 1.7f * float(rodIndex);
            const float s = std::clamp((mesh.positions[v].y - rod.restNodes[0].y) / rodLength(rod), 0.0f, 1.5f);
            const float sway = amplitude * std::sin(6.2831853f * float(f) / float(frames) + phase) * s * s;
            frame[v] = mesh.positions[v] + sway * glm::vec3(std::cos(heading), 0.0f, std::sin(heading));
        }
        result.frames.push_back(std::move(frame));
    }
    for (size_t v = 0; v < mesh.vertexCount(); ++v)
        for (uint32_t f = 0; f < frames; f += frames / 4)
            for (int axis = 0; axis < 3; ++axis)
                result.motion.push_back(result.frames[f][v][axis] - mesh.positions[v][axis]);
    return result;
}

} // namespace

SimplifyInput IrisCase::input() const {
    SimplifyInput in;
    in.positions = clump.mesh.positions;
    in.normals = clump.mesh.normals;
    in.uvs = clump.mesh.uvs;
    in.indices = clump.mesh.indices;
    in.collapseGroups = groups;
    // Light: a difference of the whole range (~1) costs like 5 cm; motion is in metres already.
    in.attributes.push_back({"light", light, 1, 0.05f});
    in.attributes.push_back({"motion", motion, kMotionWidth, 1.0f});
    return in;
}

LodErrorInput IrisCase::errorInput() const {
    LodErrorInput in;
    in.positions = clump.mesh.positions;
    in.indices = clump.mesh.indices;
    in.lightScalar = light;
    in.frames = frames;
    return in;
}

const IrisCase& irisCase(const std::string& preset) {
    static std::mutex mutex;
    static std::map<std::string, IrisCase> cases;
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cases.find(preset);
    if (it == cases.end())
        it = cases.emplace(preset, makeIrisCase(preset)).first;
    return it->second;
}

std::vector<glm::vec3> surfaceNormals(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices) {
    auto key = [](const glm::vec3& p) { return std::make_tuple(p.x + 0.0f, p.y + 0.0f, p.z + 0.0f); };
    std::map<std::tuple<float, float, float>, glm::vec3> sum;
    for (size_t i = 0; i < indices.size(); i += 3) {
        const glm::vec3 a = positions[indices[i]], b = positions[indices[i + 1]], c = positions[indices[i + 2]];
        const glm::vec3 n = glm::cross(b - a, c - a);
        for (const glm::vec3& p : {a, b, c})
            sum[key(p)] += n;
    }
    std::vector<glm::vec3> normals(positions.size(), glm::vec3(0.0f));
    for (size_t v = 0; v < positions.size(); ++v) {
        auto it = sum.find(key(positions[v]));
        if (it != sum.end() && glm::length(it->second) > 0.0f)
            normals[v] = glm::normalize(it->second);
    }
    return normals;
}

std::vector<uint32_t> originalIndices(const std::vector<uint32_t>& vertices, const std::vector<uint32_t>& indices) {
    std::vector<uint32_t> result(indices.size());
    for (size_t i = 0; i < indices.size(); ++i)
        result[i] = vertices[indices[i]];
    return result;
}

std::vector<std::pair<uint32_t, uint32_t>> boundaryEdges(const std::vector<uint32_t>& indices) {
    std::map<std::pair<uint32_t, uint32_t>, int> count;
    for (size_t i = 0; i < indices.size(); i += 3)
        for (int k = 0; k < 3; ++k)
            ++count[std::minmax(indices[i + k], indices[i + (k + 1) % 3])];
    std::vector<std::pair<uint32_t, uint32_t>> result;
    for (const auto& [edge, n] : count)
        if (n == 1)
            result.push_back(edge);
    return result;
}

} // namespace meadow::test
