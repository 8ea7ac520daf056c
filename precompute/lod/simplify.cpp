// Half-edge collapse simplification with an attribute quadric (lod.h).
//
// Why half-edge collapses (each collapse moves a vertex onto a neighbour) rather than full edge
// collapses to an optimal point (Garland & Heckbert 1997): every surviving vertex is an original
// vertex, so its motion rows, rod, light transfer, UV and part stay exact; nothing is averaged or
// re-baked, and a coarse LOD's vertex set is a subset of a fine one's.
//
// Topology works on positions, not vertices: vertices with bitwise-equal positions (and normals
// not facing opposite ways) form one position with several "wedges" (Hoppe 1999), e.g. the two
// sides of a stem's UV seam. A collapse moves a whole position P onto a neighbouring position R;
// each wedge of P must go to the one wedge of R it shares an edge with, so seams collapse along
// themselves, both sides together, and never across (meshoptimizer's seam rule, generalised).
// Position classes, as in meshoptimizer's simplifier: interior, border (exactly two boundary
// edges), locked (non-manifold edges or several boundary loops through one point). A border
// position only slides along a boundary edge onto a border position, so a thin blade's outline
// keeps original boundary vertices; planes through boundary edges perpendicular to their face
// (G&H 1997, section 6.1) make cutting a corner of that outline expensive.
//
// Every collapse must also keep the mesh a manifold (the link condition, Dey et al. 1999), leave
// no vertex without triangles, create no duplicate triangle, and turn no remaining triangle by
// more than acos(minNormalDot) nor against the original surface normal at its corners (no flips,
// no folds of two-sided sheets). A collapse's cost is its quadric error plus the square of the
// surface area it changes (SimplifyOptions::areaWeight): on the boundary planes a border position
// slides along its outline at no cost, which would shorten every blade and petal by its tip.
// Collapses are ordered by cost in a priority queue with lazy invalidation: each position holds
// one candidate (its cheapest valid collapse) and a version; a collapse re-evaluates the positions
// around the kept one.
#include "lod/attribute_quadric.h"
#include "lod/lod.h"

#include "core/error.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <numeric>
#include <queue>
#include <string>
#include <unordered_map>

