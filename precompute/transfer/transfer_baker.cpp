// The frame bake (transfer.h): checks input, runs the stages of bake_detail.h in order and
// converts the result to the float layouts of transfer.h.
//
//   1. Embree scene: first frame builds it, later frames refill positions and rebuild the BVH.
//   2. Ground grid rays: the grid's direct transfer, needed by step 4 to light the clump from below.
//   3. Vertex rays: direct shadowed transfer of both sides, hit records.
//   4. Interreflection over the records, translucency on every bounce.
//   5. Ground grid bounce: the clump's final exit light gathered by the grid points.
#include "core/error.h"
#include "transfer/bake_detail.h"
#include "transfer/ray_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

namespace meadow::transfer {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

bool inUnitRange(float x) {
    return x >= 0.0f && x <= 1.0f;
} // false for NaN too

void require(bool condition, const std::string& message) {
    if (!condition)
        throw Error("transfer bake settings: " + message);
}

std::vector<float> toFloat(std::span<const double> values) {
    return std::vector<float>(values.begin(), values.end());
}

} // namespace

void checkBakeSettings(const BakeSettings& s) {
    require(s.order >= 1 && s.order <= sh::kMaxOrder,
            "order " + std::to_string(s.order) + " is outside 1.." + std::to_string(sh::kMaxOrder));
    require(s.raysPerVertex >= 8 && s.raysPerVertex <= 65536,
            "raysPerVertex " + std::to_string(s.raysPerVertex) + " is outside 8..65536");
    require(s.bounces <= 16, "bounces " + std::to_string(s.bounces) + " is more than 16");
    require(std::isfinite(s.rayOffset) && s.rayOffset > 0.0f && s.rayOffset < 0.1f,
            "rayOffset " + std::to_string(s.rayOffset) + " m is outside (0, 0.1)");
    for (uint32_t part = 0; part < kPartKindCount; ++part) {
        require(inUnitRange(s.translucency[part]), "translucency of part " + std::to_string(part) + " is " +
                                                       std::to_string(s.translucency[part]) + ", outside [0, 1]");
    }
    for (int c = 0; c < 3; ++c)
        require(inUnitRange(s.groundAlbedo[c]), "groundAlbedo channel " + std::to_string(c) + " is outside [0, 1]");
    require(std::isfinite(s.groundCentre.x) && std::isfinite(s.groundCentre.y), "groundCentre is not finite");
    require(std::isfinite(s.groundGridSize) && s.groundGridSize > 0.0f,
            "groundGridSize " + std::to_string(s.groundGridSize) + " m is not positive");
    require(s.groundGridResolution == 0 || (s.groundGridResolution >= 2 && s.groundGridResolution <= 1024),
            "groundGridResolution " + std::to_string(s.groundGridResolution) + " is neither 0 nor in 2..1024");
    require(s.groundRaysPerPoint >= 8 && s.groundRaysPerPoint <= 65536,
            "groundRaysPerPoint " + std::to_string(s.groundRaysPerPoint) + " is outside 8..65536");
}

std::vector<float> translucencyForParts(std::span<const PartKind> parts, const BakeSettings& settings) {
    std::vector<float> tau(parts.size());
    for (size_t v = 0; v < parts.size(); ++v) {
        const uint32_t part = uint32_t(parts[v]);
        if (part >= kPartKindCount)
            throw Error("transfer bake: vertex " + std::to_string(v) + " has an unknown part kind " +
                        std::to_string(part));
        tau[v] = settings.translucency[part];
    }
    return tau;
}

struct TransferBaker::State {
    BakeSettings settings;
    std::vector<uint32_t> indices;
    std::vector<glm::vec3> albedo;
    std::vector<float> translucency;
    RayScene scene;
    bool sceneBuilt = false;

    State(const BakeSettings& s) : settings(s), scene(s.groundPlane) {}
};

TransferBaker::TransferBaker(std::span<const uint32_t> indices, std::span<const glm::vec3> albedo,
                             std::span<const float> translucency, const BakeSettings& settings) {
    checkBakeSettings(settings);
    const size_t vertexCount = albedo.size();
    if (translucency.size() != vertexCount) {
        throw Error("transfer bake: " + std::to_string(translucency.size()) + " translucency values for " +
                    std::to_string(vertexCount) + " vertices (one albedo per vertex)");
    }
    if (indices.size() % 3 != 0)
        throw Error("transfer bake: " + std::to_string(indices.size()) + " indices is not a whole number of triangles");
    for (size_t i = 0; i < indices.size(); ++i) {
        if (indices[i] >= vertexCount) {
            throw Error("transfer bake: index " + std::to_string(i) + " is " + std::to_string(indices[i]) +
                        ", but there are " + std::to_string(vertexCount) + " vertices");
        }
    }
    for (size_t v = 0; v < vertexCount; ++v) {
        const glm::vec3& a = albedo[v];
        if (!inUnitRange(a.x) || !inUnitRange(a.y) || !inUnitRange(a.z))
            throw Error("transfer bake: albedo of vertex " + std::to_string(v) + " is outside [0, 1]");
        if (!inUnitRange(translucency[v]))
            throw Error("transfer bake: translucency of vertex " + std::to_string(v) + " is outside [0, 1]");
    }
    state_ = std::make_unique<State>(settings);
    state_->indices.assign(indices.begin(), indices.end());
    state_->albedo.assign(albedo.begin(), albedo.end());
    state_->translucency.assign(translucency.begin(), translucency.end());
}

TransferBaker::~TransferBaker() = default;
TransferBaker::TransferBaker(TransferBaker&&) noexcept = default;
TransferBaker& TransferBaker::operator=(TransferBaker&&) noexcept = default;

