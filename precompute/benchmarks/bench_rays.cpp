// Embree ray casting of the light-transfer bake (precompute/transfer), on the iris clump at rest
// with the ground plane, at the preset's bake settings (transfer::bakeSettingsForPreset: ci 128,
// full 256 rays per vertex, SH order 3):
//   ray_intersect_batch  RayScene::intersect over a batch: every vertex ray of one frame, built
//                        as castVertexRays builds them (each vertex's rotated spherical Fibonacci
//                        set, leaving rayOffset along the side's normal); one thread, closest hits
//                        only. The bake casts these same rays one by one (RayScene::intersect)
//                        inside castVertexRays; the batch call is that loop.
//   cast_vertex_rays     detail::castVertexRays (bake_detail.h), the bake's ray stage itself: the
//                        same rays on every core (TBB), plus the SH projection of blocked
//                        directions and the hit records the interreflection bounces gather.
//   ray_scene_rebuild    RayScene::updatePositions: the per-frame BVH rebuild of a deforming clump.
#include "fixtures.h"

#include "transfer/bake_detail.h"
#include "transfer/ray_scene.h"
#include "transfer/sphere_sampling.h"
#include "transfer/transfer.h"

#include <map>
#include <memory>
#include <mutex>

namespace meadow::bench {
namespace {

using namespace meadow::transfer;

struct RayCase {
    BakeSettings settings;
    RayScene scene{true};
    detail::FrameGeometry frame;
    std::vector<Ray> rays; // vertex-major, as castVertexRays casts them
    std::vector<RayHit> hits;
};

RayCase& rayCase(const std::string& preset) {
    static std::mutex mutex;
    static std::map<std::string, std::unique_ptr<RayCase>> cases;
    std::lock_guard<std::mutex> lock(mutex);
    std::unique_ptr<RayCase>& slot = cases[preset];
    if (slot)
        return *slot;
    const PlantMesh& mesh = irisClump(preset).mesh;
    auto c = std::make_unique<RayCase>();
    c->settings = bakeSettingsForPreset(preset);
    c->scene.setMesh(mesh.positions, mesh.indices);
    c->frame = detail::prepareFrame(mesh.positions, mesh.normals, mesh.indices, uint32_t(mesh.vertexCount()));
    const std::vector<glm::dvec3> lattice = sphericalFibonacci(c->settings.raysPerVertex);
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        const glm::dvec3 normal(c->frame.normals[v]);
        const glm::vec3 offset = c->frame.normals[v] * c->settings.rayOffset;
        const glm::dmat3 rotation = randomRotation(c->settings.seed, v);
        for (const glm::dvec3& point : lattice) {
            const glm::dvec3 direction = rotation * point;
            const double cosine = glm::dot(normal, direction);
            if (cosine == 0.0)
                continue;
            Ray ray;
            ray.origin = mesh.positions[v] + (cosine < 0.0 ? -offset : offset);
            ray.direction = glm::vec3(direction);
            c->rays.push_back(ray);
        }
    }
    c->hits.resize(c->rays.size());
    slot = std::move(c);
    return *slot;
}

std::string raysLabel(const std::string& preset, const RayCase& c) {
    return describeClump(preset) + ", " + std::to_string(c.settings.raysPerVertex) + " rays per vertex; items = rays";
}

void rayIntersectBatch(benchmark::State& state, const std::string& preset) {
    RayCase* c = setupOrFail(state, [&]() -> RayCase& { return rayCase(preset); });
    if (!c)
        return;
    for (auto _ : state) {
        c->scene.intersect(c->rays, c->hits);
        benchmark::DoNotOptimize(c->hits.data());
        benchmark::ClobberMemory();
    }
    size_t blocked = 0;
    for (const RayHit& hit : c->hits)
        blocked += hit.triangle != kNoHit;
    if (blocked == 0 || blocked == c->hits.size())
        return fail(state, "every ray hit or every ray missed: the scene or the rays are wrong");
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(c->rays.size()));
    state.counters["blocked"] = double(blocked) / double(c->hits.size());
    state.SetLabel(raysLabel(preset, *c) + "; 1 thread");
}

void castVertexRays(benchmark::State& state, const std::string& preset) {
    RayCase* c = setupOrFail(state, [&]() -> RayCase& { return rayCase(preset); });
    if (!c)
        return;
    std::vector<double> direct;
    detail::HitRecords records;
    try {
        for (auto _ : state) {
            detail::castVertexRays(c->scene, c->frame, c->settings, direct, records);
            benchmark::DoNotOptimize(direct.data());
            benchmark::DoNotOptimize(records.hits.data());
            benchmark::ClobberMemory();
        }
    } catch (const std::exception& e) {
        return fail(state, e.what());
    }
    const uint64_t rays = uint64_t(c->frame.positions.size()) * c->settings.raysPerVertex;
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(rays));
    state.SetLabel(raysLabel(preset, *c) + "; all cores");
}

void raySceneRebuild(benchmark::State& state, const std::string& preset) {
    RayCase* c = setupOrFail(state, [&]() -> RayCase& { return rayCase(preset); });
    if (!c)
        return;
    try {
        for (auto _ : state) {
            c->scene.updatePositions(c->frame.positions);
            benchmark::ClobberMemory();
        }
    } catch (const std::exception& e) {
        return fail(state, e.what());
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * c->scene.triangleCount());
    state.SetLabel(describeClump(preset) + "; items = triangles; one-thread BVH build");
}

} // namespace

void registerRayBenchmarks() {
    for (const char* preset : kPresets) {
        const std::string p = preset;
        benchmark::RegisterBenchmark(("ray_intersect_batch/" + p).c_str(),
                                     [p](benchmark::State& s) { rayIntersectBatch(s, p); });
        benchmark::RegisterBenchmark(("cast_vertex_rays/" + p).c_str(), [p](benchmark::State& s) {
            castVertexRays(s, p);
        })->UseRealTime();
        benchmark::RegisterBenchmark(("ray_scene_rebuild/" + p).c_str(), [p](benchmark::State& s) {
            raySceneRebuild(s, p);
        })->UseRealTime();
    }
}

} // namespace meadow::bench