namespace meadow {

using namespace lod_detail;

namespace {

enum class PositionKind : uint8_t { Interior, Border, Locked };

constexpr uint32_t kNone = 0xffffffffu;
// A triangle whose height is below this fraction of its longest edge counts as degenerate.
constexpr double kMinRelativeHeight = 1e-3;
// Vertices at one position are wedges of one point unless their normals face opposite ways
// (a duplicated back face: two sheets that must stay separate surfaces).
constexpr float kWeldNormalDot = -0.5f;

struct Candidate {
    double cost;
    uint32_t position, target, version;
};

// std::priority_queue keeps the largest on top: "larger" = more expensive, ties broken by index
// so the order never depends on the heap's internals.
struct CandidateOrder {
    bool operator()(const Candidate& a, const Candidate& b) const {
        if (a.cost != b.cost)
            return a.cost > b.cost;
        if (a.position != b.position)
            return a.position > b.position;
        return a.target > b.target;
    }
};

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void validateInput(const SimplifyInput& input) {
    const size_t n = input.positions.size();
    auto fail = [](const std::string& problem) { return Error("simplify: " + problem); };
    if (n == 0 || input.indices.empty())
        throw fail("the mesh has no vertices or no triangles");
    if (n >= kNone)
        throw fail("too many vertices (" + std::to_string(n) + ")");
    if (input.indices.size() % 3 != 0)
        throw fail("index count " + std::to_string(input.indices.size()) + " is not a multiple of 3");
    if (!input.normals.empty() && input.normals.size() != n)
        throw fail(std::to_string(input.normals.size()) + " normals for " + std::to_string(n) + " positions");
    if (!input.uvs.empty() && input.uvs.size() != n)
        throw fail(std::to_string(input.uvs.size()) + " UVs for " + std::to_string(n) + " positions");
    if (!input.collapseGroups.empty() && input.collapseGroups.size() != n)
        throw fail(std::to_string(input.collapseGroups.size()) + " collapse groups for " + std::to_string(n) +
                   " positions");
    for (size_t i = 0; i < input.indices.size(); ++i)
        if (input.indices[i] >= n)
            throw fail("index " + std::to_string(i) + " (triangle " + std::to_string(i / 3) + ") is " +
                       std::to_string(input.indices[i]) + ", the mesh has " + std::to_string(n) + " vertices");
    for (size_t v = 0; v < n; ++v) {
        if (!finite(input.positions[v]))
            throw fail("the position of vertex " + std::to_string(v) + " is not finite");
        if (!input.normals.empty() && !finite(input.normals[v]))
            throw fail("the normal of vertex " + std::to_string(v) + " is not finite");
        if (!input.uvs.empty() && !(std::isfinite(input.uvs[v].x) && std::isfinite(input.uvs[v].y)))
            throw fail("the UV of vertex " + std::to_string(v) + " is not finite");
    }
    for (const AttributeGroup& group : input.attributes) {
        const std::string name = "attribute group '" + group.name + "'";
        if (group.width == 0)
            throw fail(name + " has width 0");
        if (group.values.size() != n * group.width)
            throw fail(name + " holds " + std::to_string(group.values.size()) + " values, expected " +
                       std::to_string(n) + " vertices x " + std::to_string(group.width));
        if (!std::isfinite(group.weight) || group.weight < 0.0f)
            throw fail(name + " has weight " + std::to_string(group.weight) + " (must be finite and >= 0)");
        for (size_t i = 0; i < group.values.size(); ++i)
            if (!std::isfinite(group.values[i]))
                throw fail(name + " value " + std::to_string(i % group.width) + " of vertex " +
                           std::to_string(i / group.width) + " is not finite");
    }
}

void validateOptions(const SimplifyOptions& options) {
    auto check = [](float value, const char* name, float lo, float hi) {
        if (!(value >= lo && value <= hi))
            throw Error(std::string("simplify: option ") + name + " = " + std::to_string(value) + " is outside [" +
                        std::to_string(lo) + ", " + std::to_string(hi) + "]");
    };
    check(options.normalWeight, "normalWeight", 0.0f, 1e6f);
    check(options.uvWeight, "uvWeight", 0.0f, 1e6f);
    check(options.boundaryWeight, "boundaryWeight", 0.0f, 1e6f);
    check(options.minNormalDot, "minNormalDot", -1.0f, 0.99f);
    check(options.areaWeight, "areaWeight", 0.0f, 1e9f);
}

void eraseValue(std::vector<uint32_t>& list, uint32_t value) {
    auto it = std::find(list.begin(), list.end(), value);
    if (it != list.end())
        list.erase(it);
}

} // namespace

struct MeshSimplifier::State {
    SimplifyOptions options;
    uint32_t vertexCount = 0, attributeCount = 0;
    size_t stride = 0;

    // Per vertex (wedge).
    std::vector<uint32_t> positionOf;
    std::vector<uint32_t> group;   // empty: no groups
    std::vector<float> attributes; // attributeCount per vertex, already weighted
    std::vector<double> quadrics;  // stride per vertex
    std::vector<std::vector<uint32_t>> vertexTriangles;
    std::vector<uint32_t> collapsedInto; // itself while alive; kRemovedVertex when removed

    // Per position.
    std::vector<glm::dvec3> point; // centred on the mesh's bounding box, for precision
    std::vector<std::vector<uint32_t>> wedges;
    std::vector<PositionKind> kind;
    std::vector<uint8_t> alive;
    std::vector<uint32_t> version;
    std::vector<glm::dvec3> surfaceNormal; // area-weighted normal of the original faces around it

    std::vector<std::array<uint32_t, 3>> triangles;
    std::vector<uint8_t> triangleAlive;
    uint32_t aliveTriangles = 0;

    std::priority_queue<Candidate, std::vector<Candidate>, CandidateOrder> heap;
    bool enforceGroups = false;
    bool rescanned = false;
    SimplifyStage stage = SimplifyStage::Constrained;
    double maxError = 0.0;
    uint32_t removedComponents = 0;

    // Scratch, reused to avoid allocation in the inner loop.
    std::vector<uint32_t> scratchA, scratchB, scratchC;
    std::vector<std::pair<uint32_t, uint32_t>> wedgeMap;

