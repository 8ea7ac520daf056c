#include "iris.h"

#include "atlas.h"
#include "core/error.h"
#include "core/random.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <glm/gtc/constants.hpp>

namespace meadow {
namespace {

constexpr float kPi = glm::pi<float>();
constexpr glm::vec3 kUp{0.0f, 1.0f, 0.0f};

float radians(float degrees) {
    return degrees * (kPi / 180.0f);
}

float smoothStep(float edge0, float edge1, float x) {
    float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// Rotates v about the unit axis by angle (Rodrigues).
glm::vec3 rotate(const glm::vec3& v, const glm::vec3& axis, float angle) {
    float c = std::cos(angle), s = std::sin(angle);
    return v * c + glm::cross(axis, v) * s + axis * (glm::dot(axis, v) * (1.0f - c));
}

// A curve given by its unit direction as a function of arc length fraction s in [0, 1],
// integrated into a dense polyline so positions are exact in arc length (segment lengths
// equal), which makes rod nodes evenly spaced.
class Spine {
  public:
    Spine(glm::vec3 start, float length, const std::function<glm::vec3(float)>& direction) : length_(length) {
        points_.resize(kSteps + 1);
        directions_.resize(kSteps + 1);
        points_[0] = start;
        for (uint32_t i = 0; i < kSteps; ++i) {
            float s = (static_cast<float>(i) + 0.5f) / static_cast<float>(kSteps);
            points_[i + 1] = points_[i] + glm::normalize(direction(s)) * (length / static_cast<float>(kSteps));
        }
        for (uint32_t i = 0; i <= kSteps; ++i)
            directions_[i] = glm::normalize(direction(static_cast<float>(i) / static_cast<float>(kSteps)));
    }
    glm::vec3 position(float s) const { return sample(points_, s); }
    glm::vec3 tangent(float s) const { return glm::normalize(sample(directions_, s)); }
    float length() const { return length_; }

  private:
    static constexpr uint32_t kSteps = 96;
    static glm::vec3 sample(const std::vector<glm::vec3>& values, float s) {
        float x = std::clamp(s, 0.0f, 1.0f) * static_cast<float>(kSteps);
        uint32_t i = std::min(static_cast<uint32_t>(x), kSteps - 1);
        return glm::mix(values[i], values[i + 1], x - static_cast<float>(i));
    }
    std::vector<glm::vec3> points_, directions_;
    float length_;
};

// Appends parts to a clump's mesh, binding every vertex as it goes.
class MeshBuilder {
  public:
    explicit MeshBuilder(PlantClump& clump) : clump_(clump) {}

    uint32_t addRod(Rod rod) {
        clump_.rods.push_back(std::move(rod));
        return static_cast<uint32_t>(clump_.rods.size() - 1);
    }

    // Binds a point at arc length fraction s of a rod whose nodes are evenly spaced.
    SkinBinding bindAlong(uint32_t rodIndex, float s, const glm::vec3& position) const {
        const Rod& rod = clump_.rods[rodIndex];
        uint32_t segments = static_cast<uint32_t>(rod.restNodes.size() - 1);
        float x = std::clamp(s, 0.0f, 1.0f) * static_cast<float>(segments);
        uint32_t segment = std::min(static_cast<uint32_t>(x), segments - 1);
        float t = x - static_cast<float>(segment);
        return bindAt(rodIndex, segment, t, position);
    }
    // Binds a point rigidly to node `node` (>= 1) of a rod.
    SkinBinding bindRigid(uint32_t rodIndex, uint32_t node, const glm::vec3& position) const {
        return bindAt(rodIndex, node - 1, 1.0f, position);
    }

    // A grid of rows × columns vertices (row-major), optionally closed by one tip vertex after
    // the last row. Normals are accumulated from the triangles unless given.
    struct Grid {
        uint32_t rows = 0, columns = 0;
        std::vector<glm::vec3> positions; // rows * columns (+ 1 with a tip)
        std::vector<glm::vec2> local;     // part-local (u across, v along) in 0..1
        std::vector<SkinBinding> skin;
        std::vector<glm::vec3> normals; // empty: computed
        bool tip = false;
    };

    void addGrid(const Grid& grid, PartKind part) {
        PlantMesh& mesh = clump_.mesh;
        uint32_t base = static_cast<uint32_t>(mesh.positions.size());
        size_t first = mesh.indices.size();
        auto at = [&](uint32_t r, uint32_t c) { return base + r * grid.columns + c; };
        for (uint32_t r = 0; r + 1 < grid.rows; ++r)
            for (uint32_t c = 0; c + 1 < grid.columns; ++c)
                mesh.indices.insert(mesh.indices.end(), {at(r, c), at(r, c + 1), at(r + 1, c), at(r, c + 1),
                                                         at(r + 1, c + 1), at(r + 1, c)});
        if (grid.tip) {
            uint32_t tipIndex = base + grid.rows * grid.columns;
            for (uint32_t c = 0; c + 1 < grid.columns; ++c)
                mesh.indices.insert(mesh.indices.end(), {at(grid.rows - 1, c), at(grid.rows - 1, c + 1), tipIndex});
        }
        AtlasRegion region = irisAtlasRegion(part);
        for (size_t i = 0; i < grid.positions.size(); ++i) {
            mesh.positions.push_back(grid.positions[i]);
            mesh.uvs.push_back(region.map(grid.local[i]));
            mesh.skin.push_back(grid.skin[i]);
            mesh.parts.push_back(part);
        }
        if (!grid.normals.empty()) {
            mesh.normals.insert(mesh.normals.end(), grid.normals.begin(), grid.normals.end());
            return;
        }
        std::vector<glm::vec3> sum(grid.positions.size(), glm::vec3(0.0f));
        for (size_t i = first; i < mesh.indices.size(); i += 3) {
            uint32_t a = mesh.indices[i] - base, b = mesh.indices[i + 1] - base, c = mesh.indices[i + 2] - base;
            // Area-weighted: the cross product's length is twice the triangle's area.
            glm::vec3 n = glm::cross(grid.positions[b] - grid.positions[a], grid.positions[c] - grid.positions[a]);
            sum[a] += n;
            sum[b] += n;
            sum[c] += n;
        }
        for (const glm::vec3& n : sum)
            mesh.normals.push_back(glm::normalize(n));
    }

  private:
    SkinBinding bindAt(uint32_t rodIndex, uint32_t segment, float t, const glm::vec3& position) const {
        const Rod& rod = clump_.rods[rodIndex];
        glm::vec3 onRod = glm::mix(rod.restNodes[segment], rod.restNodes[segment + 1], t);
        return SkinBinding{rodIndex, segment, t, position - onRod};
    }
    PlantClump& clump_;
};

// Shape constants of garden bearded irises (Iris germanica hybrids), in metres.
constexpr float kLeafWidthMin = 0.02f, kLeafWidthMax = 0.04f;
constexpr float kLeafLengthMin = 0.42f, kLeafLengthMax = 0.88f; // inside the 0.4–0.9 m of DESIGN 2.1
constexpr float kLeafThickness = 0.0015f;
constexpr float kStemLengthMin = 0.5f, kStemLengthMax = 0.9f;
constexpr float kRhizomeSpacingMin = 0.04f, kRhizomeSpacingMax = 0.075f;

// Sword shape: a narrower clasping base, parallel sides, a long taper to the point.
float leafWidthProfile(float s) {
    if (s < 0.6f)
        return 0.55f + 0.45f * smoothStep(0.0f, 0.14f, s);
    return std::pow((1.0f - s) / 0.4f, 0.75f);
}

void addLeaf(MeshBuilder& builder, Random& rng, const IrisParams& params, uint32_t plant, glm::vec3 rhizome,
             glm::vec3 fan, float fanPosition, float length, float& topHeight) {
    glm::vec3 fanNormal = glm::normalize(glm::cross(fan, kUp));
    float lean = fanPosition * radians(rng.uniform(16.0f, 26.0f)) + radians(rng.uniform(-4.0f, 4.0f));
    // Outer leaves arch outwards in the fan's plane and droop a little out of it; the inner,
    // youngest leaves stay nearly straight.
    float side = fanPosition < 0.0f ? -1.0f : 1.0f;
    float archIn = side * std::abs(fanPosition) * radians(rng.uniform(8.0f, 24.0f));
    float archOut = radians(rng.uniform(-18.0f, 18.0f)) * (0.3f + std::abs(fanPosition));
    float twist = radians(rng.uniform(-25.0f, 25.0f));
    float width = rng.uniform(kLeafWidthMin, kLeafWidthMax);
    // Leaves are equitant: each clasps the next at the base, so their bases sit side by side
    // along the fan and a few millimetres apart across it.
    glm::vec3 base = rhizome + fan * (fanPosition * 0.012f) + fanNormal * rng.uniform(-0.003f, 0.003f);

    Spine spine(base, length, [&](float s) {
        float theta = lean + archIn * s * s;
        float psi = archOut * s * s;
        return std::cos(psi) * (std::cos(theta) * kUp + std::sin(theta) * fan) + std::sin(psi) * fanNormal;
    });
    auto frame = [&](float s, glm::vec3& sideDir, glm::vec3& normal) {
        glm::vec3 tangent = spine.tangent(s);
        sideDir = glm::normalize(glm::cross(tangent, fanNormal));
        sideDir = rotate(sideDir, tangent, twist * s);
        normal = glm::cross(sideDir, tangent);
    };

    Rod rod;
    rod.kind = RodKind::Leaf;
    rod.plant = plant;
    rod.thickness = kLeafThickness;
    for (uint32_t k = 0; k < params.leafNodes; ++k) {
        float s = static_cast<float>(k) / static_cast<float>(params.leafNodes - 1);
        rod.restNodes.push_back(spine.position(s));
        // The tip has no width; keep a small collision radius there.
        rod.width.push_back(std::max(width * leafWidthProfile(s), 0.002f));
    }
    uint32_t rodIndex = builder.addRod(std::move(rod));

    MeshBuilder::Grid grid;
    grid.rows = params.leafRows;
    grid.columns = params.leafColumns;
    grid.tip = true;
    for (uint32_t r = 0; r < grid.rows; ++r) {
        float s = static_cast<float>(r) / static_cast<float>(grid.rows);
        glm::vec3 sideDir, normal;
        frame(s, sideDir, normal);
        float halfWidth = 0.5f * width * leafWidthProfile(s);
        // Folded along the midrib: strongly at the clasping base, a shallow keel above.
        float fold = 0.2f + 0.6f * (1.0f - smoothStep(0.0f, 0.25f, s));
        for (uint32_t c = 0; c < grid.columns; ++c) {
            float u = static_cast<float>(c) / static_cast<float>(grid.columns - 1) * 2.0f - 1.0f;
            glm::vec3 p =
                spine.position(s) + sideDir * (u * halfWidth) - normal * (fold * halfWidth * (1.0f - std::abs(u)));
            grid.positions.push_back(p);
            grid.local.emplace_back(0.5f * (u + 1.0f), s);
            grid.skin.push_back(builder.bindAlong(rodIndex, s, p));
            topHeight = std::max(topHeight, p.y);
        }
    }
    glm::vec3 tip = spine.position(1.0f);
    grid.positions.push_back(tip);
    grid.local.emplace_back(0.5f, 1.0f);
    grid.skin.push_back(builder.bindAlong(rodIndex, 1.0f, tip));
    topHeight = std::max(topHeight, tip.y);
    builder.addGrid(grid, PartKind::Leaf);
}

// A closed tube around a spine (stems, pedicels), with radial normals so it shades round. The
// seam column is duplicated so u runs 0..1 around it.
void addTube(MeshBuilder& builder, const Spine& spine, uint32_t rings, uint32_t sides,
             const std::function<float(float)>& radius, const std::function<SkinBinding(float, glm::vec3)>& bind) {
    MeshBuilder::Grid grid;
    grid.rows = rings;
    grid.columns = sides + 1;
    for (uint32_t r = 0; r < rings; ++r) {
        float s = static_cast<float>(r) / static_cast<float>(rings - 1);
        glm::vec3 tangent = spine.tangent(s);
        glm::vec3 ref = std::abs(tangent.y) < 0.9f ? kUp : glm::vec3(1.0f, 0.0f, 0.0f);
        glm::vec3 e1 = glm::normalize(glm::cross(tangent, ref));
        glm::vec3 e2 = glm::cross(e1, tangent);
        for (uint32_t c = 0; c <= sides; ++c) {
            float angle = 2.0f * kPi * static_cast<float>(c % sides) / static_cast<float>(sides);
            glm::vec3 n = std::cos(angle) * e1 + std::sin(angle) * e2;
            glm::vec3 p = spine.position(s) + n * radius(s);
            grid.positions.push_back(p);
            grid.normals.push_back(n);
            grid.local.emplace_back(static_cast<float>(c) / static_cast<float>(sides), s);
            grid.skin.push_back(bind(s, p));
        }
    }
    builder.addGrid(grid, PartKind::Stem);
}

// One petal-like sheet leaving the flower centre at azimuth `radial`, its spine in the plane of
// the flower axis and `radial`, climbing at `elevation(v)` (radians above the plane normal to
// the axis).
struct PetalShape {
    float length = 0.0f, width = 0.0f;
    float baseRadius = 0.0f, baseHeight = 0.0f;
    std::function<float(float)> elevation;
    std::function<float(float)> widthProfile;
    float cup = 0.0f;        // edge displacement along the normal, in half widths, times u²
    float ruffle = 0.0f;     // edge wave amplitude, in half widths
    float beardRaise = 0.0f; // a ridge along the haft's midline, in half widths
};

void addPetal(MeshBuilder& builder, Random& rng, const PetalShape& shape, PartKind part, uint32_t rows,
              uint32_t columns, glm::vec3 centre, glm::vec3 axis, glm::vec3 radial,
              const std::function<SkinBinding(glm::vec3)>& bind) {
    glm::vec3 tangential = glm::cross(axis, radial);
    glm::vec3 start = centre + radial * shape.baseRadius + axis * shape.baseHeight;
    Spine spine(start, shape.length, [&](float v) {
        float a = shape.elevation(v);
        return std::cos(a) * radial + std::sin(a) * axis;
    });
    float rufflePhase = rng.uniform(0.0f, 2.0f * kPi);
    float ruffleFrequency = rng.uniform(14.0f, 20.0f);
    MeshBuilder::Grid grid;
    grid.rows = rows;
    grid.columns = columns;
    for (uint32_t r = 0; r < rows; ++r) {
        float v = static_cast<float>(r) / static_cast<float>(rows - 1);
        glm::vec3 direction = spine.tangent(v);
        glm::vec3 normal = glm::cross(direction, tangential);
        float halfWidth = 0.5f * shape.width * shape.widthProfile(v);
        for (uint32_t c = 0; c < columns; ++c) {
            float u = static_cast<float>(c) / static_cast<float>(columns - 1) * 2.0f - 1.0f;
            float lift = shape.cup * u * u +
                         shape.ruffle * std::abs(u * u * u) * std::sin(ruffleFrequency * v + rufflePhase) +
                         shape.beardRaise * std::exp(-u * u / 0.08f) * (1.0f - smoothStep(0.3f, 0.5f, v));
            glm::vec3 p = spine.position(v) + tangential * (u * halfWidth) + normal * (lift * halfWidth);
            grid.positions.push_back(p);
            grid.local.emplace_back(0.5f * (u + 1.0f), v);
            grid.skin.push_back(bind(p));
        }
    }
    builder.addGrid(grid, part);
}

// Three falls, three standards and three style arms around `axis` at `centre`.
void addFlower(MeshBuilder& builder, Random& rng, const IrisParams& params, glm::vec3 centre, glm::vec3 axis,
               float scale, const std::function<SkinBinding(glm::vec3)>& bind) {
    glm::vec3 ref = std::abs(axis.y) < 0.9f ? kUp : glm::vec3(1.0f, 0.0f, 0.0f);
    glm::vec3 e1 = glm::normalize(glm::cross(axis, ref));
    glm::vec3 e2 = glm::cross(axis, e1);
    float phase = rng.uniform(0.0f, 2.0f * kPi);
    auto radialAt = [&](float azimuth) { return std::cos(azimuth) * e1 + std::sin(azimuth) * e2; };

    // Falls: the haft rises from the centre, then the blade arches over and hangs down.
    PetalShape fall;
    fall.baseRadius = 0.004f * scale;
    fall.baseHeight = 0.004f * scale;
    fall.widthProfile = [](float v) { return std::max(0.16f, std::sqrt(std::sin(kPi * std::pow(v, 1.4f)))); };
    fall.cup = -0.3f;
    fall.ruffle = 0.1f;
    fall.beardRaise = 0.12f;
    // Standards: upright, curving in at the top so the three meet in a dome, edges cupped inward.
    PetalShape standard;
    standard.baseRadius = 0.003f * scale;
    standard.baseHeight = 0.012f * scale;
    standard.widthProfile = [](float v) { return std::max(0.16f, std::sqrt(std::sin(kPi * std::pow(v, 1.25f)))); };
    standard.cup = 0.45f;
    standard.ruffle = 0.14f;
    // Style arms: narrow, arching over the haft of each fall, the crest turned up at the end.
    PetalShape styleArm;
    styleArm.baseRadius = 0.002f * scale;
    styleArm.baseHeight = 0.010f * scale;
    styleArm.widthProfile = [](float v) { return 0.55f + 0.45f * v; };
    styleArm.cup = -0.5f;

    for (uint32_t k = 0; k < 3; ++k) {
        float azimuth = phase + 2.0f * kPi * static_cast<float>(k) / 3.0f + radians(rng.uniform(-5.0f, 5.0f));
        float rise = radians(rng.uniform(30.0f, 42.0f));
        float droop = radians(rng.uniform(95.0f, 125.0f));
        fall.length = 0.08f * scale * rng.uniform(0.94f, 1.06f);
        fall.width = 0.052f * scale * rng.uniform(0.94f, 1.06f);
        fall.elevation = [=](float v) { return rise - droop * std::pow(v, 1.3f); };
        addPetal(builder, rng, fall, PartKind::Fall, params.petalRows, params.petalColumns, centre, axis,
                 radialAt(azimuth), bind);

        float styleRise = radians(rng.uniform(22.0f, 28.0f));
        styleArm.length = 0.03f * scale * rng.uniform(0.94f, 1.06f);
        styleArm.width = 0.018f * scale;
        styleArm.elevation = [=](float v) {
            return styleRise - radians(30.0f) * v + radians(40.0f) * smoothStep(0.65f, 1.0f, v);
        };
        addPetal(builder, rng, styleArm, PartKind::StyleArm, params.styleArmRows, params.styleArmColumns, centre, axis,
                 radialAt(azimuth), bind);

        float standardAzimuth = azimuth + kPi / 3.0f;
        float open = radians(rng.uniform(60.0f, 70.0f));
        float close = radians(rng.uniform(45.0f, 60.0f));
        standard.length = 0.068f * scale * rng.uniform(0.94f, 1.06f);
        standard.width = 0.046f * scale * rng.uniform(0.94f, 1.06f);
        standard.elevation = [=](float v) { return open + close * std::pow(v, 1.5f); };
        addPetal(builder, rng, standard, PartKind::Standard, params.petalRows, params.petalColumns, centre, axis,
                 radialAt(standardAzimuth), bind);
    }
}

void addIris(MeshBuilder& builder, Random& rng, const IrisParams& params, uint32_t plant, glm::vec3 rhizome,
             glm::vec3 outward) {
    float fanAngle = rng.uniform(0.0f, kPi);
    glm::vec3 fan(std::cos(fanAngle), 0.0f, std::sin(fanAngle));

    uint32_t leafCount = 5 + static_cast<uint32_t>(rng.uniform() * 4.0f); // 5..8
    float longest = rng.uniform(0.6f, 0.84f);
    float leafTop = 0.0f;
    for (uint32_t i = 0; i < leafCount; ++i) {
        float fanPosition = static_cast<float>(i) / static_cast<float>(leafCount - 1) * 2.0f - 1.0f;
        // The youngest leaves in the middle of the fan are the longest.
        float length = longest * (1.0f - 0.3f * std::pow(std::abs(fanPosition), 1.5f)) * rng.uniform(0.92f, 1.0f);
        length = std::clamp(length, kLeafLengthMin, kLeafLengthMax);
        addLeaf(builder, rng, params, plant, rhizome, fan, fanPosition, length, leafTop);
    }

    // The stem rises from the middle of the fan a little above the leaves, leaning away from the
    // clump's centre so neighbouring flowers do not sit inside each other.
    float stemLength = std::clamp(leafTop + rng.uniform(0.06f, 0.16f), kStemLengthMin, kStemLengthMax);
    float lean0 = radians(rng.uniform(2.0f, 8.0f));
    float lean1 = radians(rng.uniform(4.0f, 12.0f));
    float azimuthJitter = radians(rng.uniform(-30.0f, 30.0f));
    glm::vec3 leanDir = glm::length(outward) > 1e-4f ? glm::normalize(outward) : fan;
    leanDir = rotate(leanDir, kUp, azimuthJitter);
    Spine stemSpine(rhizome, stemLength, [&](float s) {
        float lean = lean0 + lean1 * s;
        return std::cos(lean) * kUp + std::sin(lean) * leanDir;
    });
    float diameter = rng.uniform(0.006f, 0.009f);
    auto stemDiameter = [&](float s) { return diameter * (1.0f - 0.3f * s); };

    bool secondFlower = rng.uniform() < 0.45f;
    uint32_t sideNode = static_cast<uint32_t>(std::lround(0.68f * static_cast<float>(params.stemNodes - 1)));
    float topFlowerMass = rng.uniform(0.004f, 0.007f);
    float sideFlowerMass = secondFlower ? 0.8f * topFlowerMass : 0.0f;

    Rod rod;
    rod.kind = RodKind::Stem;
    rod.plant = plant;
    rod.thickness = diameter;
    rod.tipMass = topFlowerMass;
    for (uint32_t k = 0; k < params.stemNodes; ++k) {
        float s = static_cast<float>(k) / static_cast<float>(params.stemNodes - 1);
        rod.restNodes.push_back(stemSpine.position(s));
        rod.width.push_back(stemDiameter(s));
        rod.nodeMass.push_back(k == sideNode ? sideFlowerMass : 0.0f);
    }
    uint32_t stemRod = builder.addRod(std::move(rod));
    addTube(
        builder, stemSpine, params.stemRows, params.stemSides, [&](float s) { return 0.5f * stemDiameter(s); },
        [&](float s, glm::vec3 p) { return builder.bindAlong(stemRod, s, p); });

    uint32_t topNode = params.stemNodes - 1;
    auto bindTop = [&](glm::vec3 p) { return builder.bindRigid(stemRod, topNode, p); };
    addFlower(builder, rng, params, stemSpine.position(1.0f), stemSpine.tangent(1.0f), rng.uniform(0.88f, 1.08f),
              bindTop);

    if (secondFlower) {
        // A second bud opens lower down on a short pedicel, turned outwards.
        float s = static_cast<float>(sideNode) / static_cast<float>(params.stemNodes - 1);
        glm::vec3 stemTangent = stemSpine.tangent(s);
        float sideAngle = rng.uniform(0.0f, 2.0f * kPi);
        glm::vec3 sideDir =
            glm::normalize(glm::cross(stemTangent, glm::vec3(std::cos(sideAngle), 0.0f, std::sin(sideAngle))));
        glm::vec3 pedicelDir = glm::normalize(stemTangent + 1.2f * sideDir);
        Spine pedicel(stemSpine.position(s), 0.045f,
                      [&](float v) { return glm::normalize(pedicelDir + stemTangent * v); });
        auto bindSide = [&](glm::vec3 p) { return builder.bindRigid(stemRod, sideNode, p); };
        addTube(
            builder, pedicel, 2, std::max(3u, params.stemSides - 2), [&](float) { return 0.32f * stemDiameter(s); },
            [&](float, glm::vec3 p) { return bindSide(p); });
        addFlower(builder, rng, params, pedicel.position(1.0f), pedicel.tangent(1.0f), rng.uniform(0.8f, 0.95f),
                  bindSide);
    }
}

void checkParams(const IrisParams& p) {
    auto need = [](bool ok, const char* what) {
        if (!ok)
            throw Error(std::string("iris parameters: ") + what);
    };
    need(p.leafRows >= 2, "leafRows must be at least 2");
    need(p.leafColumns >= 3 && p.leafColumns % 2 == 1, "leafColumns must be odd and at least 3");
    need(p.leafNodes >= 3 && p.leafNodes <= 12, "leafNodes must be 3 to 12");
    need(p.stemRows >= 2, "stemRows must be at least 2");
    need(p.stemSides >= 3, "stemSides must be at least 3");
    need(p.stemNodes >= 3 && p.stemNodes <= 12, "stemNodes must be 3 to 12");
    need(p.petalRows >= 2 && p.petalColumns >= 2, "petalRows and petalColumns must be at least 2");
    need(p.styleArmRows >= 2 && p.styleArmColumns >= 2, "styleArmRows and styleArmColumns must be at least 2");
}

PlantClump makeClump(uint64_t seed, uint32_t index, const IrisParams& params) {
    Random rng(splitMix64(seed ^ splitMix64(0x1715c1u + index)));
    PlantClump clump;
    clump.name = "iris-clump-" + std::to_string(index);
    clump.plants = 6 + (rng.uniform() < 0.5f ? 1u : 0u);

    // Rhizomes branch from one another: each new one starts a few centimetres from an earlier
    // one, never closer than kRhizomeSpacingMin to any.
    std::vector<glm::vec3> rhizomes{glm::vec3(0.0f)};
    while (rhizomes.size() < clump.plants) {
        glm::vec3 best(0.0f);
        float bestClearance = -1.0f;
        for (int attempt = 0; attempt < 64 && bestClearance < kRhizomeSpacingMin; ++attempt) {
            const glm::vec3& parent =
                rhizomes[static_cast<size_t>(rng.uniform() * static_cast<float>(rhizomes.size()))];
            float angle = rng.uniform(0.0f, 2.0f * kPi);
            float distance = rng.uniform(kRhizomeSpacingMin + 0.005f, kRhizomeSpacingMax);
            glm::vec3 candidate = parent + distance * glm::vec3(std::cos(angle), 0.0f, std::sin(angle));
            float clearance = 1e9f;
            for (const glm::vec3& r : rhizomes)
                clearance = std::min(clearance, glm::length(candidate - r));
            if (clearance > bestClearance) {
                bestClearance = clearance;
                best = candidate;
            }
        }
        rhizomes.push_back(best);
    }
    glm::vec3 centroid(0.0f);
    for (const glm::vec3& r : rhizomes)
        centroid += r;
    centroid /= static_cast<float>(rhizomes.size());

    MeshBuilder builder(clump);
    for (uint32_t plant = 0; plant < clump.plants; ++plant) {
        Random plantRng(rng.next());
        glm::vec3 rhizome = rhizomes[plant] - centroid;
        addIris(builder, plantRng, params, plant, rhizome, glm::vec3(rhizome.x, 0.0f, rhizome.z));
    }
    return clump;
}

} // namespace

IrisParams irisParamsForPreset(const std::string& preset) {
    if (preset == "full")
        return IrisParams{};
    if (preset == "ci") {
        IrisParams p;
        p.leafRows = 5;
        p.leafColumns = 3;
        p.leafNodes = 7;
        p.stemRows = 5;
        p.stemSides = 4;
        p.stemNodes = 7;
        p.petalRows = 4;
        p.petalColumns = 3;
        p.styleArmRows = 3;
        p.styleArmColumns = 2;
        p.atlasSize = 256;
        return p;
    }
    throw Error("unknown preset '" + preset + "' (use ci or full)");
}

std::vector<PlantClump> makeIrisClumps(uint64_t seed, uint32_t clumpCount, const IrisParams& params) {
    checkParams(params);
    std::vector<PlantClump> clumps;
    clumps.reserve(clumpCount);
    for (uint32_t i = 0; i < clumpCount; ++i)
        clumps.push_back(makeClump(seed, i, params));
    return clumps;
}

} // namespace meadow
