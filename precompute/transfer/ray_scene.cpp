#include "transfer/ray_scene.h"

#include "core/error.h"

#include <embree3/rtcore.h>
#include <tbb/task_arena.h>

#include <cassert>
#include <cmath>
#include <cstring>
#include <string>

namespace meadow::transfer {

struct RayScene::Embree {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    RTCGeometry geometry = nullptr; // null while the scene holds no triangles
    std::string lastError;          // written by the error callback, during calls on this thread

    ~Embree() {
        if (geometry)
            rtcReleaseGeometry(geometry);
        if (scene)
            rtcReleaseScene(scene);
        if (device)
            rtcReleaseDevice(device);
    }
};

namespace {

const char* errorName(RTCError code) {
    switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_UNKNOWN: return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
    }
    return "unrecognised error";
}

void recordError(void* user, RTCError code, const char* message) {
    auto* embree = static_cast<std::string*>(user);
    *embree = std::string(errorName(code)) + (message ? std::string(": ") + message : std::string());
}

void checkFinite(std::span<const glm::vec3> positions) {
    for (size_t i = 0; i < positions.size(); ++i) {
        const glm::vec3& p = positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw Error("ray scene: position of vertex " + std::to_string(i) + " is not finite");
    }
}

RTCRayHit toEmbree(const Ray& ray, float tFar) {
    RTCRayHit rayHit;
    rayHit.ray.org_x = ray.origin.x;
    rayHit.ray.org_y = ray.origin.y;
    rayHit.ray.org_z = ray.origin.z;
    rayHit.ray.tnear = 0.0f;
    rayHit.ray.dir_x = ray.direction.x;
    rayHit.ray.dir_y = ray.direction.y;
    rayHit.ray.dir_z = ray.direction.z;
    rayHit.ray.time = 0.0f;
    rayHit.ray.tfar = tFar;
    rayHit.ray.mask = 0xffffffffu;
    rayHit.ray.id = 0;
    rayHit.ray.flags = 0;
    rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayHit.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rayHit.hit.u = 0.0f;
    rayHit.hit.v = 0.0f;
    rayHit.hit.Ng_x = rayHit.hit.Ng_y = rayHit.hit.Ng_z = 0.0f;
    return rayHit;
}

} // namespace

RayScene::RayScene(bool groundPlane) : embree_(std::make_unique<Embree>()), groundPlane_(groundPlane) {
    embree_->device = rtcNewDevice(nullptr);
    if (!embree_->device)
        throw Error(std::string("ray scene: cannot create an Embree device: ") + errorName(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(embree_->device, recordError, &embree_->lastError);
    embree_->scene = rtcNewScene(embree_->device);
    // Robust traversal: no ray slips between two triangles through their shared edge, so closed
    // and near-closed shapes (stems, the furnace bowl of the tests) do not leak light.
    rtcSetSceneFlags(embree_->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(embree_->scene, RTC_BUILD_QUALITY_MEDIUM);
    commit("create the scene");
}

RayScene::~RayScene() = default;

void RayScene::commit(const char* what) {
    embree_->lastError.clear();
    // One thread: the BVH, and so the choice between exactly tied hits, is then the same on every
    // machine (see the header).
    tbb::task_arena singleThread(1);
    singleThread.execute([&] { rtcCommitScene(embree_->scene); });
    const RTCError code = rtcGetDeviceError(embree_->device);
    if (code != RTC_ERROR_NONE) {
        throw Error(std::string("ray scene: Embree failed to ") + what + ": " +
                    (embree_->lastError.empty() ? errorName(code) : embree_->lastError));
    }
}

void RayScene::setMesh(std::span<const glm::vec3> positions, std::span<const uint32_t> indices) {
    if (indices.size() % 3 != 0)
        throw Error("ray scene: " + std::to_string(indices.size()) + " indices is not a whole number of triangles");
    if (indices.size() / 3 >= kMaxTriangles)
        throw Error("ray scene: " + std::to_string(indices.size() / 3) + " triangles is too many");
    if (positions.size() >= size_t(kNoHit))
        throw Error("ray scene: " + std::to_string(positions.size()) + " vertices is too many");
    for (size_t i = 0; i < indices.size(); ++i) {
        if (indices[i] >= positions.size()) {
            throw Error("ray scene: index " + std::to_string(i) + " is " + std::to_string(indices[i]) +
                        ", but there are " + std::to_string(positions.size()) + " vertices");
        }
    }
    checkFinite(positions);

    if (embree_->geometry) {
        rtcDetachGeometry(embree_->scene, 0);
        rtcReleaseGeometry(embree_->geometry);
        embree_->geometry = nullptr;
    }
    vertexCount_ = uint32_t(positions.size());
    triangleCount_ = uint32_t(indices.size() / 3);
    if (triangleCount_ > 0) {
        RTCGeometry geometry = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        embree_->geometry = geometry;
        // Embree pads buffers it allocates itself, as its SIMD vertex loads need.
        auto* vertexData = static_cast<float*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), positions.size()));
        auto* indexData = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), triangleCount_));
        if (!vertexData || !indexData)
            throw Error("ray scene: Embree cannot allocate buffers for " + std::to_string(triangleCount_) +
                        " triangles");
        std::memcpy(vertexData, positions.data(), positions.size() * sizeof(glm::vec3));
        std::memcpy(indexData, indices.data(), indices.size() * sizeof(uint32_t));
        rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_MEDIUM);
        rtcCommitGeometry(geometry);
        rtcAttachGeometryByID(embree_->scene, geometry, 0);
    }
    commit("build the scene");
}