    State(const SimplifyInput& input, const SimplifyOptions& options);

    std::span<double> quadric(uint32_t v) { return {&quadrics[size_t(v) * stride], stride}; }
    const float* attributesOf(uint32_t v) const { return attributes.data() + size_t(v) * attributeCount; }
    uint32_t positionAt(uint32_t triangle, int corner) const { return positionOf[triangles[triangle][corner]]; }
    bool hasPosition(uint32_t triangle, uint32_t p) const {
        return positionAt(triangle, 0) == p || positionAt(triangle, 1) == p || positionAt(triangle, 2) == p;
    }

    void weldPositions(const SimplifyInput& input);
    void classifyPositions();
    void buildQuadrics();
    void neighbours(uint32_t p, std::vector<uint32_t>& out) const;
    bool mapWedges(uint32_t p, uint32_t r);
    uint32_t edgeTriangleCount(uint32_t p, uint32_t r) const;
    bool isValid(uint32_t p, uint32_t r);
    double quadricCost(uint32_t r);
    double areaChange(uint32_t p, uint32_t r) const;
    double cost(uint32_t p, uint32_t r);
    void updateCandidate(uint32_t p);
    void rescan();
    void collapse(uint32_t p, uint32_t r);
    void removeComponents(uint32_t target);
    SimplifiedMesh snapshot(uint32_t target) const;
};

MeshSimplifier::State::State(const SimplifyInput& input, const SimplifyOptions& opts) : options(opts) {
    vertexCount = uint32_t(input.positions.size());
    if (!input.normals.empty() && options.normalWeight > 0.0f)
        attributeCount += 3;
    if (!input.uvs.empty() && options.uvWeight > 0.0f)
        attributeCount += 2;
    for (const AttributeGroup& g : input.attributes)
        if (g.weight > 0.0f)
            attributeCount += g.width;
    stride = quadricStride(attributeCount);

    attributes.resize(size_t(vertexCount) * attributeCount);
    for (uint32_t v = 0; v < vertexCount; ++v) {
        float* out = attributes.data() + size_t(v) * attributeCount;
        if (!input.normals.empty() && options.normalWeight > 0.0f)
            for (int k = 0; k < 3; ++k)
                *out++ = input.normals[v][k] * options.normalWeight;
        if (!input.uvs.empty() && options.uvWeight > 0.0f)
            for (int k = 0; k < 2; ++k)
                *out++ = input.uvs[v][k] * options.uvWeight;
        for (const AttributeGroup& g : input.attributes)
            if (g.weight > 0.0f)
                for (uint32_t k = 0; k < g.width; ++k)
                    *out++ = g.values[size_t(v) * g.width + k] * g.weight;
    }
    if (!input.collapseGroups.empty())
        group.assign(input.collapseGroups.begin(), input.collapseGroups.end());
    enforceGroups = options.separateGroups && !group.empty();

    weldPositions(input);

    // Triangles with two corners at one position have no area and no place in a manifold; they
    // are dropped here (they would be the first thing any simplification removes).
    const size_t triangleCount = input.indices.size() / 3;
    triangles.resize(triangleCount);
    triangleAlive.assign(triangleCount, 0);
    vertexTriangles.resize(vertexCount);
    for (size_t t = 0; t < triangleCount; ++t) {
        triangles[t] = {input.indices[3 * t], input.indices[3 * t + 1], input.indices[3 * t + 2]};
        const uint32_t a = positionAt(uint32_t(t), 0), b = positionAt(uint32_t(t), 1), c = positionAt(uint32_t(t), 2);
        if (a == b || b == c || a == c)
            continue;
        triangleAlive[t] = 1;
        ++aliveTriangles;
        for (uint32_t v : triangles[t])
            vertexTriangles[v].push_back(uint32_t(t));
    }
    collapsedInto.resize(vertexCount);
    std::iota(collapsedInto.begin(), collapsedInto.end(), 0u);

    classifyPositions();
    buildQuadrics();
    rescan();
}

void MeshSimplifier::State::weldPositions(const SimplifyInput& input) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& p : input.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const glm::dvec3 centre = 0.5 * (glm::dvec3(lo) + glm::dvec3(hi));
    struct KeyHash {
        size_t operator()(const std::array<uint32_t, 3>& k) const {
            return size_t(k[0] * 73856093u ^ k[1] * 19349663u ^ k[2] * 83492791u);
        }
    };
    // Positions are assigned in vertex order and the map is only looked up, never iterated, so
    // the numbering is deterministic.
    std::unordered_map<std::array<uint32_t, 3>, std::vector<uint32_t>, KeyHash> byBits;
    positionOf.resize(vertexCount);
    for (uint32_t v = 0; v < vertexCount; ++v) {
        const glm::vec3 p = input.positions[v] + glm::vec3(0.0f); // -0 becomes +0
        const std::array<uint32_t, 3> key{std::bit_cast<uint32_t>(p.x), std::bit_cast<uint32_t>(p.y),
                                          std::bit_cast<uint32_t>(p.z)};
        std::vector<uint32_t>& candidates = byBits[key];
        uint32_t found = kNone;
        for (uint32_t position : candidates) {
            const uint32_t first = wedges[position][0];
            if (input.normals.empty() || glm::dot(input.normals[v], input.normals[first]) >= kWeldNormalDot) {
                found = position;
                break;
            }
        }
        if (found == kNone) {
            found = uint32_t(point.size());
            point.push_back(glm::dvec3(input.positions[v]) - centre);
            wedges.emplace_back();
            candidates.push_back(found);
        }
        wedges[found].push_back(v);
        positionOf[v] = found;
    }
    const size_t positions = point.size();
    kind.assign(positions, PositionKind::Interior);
    alive.assign(positions, 1);
    version.assign(positions, 0);
    surfaceNormal.assign(positions, glm::dvec3(0.0));
}

