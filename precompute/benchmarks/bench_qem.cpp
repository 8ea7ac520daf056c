// Quadric simplification (precompute/lod): the attribute-quadric half-edge collapses that make a
// clump's LODs, from the full mesh down to every budget of the scene (LodParams: 1, 1/3, 1/10,
// 1/20, 1/30 of the triangles) in one MeshSimplifier, as buildLods runs it.
//   qem_simplify  MeshSimplifier construction (quadrics of every face and attribute) and the
//                 collapses to the five budgets; items = collapses (vertices merged away).
//   qem_quadrics  the construction alone (items = input triangles), to split the two.
//   lod_chain     buildLods: the same plus meshoptimizer's vertex cache and fetch orders.
// The input is what buildClumpLods (clump_lod.cpp) gives the simplifier: the clump's mean pose as
// drawn (clumpRenderMesh), rod collapse groups, motion rows of LOD 0 weighted 1 and the mean light
// transfer weighted 0.01. To keep the setup to seconds its data comes from shorter real runs than
// a library's: the motion from buildClumpMotion with two wind levels (2 and 7 m/s) of 2 s each,
// the transfer from one bake of the mean pose (ci bake settings, no ground grid) as the mean. The
// attribute widths (what the quadrics cost) are printed in the label.
#include "fixtures.h"

#include "light/vertex_appearance.h"
#include "lod/lod.h"
#include "pipeline/clump_lod.h"
#include "pipeline/clump_motion.h"
#include "scene/scene.h"
#include "transfer/transfer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#ifndef MEADOW_SOURCE_DIR
#error "MEADOW_SOURCE_DIR must name the repository root (precompute/benchmarks/CMakeLists.txt)"
#endif

namespace meadow::bench {
namespace {

struct QemCase {
    Scene scene;
    ClumpMotion motion;
    Mesh meanPose;
    ClumpSimplifyData data; // as buildClumpLods gives the simplifier
    std::array<uint32_t, kLodCount> targets{};
};

QemCase& qemCase(const std::string& preset) {
    static std::mutex mutex;
    static std::map<std::string, std::unique_ptr<QemCase>> cases;
    std::lock_guard<std::mutex> lock(mutex);
    std::unique_ptr<QemCase>& slot = cases[preset];
    if (slot)
        return *slot;
    auto c = std::make_unique<QemCase>();
    c->scene = loadScene(MEADOW_SOURCE_DIR "/data/scenes/irises.json", preset, std::nullopt);
    c->scene.wind.levelSpeeds = {2.0f, 7.0f};
    c->scene.motion.settleSeconds = 0.5f;
    c->scene.motion.recordSeconds = 2.0f;
    c->motion = buildClumpMotion(irisClump(preset), c->scene, c->scene.seed * 1000003ull);
    c->meanPose = clumpRenderMesh(c->motion);

    c->data = clumpSimplifyData(c->motion, c->meanPose);
    const uint32_t vertexCount = uint32_t(c->data.positions.size());

    // One bake of the mean pose stands for the mean transfer T̄ (gradients zero: only T̄ is read).
    transfer::BakeSettings bake = transfer::bakeSettingsForPreset("ci");
    bake.groundGridResolution = 0;
    const std::vector<glm::vec3> albedo(vertexCount, glm::vec3(0.4f, 0.5f, 0.3f));
    const std::vector<float> translucency = transfer::translucencyForParts(c->motion.clump.mesh.parts, bake);
    const transfer::ClumpTransfer baked =
        transfer::bakeTransfer({c->data.positions, c->data.normals, c->meanPose.indices, albedo, translucency}, bake);
    VertexAppearance appearance;
    appearance.vertexCount = vertexCount;
    appearance.valuesPerVertex = uint32_t(baked.vertices.coefficients.size() / vertexCount);
    appearance.coefficients.assign(baked.vertices.coefficients.size() * 4, 0.0f);
    for (size_t i = 0; i < baked.vertices.coefficients.size(); ++i)
        appearance.coefficients[4 * i] = baked.vertices.coefficients[i];
    c->data.transfer = meanTransferAttributes(appearance);

    const double fullTriangles = double(c->meanPose.indices.size() / 3);
    for (uint32_t l = 0; l < kLodCount; ++l) // lod_chain.cpp's budgets
        c->targets[l] = uint32_t(std::max(1.0, std::round(double(c->scene.lod.triangleFractions[l]) * fullTriangles)));
    slot = std::move(c);
    return *slot;
}

std::string qemLabel(const std::string& preset, const QemCase& c, const char* items) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "%s clump: %zu vertices, %zu triangles -> %u; attributes 6 + %u motion + %u light; "
                  "items = %s",
                  preset.c_str(), c.data.positions.size(), c.meanPose.indices.size() / 3, c.targets[kLodCount - 1],
                  c.data.motionRows.width, c.data.transfer.width, items);
    return text;
}