void RayScene::updatePositions(std::span<const glm::vec3> positions) {
    if (positions.size() != vertexCount_) {
        throw Error("ray scene: " + std::to_string(positions.size()) + " positions for a mesh of " +
                    std::to_string(vertexCount_) + " vertices");
    }
    checkFinite(positions);
    if (!embree_->geometry)
        return; // ground only: nothing to move
    auto* vertexData = static_cast<float*>(rtcGetGeometryBufferData(embree_->geometry, RTC_BUFFER_TYPE_VERTEX, 0));
    std::memcpy(vertexData, positions.data(), positions.size() * sizeof(glm::vec3));
    rtcUpdateGeometryBuffer(embree_->geometry, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(embree_->geometry);
    commit("rebuild the scene");
}

float RayScene::groundDistance(const Ray& ray) const {
    if (!groundPlane_ || !(ray.direction.y < 0.0f))
        return std::numeric_limits<float>::infinity();
    return std::max(ray.origin.y, 0.0f) / -ray.direction.y;
}

RayHit RayScene::intersect(const Ray& ray) const {
    RayHit hit;
    const float ground = groundDistance(ray);
    const float tFar = std::min(ray.tFar, ground);
    if (tFar > 0.0f && embree_->geometry) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rayHit = toEmbree(ray, tFar);
        rtcIntersect1(embree_->scene, &context, &rayHit);
        if (rayHit.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
            hit.triangle = rayHit.hit.primID;
            hit.u = rayHit.hit.u;
            hit.v = rayHit.hit.v;
            hit.t = rayHit.ray.tfar;
            return hit;
        }
    }
    if (std::isfinite(ground) && ground <= ray.tFar) {
        hit.triangle = kGroundHit;
        hit.t = ground;
        hit.u = ray.origin.x + ground * ray.direction.x;
        hit.v = ray.origin.z + ground * ray.direction.z;
    }
    return hit;
}

bool RayScene::occluded(const Ray& ray) const {
    const float ground = groundDistance(ray);
    if (std::isfinite(ground) && ground <= ray.tFar)
        return true;
    if (!embree_->geometry)
        return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rayHit = toEmbree(ray, ray.tFar);
    rtcOccluded1(embree_->scene, &context, &rayHit.ray);
    // Embree marks an occluded ray by setting tfar to -infinity.
    return rayHit.ray.tfar < 0.0f;
}

void RayScene::intersect(std::span<const Ray> rays, std::span<RayHit> hits) const {
    assert(rays.size() == hits.size());
    for (size_t i = 0; i < rays.size(); ++i)
        hits[i] = intersect(rays[i]);
}

} // namespace meadow::transfer