void MeshSimplifier::State::classifyPositions() {
    // Position-level edges: (smaller, larger) -> number of triangles using it.
    std::vector<uint64_t> edges;
    edges.reserve(size_t(aliveTriangles) * 3);
    for (uint32_t t = 0; t < triangles.size(); ++t) {
        if (!triangleAlive[t])
            continue;
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = positionAt(t, k), b = positionAt(t, (k + 1) % 3);
            edges.push_back(uint64_t(std::min(a, b)) << 32 | std::max(a, b));
        }
        const glm::dvec3 n = glm::cross(point[positionAt(t, 1)] - point[positionAt(t, 0)],
                                        point[positionAt(t, 2)] - point[positionAt(t, 0)]);
        for (int k = 0; k < 3; ++k)
            surfaceNormal[positionAt(t, k)] += n;
    }
    for (glm::dvec3& n : surfaceNormal) {
        const double length = glm::length(n);
        n = length > 0.0 ? n / length : glm::dvec3(0.0);
    }
    std::sort(edges.begin(), edges.end());
    std::vector<uint32_t> borderEdges(point.size(), 0);
    for (size_t i = 0; i < edges.size();) {
        size_t j = i;
        while (j < edges.size() && edges[j] == edges[i])
            ++j;
        const uint32_t a = uint32_t(edges[i] >> 32), b = uint32_t(edges[i] & 0xffffffffu);
        if (j - i == 1) {
            ++borderEdges[a];
            ++borderEdges[b];
        } else if (j - i > 2) {
            kind[a] = kind[b] = PositionKind::Locked;
        }
        i = j;
    }
    for (size_t p = 0; p < point.size(); ++p) {
        if (kind[p] == PositionKind::Locked)
            continue;
        if (borderEdges[p] == 2)
            kind[p] = PositionKind::Border;
        else if (borderEdges[p] != 0)
            kind[p] = PositionKind::Locked; // several boundary loops meet here
    }
}