void qemSimplify(benchmark::State& state, const std::string& preset) {
    QemCase* c = setupOrFail(state, [&]() -> QemCase& { return qemCase(preset); });
    if (!c)
        return;
    const SimplifyInput input = c->data.input();
    SimplifiedMesh last;
    try {
        for (auto _ : state) {
            MeshSimplifier simplifier(input);
            for (uint32_t target : c->targets) {
                last = simplifier.simplifyTo(target);
                benchmark::DoNotOptimize(last.indices.data());
            }
            benchmark::ClobberMemory();
        }
    } catch (const std::exception& e) {
        return fail(state, e.what());
    }
    uint32_t collapses = 0;
    for (uint32_t v = 0; v < last.representative.size(); ++v)
        collapses += last.representative[v] != v && last.representative[v] != kRemovedVertex;
    if (collapses == 0 || last.triangleCount() > c->targets[kLodCount - 1])
        return fail(state, "the simplifier did not reach the last budget");
    const uint32_t removed = uint32_t(c->meanPose.indices.size() / 3) - last.triangleCount();
    state.SetItemsProcessed(int64_t(state.iterations()) * collapses);
    state.counters["triangles_removed/s"] =
        benchmark::Counter(double(state.iterations()) * removed, benchmark::Counter::kIsRate);
    state.SetLabel(qemLabel(preset, *c, "collapses"));
}

void qemQuadrics(benchmark::State& state, const std::string& preset) {
    QemCase* c = setupOrFail(state, [&]() -> QemCase& { return qemCase(preset); });
    if (!c)
        return;
    const SimplifyInput input = c->data.input();
    try {
        for (auto _ : state) {
            MeshSimplifier simplifier(input);
            benchmark::DoNotOptimize(&simplifier);
            benchmark::ClobberMemory();
        }
    } catch (const std::exception& e) {
        return fail(state, e.what());
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(c->meanPose.indices.size() / 3));
    state.SetLabel(qemLabel(preset, *c, "input triangles"));
}

void lodChain(benchmark::State& state, const std::string& preset) {
    QemCase* c = setupOrFail(state, [&]() -> QemCase& { return qemCase(preset); });
    if (!c)
        return;
    const SimplifyInput input = c->data.input();
    LodOptions options;
    options.triangleFractions = c->scene.lod.triangleFractions;
    try {
        for (auto _ : state) {
            const std::array<MeshLod, kLodCount> lods = buildLods(input, options);
            benchmark::DoNotOptimize(lods.back().indices.data());
            benchmark::ClobberMemory();
        }
    } catch (const std::exception& e) {
        return fail(state, e.what());
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(c->meanPose.indices.size() / 3));
    state.SetLabel(qemLabel(preset, *c, "input triangles"));
}

} // namespace

void registerQemBenchmarks() {
    for (const char* preset : kPresets) {
        const std::string p = preset;
        benchmark::RegisterBenchmark(("qem_simplify/" + p).c_str(), [p](benchmark::State& s) { qemSimplify(s, p); });
        benchmark::RegisterBenchmark(("qem_quadrics/" + p).c_str(), [p](benchmark::State& s) { qemQuadrics(s, p); });
        benchmark::RegisterBenchmark(("lod_chain/" + p).c_str(), [p](benchmark::State& s) { lodChain(s, p); });
    }
}

} // namespace meadow::bench