uint32_t TransferBaker::vertexCount() const {
    return uint32_t(state_->albedo.size());
}

ClumpTransfer TransferBaker::bake(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals) {
    State& s = *state_;
    const BakeSettings& settings = s.settings;
    const int order = settings.order;
    const size_t n2 = size_t(order * order);
    const Clock::time_point start = Clock::now();
    ClumpTransfer result;

    const detail::FrameGeometry frame = detail::prepareFrame(positions, normals, s.indices, vertexCount());
    Clock::time_point stage = Clock::now();
    if (!s.sceneBuilt) {
        s.scene.setMesh(positions, s.indices);
        s.sceneBuilt = true;
    } else {
        s.scene.updatePositions(positions);
    }
    result.stats.buildSeconds = secondsSince(stage);

    // 2. Ground grid: direct transfer first, it lights the clump's first bounce from below.
    stage = Clock::now();
    std::vector<double> groundDirect;
    detail::HitRecords groundRecords;
    const uint32_t resolution = settings.groundGridResolution;
    if (resolution > 0) {
        detail::castGroundRays(s.scene, frame, settings, groundDirect, groundRecords);
        result.stats.groundRays = uint64_t(resolution) * resolution * settings.groundRaysPerPoint;
    }
    result.stats.groundSeconds = secondsSince(stage);

    // 3. Vertex rays.
    stage = Clock::now();
    std::vector<double> direct;
    detail::HitRecords records;
    detail::castVertexRays(s.scene, frame, settings, direct, records);
    result.stats.vertexRays = uint64_t(vertexCount()) * settings.raysPerVertex;
    result.stats.castSeconds = secondsSince(stage);

    // 4. Interreflection.
    stage = Clock::now();
    const detail::GroundSource ground = detail::makeGroundSource(settings, groundDirect);
    const std::vector<double> total =
        detail::interreflect(records, direct, s.indices, s.albedo, s.translucency, settings, ground);
    result.stats.bounceSeconds = secondsSince(stage);

    result.vertices.order = order;
    result.vertices.vertexCount = vertexCount();
    result.vertices.coefficients = toFloat(total);

    // 5. Ground grid: direct in every channel, plus the clump's light when asked for.
    if (resolution > 0) {
        stage = Clock::now();
        const uint32_t pointCount = resolution * resolution;
        std::vector<double> ground(size_t(pointCount) * kChannelCount * n2);
        std::vector<double> exitance;
        if (settings.groundBounce)
            exitance = detail::vertexExitance(total, s.albedo, order);
        std::vector<double> gathered(kSideCount * kChannelCount * n2);
        for (uint32_t p = 0; p < pointCount; ++p) {
            std::fill(gathered.begin(), gathered.end(), 0.0);
            if (settings.groundBounce)
                detail::gatherPoint(groundRecords, p, s.indices, exitance, nullptr, order, gathered.data());
            for (uint32_t c = 0; c < kChannelCount; ++c) {
                for (size_t i = 0; i < n2; ++i) // ground points receive on their Front (upper) side only
                    ground[(size_t(p) * kChannelCount + c) * n2 + i] = groundDirect[p * n2 + i] + gathered[c * n2 + i];
            }
        }
        result.ground.order = order;
        result.ground.resolution = resolution;
        result.ground.size = settings.groundGridSize;
        result.ground.centre = settings.groundCentre;
        result.ground.coefficients = toFloat(ground);
        result.stats.groundSeconds += secondsSince(stage);
    }
    result.stats.totalSeconds = secondsSince(start);
    return result;
}

ClumpTransfer bakeTransfer(const TransferMesh& mesh, const BakeSettings& settings) {
    if (mesh.positions.size() != mesh.albedo.size()) {
        throw Error("transfer bake: " + std::to_string(mesh.positions.size()) + " positions but " +
                    std::to_string(mesh.albedo.size()) + " albedo values");
    }
    TransferBaker baker(mesh.indices, mesh.albedo, mesh.translucency, settings);
    return baker.bake(mesh.positions, mesh.normals);
}

VertexTransfer unshadowedTransfer(const TransferMesh& mesh, const BakeSettings& settings) {
    checkBakeSettings(settings);
    const size_t vertexCount = mesh.positions.size();
    if (mesh.albedo.size() != vertexCount || mesh.translucency.size() != vertexCount) {
        throw Error("transfer bake: " + std::to_string(vertexCount) + " positions but " +
                    std::to_string(mesh.albedo.size()) + " albedo and " + std::to_string(mesh.translucency.size()) +
                    " translucency values");
    }
    const detail::FrameGeometry frame =
        detail::prepareFrame(mesh.positions, mesh.normals, mesh.indices, uint32_t(vertexCount));
    const int order = settings.order;
    const size_t n2 = size_t(order * order);
    std::vector<double> raw(vertexCount * kSideCount * kChannelCount * n2);
    std::vector<double> lobe(n2);
    for (size_t v = 0; v < vertexCount; ++v) {
        for (uint32_t side = 0; side < kSideCount; ++side) {
            const glm::dvec3 normal = side == 0 ? glm::dvec3(frame.normals[v]) : -glm::dvec3(frame.normals[v]);
            clampedCosineTransfer(order, normal, lobe.data());
            for (uint32_t c = 0; c < kChannelCount; ++c)
                std::copy(lobe.begin(), lobe.end(),
                          raw.begin() + long(((v * kSideCount + side) * kChannelCount + c) * n2));
        }
    }
    std::vector<double> withTranslucency(raw.size());
    detail::applyTranslucency(raw, mesh.translucency, order, withTranslucency);
    VertexTransfer result;
    result.order = order;
    result.vertexCount = uint32_t(vertexCount);
    result.coefficients = toFloat(withTranslucency);
    return result;
}

} // namespace meadow::transfer