void MeshSimplifier::State::buildQuadrics() {
    quadrics.assign(size_t(vertexCount) * stride, 0.0);
    for (uint32_t t = 0; t < triangles.size(); ++t) {
        if (!triangleAlive[t])
            continue;
        const std::array<uint32_t, 3>& tri = triangles[t];
        const glm::dvec3 p[3] = {point[positionOf[tri[0]]], point[positionOf[tri[1]]], point[positionOf[tri[2]]]};
        const float* s[3] = {attributesOf(tri[0]), attributesOf(tri[1]), attributesOf(tri[2])};
        const glm::dvec3 cross = glm::cross(p[1] - p[0], p[2] - p[0]);
        const double area = 0.5 * glm::length(cross);
        for (uint32_t v : tri)
            addFaceQuadric(quadric(v), p, s, attributeCount, area);
        if (options.boundaryWeight <= 0.0f || area <= 0.0)
            continue;
        const glm::dvec3 faceNormal = cross / (2.0 * area);
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = positionAt(t, k), b = positionAt(t, (k + 1) % 3);
            if (edgeTriangleCount(a, b) != 1)
                continue;
            const glm::dvec3 edge = point[b] - point[a];
            const double length = glm::length(edge);
            if (!(length > 0.0))
                continue;
            const glm::dvec3 planeNormal = glm::normalize(glm::cross(edge, faceNormal));
            const double weight = double(options.boundaryWeight) * length * length;
            addPlaneQuadric(quadric(tri[k]), planeNormal, point[a], weight);
            addPlaneQuadric(quadric(tri[(k + 1) % 3]), planeNormal, point[a], weight);
        }
    }
}

void MeshSimplifier::State::neighbours(uint32_t p, std::vector<uint32_t>& out) const {
    out.clear();
    for (uint32_t w : wedges[p])
        for (uint32_t t : vertexTriangles[w])
            for (int k = 0; k < 3; ++k) {
                const uint32_t q = positionAt(t, k);
                if (q != p)
                    out.push_back(q);
            }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

uint32_t MeshSimplifier::State::edgeTriangleCount(uint32_t p, uint32_t r) const {
    uint32_t count = 0;
    for (uint32_t w : wedges[p])
        for (uint32_t t : vertexTriangles[w])
            count += hasPosition(t, r) ? 1 : 0;
    return count;
}

// Fills wedgeMap with (wedge of p, wedge of r it moves onto): the one wedge of r that shares a
// triangle with it. False if a wedge of p has none or several (it would tear or merge a seam), or
// if groups are enforced and the two wedges belong to different groups.
bool MeshSimplifier::State::mapWedges(uint32_t p, uint32_t r) {
    wedgeMap.clear();
    for (uint32_t w : wedges[p]) {
        if (vertexTriangles[w].empty())
            continue;
        uint32_t target = kNone;
        for (uint32_t t : vertexTriangles[w])
            for (uint32_t corner : triangles[t])
                if (positionOf[corner] == r) {
                    if (target != kNone && target != corner)
                        return false;
                    target = corner;
                }
        if (target == kNone)
            return false;
        if (enforceGroups && group[w] != group[target])
            return false;
        wedgeMap.emplace_back(w, target);
    }
    return !wedgeMap.empty();
}

double MeshSimplifier::State::quadricCost(uint32_t r) {
    double total = 0.0;
    for (const auto& [w, target] : wedgeMap)
        total += evaluateQuadric(quadric(w), point[r], attributesOf(target), attributeCount);
    for (uint32_t v : wedges[r])
        if (!vertexTriangles[v].empty())
            total += evaluateQuadric(quadric(v), point[r], attributesOf(v), attributeCount);
    return total;
}

// The mesh's surface area after moving p onto r, less before: the triangles on edge pr vanish, the
// others of p's stretch or shrink.
double MeshSimplifier::State::areaChange(uint32_t p, uint32_t r) const {
    double change = 0.0;
    for (const auto& [w, target] : wedgeMap) {
        (void)target;
        for (uint32_t t : vertexTriangles[w]) {
            const glm::dvec3 a = point[positionAt(t, 0)], b = point[positionAt(t, 1)], c = point[positionAt(t, 2)];
            const double before = 0.5 * glm::length(glm::cross(b - a, c - a));
            if (hasPosition(t, r)) {
                change -= before;
                continue;
            }
            std::array<glm::dvec3, 3> moved{a, b, c};
            for (int k = 0; k < 3; ++k)
                if (positionAt(t, k) == p)
                    moved[k] = point[r];
            change += 0.5 * glm::length(glm::cross(moved[1] - moved[0], moved[2] - moved[0])) - before;
        }
    }
    return change;
}

// The quadric's error plus the area term (SimplifyOptions::areaWeight). Expects wedgeMap for (p, r).
double MeshSimplifier::State::cost(uint32_t p, uint32_t r) {
    const double total = quadricCost(r);
    if (options.areaWeight <= 0.0f)
        return total;
    const double change = areaChange(p, r);
    return total + double(options.areaWeight) * change * change;
}

// The topological and geometric rules of the file comment. Expects wedgeMap for (p, r).
bool MeshSimplifier::State::isValid(uint32_t p, uint32_t r) {
    if (!alive[p] || !alive[r] || kind[p] == PositionKind::Locked)
        return false;
    const uint32_t shared = edgeTriangleCount(p, r);
    if (shared == 0)
        return false;
    if (kind[p] == PositionKind::Border && shared != 1)
        return false; // a border point only slides along its boundary

    // Something must survive, and no corner of a removed triangle may be left without triangles.
    bool survivor = false;
    for (uint32_t w : wedges[p])
        for (uint32_t t : vertexTriangles[w])
            survivor = survivor || !hasPosition(t, r);
    for (uint32_t v : wedges[r])
        for (uint32_t t : vertexTriangles[v])
            survivor = survivor || !hasPosition(t, p);
    if (!survivor)
        return false;

    // Link condition: the common neighbours of p and r are exactly the third corners of the
    // triangles on edge pr.
    std::vector<uint32_t>& opposite = scratchC;
    opposite.clear();
    for (uint32_t w : wedges[p])
        for (uint32_t t : vertexTriangles[w]) {
            if (!hasPosition(t, r))
                continue;
            for (uint32_t corner : triangles[t]) {
                const uint32_t q = positionOf[corner];
                if (q == p || q == r)
                    continue;
                opposite.push_back(q);
                uint32_t remaining = 0; // triangles of this corner that stay
                for (uint32_t u : vertexTriangles[corner])
                    remaining += (hasPosition(u, p) && hasPosition(u, r)) ? 0 : 1;
                if (remaining == 0)
                    return false;
            }
        }
    std::sort(opposite.begin(), opposite.end());
    neighbours(p, scratchA);
    neighbours(r, scratchB);
    size_t common = 0, i = 0, j = 0;
    while (i < scratchA.size() && j < scratchB.size()) {
        if (scratchA[i] < scratchB[j]) {
            ++i;
        } else if (scratchB[j] < scratchA[i]) {
            ++j;
        } else {
            if (!std::binary_search(opposite.begin(), opposite.end(), scratchA[i]))
                return false;
            ++common;
            ++i;
            ++j;
        }
    }
    if (common != size_t(std::unique(opposite.begin(), opposite.end()) - opposite.begin()))
        return false;

    // Geometry of every triangle that moves.
    for (const auto& [w, target] : wedgeMap) {
        (void)target;
        for (uint32_t t : vertexTriangles[w]) {
            if (hasPosition(t, r))
                continue;
            std::array<uint32_t, 3> corners{positionAt(t, 0), positionAt(t, 1), positionAt(t, 2)};
            const glm::dvec3 before =
                glm::cross(point[corners[1]] - point[corners[0]], point[corners[2]] - point[corners[0]]);
            for (uint32_t& c : corners)
                if (c == p)
                    c = r;
            const glm::dvec3 a = point[corners[0]], b = point[corners[1]], c = point[corners[2]];
            const glm::dvec3 after = glm::cross(b - a, c - a);
            const double longest = std::max({glm::dot(b - a, b - a), glm::dot(c - b, c - b), glm::dot(a - c, a - c)});
            const double doubleArea = glm::length(after);
            // height = doubleArea / longest edge; compare without the square root.
            if (!(doubleArea > kMinRelativeHeight * longest))
                return false;
            if (glm::dot(after, before) <= double(options.minNormalDot) * doubleArea * glm::length(before))
                return false;
            const glm::dvec3 surface =
                surfaceNormal[corners[0]] + surfaceNormal[corners[1]] + surfaceNormal[corners[2]];
            if (glm::dot(after, surface) <= 0.0)
                return false;
            // No duplicate: r must not already have a triangle on the same three points.
            for (uint32_t v : wedges[r])
                for (uint32_t u : vertexTriangles[v])
                    if (hasPosition(u, corners[0]) && hasPosition(u, corners[1]) && hasPosition(u, corners[2]))
                        return false;
        }
    }
    return true;
}

void MeshSimplifier::State::updateCandidate(uint32_t p) {
    ++version[p];
    if (!alive[p] || kind[p] == PositionKind::Locked)
        return;
    std::vector<uint32_t> around;
    neighbours(p, around);
    std::vector<std::pair<double, uint32_t>> options;
    options.reserve(around.size());
    for (uint32_t r : around) {
        if (kind[p] == PositionKind::Border && edgeTriangleCount(p, r) != 1)
            continue;
        if (!mapWedges(p, r))
            continue;
        options.emplace_back(cost(p, r), r);
    }
    std::sort(options.begin(), options.end());
    for (const auto& [c, r] : options) {
        if (mapWedges(p, r) && isValid(p, r)) {
            heap.push({c, p, r, version[p]});
            return;
        }
    }
}

void MeshSimplifier::State::rescan() {
    heap = {};
    for (uint32_t p = 0; p < point.size(); ++p)
        updateCandidate(p);
}

void MeshSimplifier::State::collapse(uint32_t p, uint32_t r) {
    // The surface this collapse answers for: the same quadrics cost() evaluates.
    double area = 0.0;
    for (const auto& [w, target] : wedgeMap)
        area += quadricArea(quadric(w));
    for (uint32_t v : wedges[r])
        if (!vertexTriangles[v].empty())
            area += quadricArea(quadric(v));
    const double c = quadricCost(r);
    if (area > 0.0)
        maxError = std::max(maxError, std::sqrt(c / area));

    for (const auto& [w, target] : wedgeMap) {
        const std::vector<uint32_t> moving = vertexTriangles[w];
        for (uint32_t t : moving) {
            if (hasPosition(t, r)) {
                triangleAlive[t] = 0;
                --aliveTriangles;
                for (uint32_t corner : triangles[t])
                    if (corner != w)
                        eraseValue(vertexTriangles[corner], t);
            } else {
                for (uint32_t& corner : triangles[t])
                    if (corner == w)
                        corner = target;
                vertexTriangles[target].push_back(t);
            }
        }
        vertexTriangles[w].clear();
        addQuadric(quadric(target), quadric(w));
        collapsedInto[w] = target;
    }
    alive[p] = 0;
    ++version[p];
    std::vector<uint32_t> around;
    neighbours(r, around);
    updateCandidate(r);
    for (uint32_t q : around)
        updateCandidate(q);
}

// The fallback's last step: whole connected components, until the target is met. Greedy on
// surface kept per triangle spent: the component that stands for the least original area per
// triangle goes first (the area its quadrics stand for, so a blade collapsed to one triangle still
// counts as the blade). On an iris clump that removes style arms, then petals, then stems (a
// tube spends six triangles on a sliver of silhouette), and leaves last.
void MeshSimplifier::State::removeComponents(uint32_t target) {
    std::vector<uint32_t> parent(point.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](uint32_t x) {
        while (parent[x] != x)
            x = parent[x] = parent[parent[x]];
        return x;
    };
    for (uint32_t t = 0; t < triangles.size(); ++t) {
        if (!triangleAlive[t])
            continue;
        for (int k = 1; k < 3; ++k) {
            const uint32_t a = find(positionAt(t, 0)), b = find(positionAt(t, k));
            if (a != b)
                parent[std::max(a, b)] = std::min(a, b); // the root is the smallest position
        }
    }
    std::vector<double> area(point.size(), 0.0);
    std::vector<uint32_t> triangleCount(point.size(), 0);
    for (uint32_t v = 0; v < vertexCount; ++v)
        if (!vertexTriangles[v].empty())
            area[find(positionOf[v])] += quadricArea(quadric(v));
    for (uint32_t t = 0; t < triangles.size(); ++t)
        if (triangleAlive[t])
            ++triangleCount[find(positionAt(t, 0))];
    std::vector<uint32_t> roots;
    for (uint32_t p = 0; p < point.size(); ++p)
        if (triangleCount[p] > 0 && find(p) == p)
            roots.push_back(p);
    std::sort(roots.begin(), roots.end(), [&](uint32_t a, uint32_t b) {
        const double da = area[a] / triangleCount[a], db = area[b] / triangleCount[b];
        return da != db ? da < db : a < b;
    });
    std::vector<uint8_t> removed(point.size(), 0);
    for (uint32_t root : roots) {
        // Keep the last component: an empty LOD is never what a caller wants.
        if (aliveTriangles <= target || triangleCount[root] >= aliveTriangles)
            break;
        removed[root] = 1;
        aliveTriangles -= triangleCount[root];
        ++removedComponents;
    }
    for (uint32_t t = 0; t < triangles.size(); ++t)
        if (triangleAlive[t] && removed[find(positionAt(t, 0))])
            triangleAlive[t] = 0;
    for (uint32_t v = 0; v < vertexCount; ++v) {
        if (vertexTriangles[v].empty() || !removed[find(positionOf[v])])
            continue;
        vertexTriangles[v].clear();
        collapsedInto[v] = kRemovedVertex;
        alive[positionOf[v]] = 0;
    }
    heap = {};
}

SimplifiedMesh MeshSimplifier::State::snapshot(uint32_t target) const {
    SimplifiedMesh result;
    result.targetTriangles = target;
    result.error = float(maxError);
    result.stage = stage;
    result.removedComponents = removedComponents;
    std::vector<uint32_t> local(vertexCount, kNone);
    for (uint32_t v = 0; v < vertexCount; ++v)
        if (!vertexTriangles[v].empty()) {
            local[v] = uint32_t(result.keptVertices.size());
            result.keptVertices.push_back(v);
        }
    result.indices.reserve(size_t(aliveTriangles) * 3);
    for (uint32_t t = 0; t < triangles.size(); ++t)
        if (triangleAlive[t])
            for (uint32_t v : triangles[t])
                result.indices.push_back(local[v]);
    result.representative.resize(vertexCount);
    for (uint32_t v = 0; v < vertexCount; ++v) {
        uint32_t x = v;
        while (x != kRemovedVertex && collapsedInto[x] != x)
            x = collapsedInto[x];
        result.representative[v] = (x != kRemovedVertex && local[x] != kNone) ? x : kRemovedVertex;
    }
    return result;
}

MeshSimplifier::MeshSimplifier(const SimplifyInput& input, const SimplifyOptions& options) {
    validateInput(input);
    validateOptions(options);
    state_ = std::make_unique<State>(input, options);
}

MeshSimplifier::~MeshSimplifier() = default;

SimplifiedMesh MeshSimplifier::simplifyTo(uint32_t targetTriangles) {
    if (targetTriangles == 0)
        throw Error("simplify: the target triangle count is 0 (a LOD needs at least one triangle)");
    State& s = *state_;
    while (s.aliveTriangles > targetTriangles) {
        if (s.heap.empty()) {
            if (!s.rescanned) {
                // Lazy updates can miss a collapse made valid by a change two rings away.
                s.rescan();
                s.rescanned = true;
                continue;
            }
            if (!s.options.allowFallback)
                break;
            if (s.enforceGroups) {
                s.enforceGroups = false;
                s.stage = SimplifyStage::GroupsRelaxed;
                s.rescan();
                continue;
            }
            s.removeComponents(targetTriangles);
            s.stage = SimplifyStage::ComponentsRemoved;
            break;
        }
        const Candidate top = s.heap.top();
        s.heap.pop();
        const uint32_t p = top.position, r = top.target;
        if (top.version != s.version[p] || !s.alive[p] || !s.alive[r])
            continue;
        if (!s.mapWedges(p, r) || !s.isValid(p, r) || s.cost(p, r) != top.cost) {
            s.updateCandidate(p);
            continue;
        }
        s.collapse(p, r);
        s.rescanned = false;
    }
    return s.snapshot(targetTriangles);
}

SimplifiedMesh simplifyMesh(const SimplifyInput& input, uint32_t targetTriangles, const SimplifyOptions& options) {
    if (targetTriangles == 0)
        throw Error("simplify: the target triangle count is 0 (a LOD needs at least one triangle)");
    return MeshSimplifier(input, options).simplifyTo(targetTriangles);
}

} // namespace meadow
