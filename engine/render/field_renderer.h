// Draws a field of instances the GPU-driven way: per frame the CPU writes one uniform block;
// a compute pass culls the instances into a compacted visible list, one range per mesh, and sets
// each mesh's indirect draw's instanceCount; one multi-draw-indirect call reads them; a compute
// pass tonemaps the result.
//
// Per frame: reset counters (copy from a template) -> cull.comp -> sky, ground, indirect draws ->
// tonemap.comp. GPU timestamps bracket "cull", "draw" and "tonemap".
#pragma once

#include "gpu_types.h"
#include "lod_select.h"
#include "mesh.h"
#include "render/camera.h"
#include "render/render_targets.h"
#include "vk/memory.h"
#include "vk/pipeline.h"

#include <span>
#include <vector>

namespace meadow {

struct GpuTimer;

struct FieldRenderer {
    Pipeline cull;
    Pipeline tonemap;
    Pipeline sky;
    Pipeline ground;
    Pipeline instance;

    Buffer frameUniforms; // host-written each frame: the only per-frame upload
    Buffer instances;
    Buffer vertices;
    Buffer indices;
    Buffer drawCommands;        // one per mesh
    Buffer drawCommandTemplate; // the same with instanceCount 0: copied over them every frame
    Buffer visibleList;
    Buffer stats;
    Buffer statsReadback;

    Image atlas;
    VkSampler sampler = VK_NULL_HANDLE;

    Buffer terrainVertices;
    Buffer terrainIndices;
    Buffer lodState; // per instance: its LOD coordinate, kept from frame to frame (lod_select.h)

    uint32_t instanceCount = 0;
    uint32_t meshCount = 0; // draw buckets: clumps x lodCount, clump-major
    uint32_t lodCount = 1;
    gpu::GpuLodParams lodParams{};
    std::vector<uint32_t> meshTriangles; // per mesh
    uint32_t terrainIndexCount = 0;
    glm::vec4 mirrorNormal{0.0f, 0.0f, 1.0f, 0.0f}; // push constant of the instance pipeline
};

// What the field stands on and how its mirrored instances reflect.
struct FieldScenery {
    Mesh terrain;                        // world space; drawn as is
    glm::vec2 windDirection{1.0f, 0.0f}; // (x, z) the clumps were simulated in
    // Levels of detail: `meshes` hold lodCount meshes per clump (clump-major) and the cull pass
    // picks each instance's with lodSelect; with 1, every instance draws its clump's one mesh.
    uint32_t lodCount = 1;
    gpu::GpuLodParams lod{};
};

struct FieldStats {
    uint32_t visibleInstances = 0;
    uint32_t testedInstances = 0;
    uint64_t trianglesDrawn = 0;          // instances + terrain + sky
    std::vector<uint32_t> visiblePerMesh; // per draw bucket; a crossfading instance counts in two
};

// Every instance's `mesh` names a clump, whose meshes are meshes[mesh * lodCount + lod]; its
// boundingRadius must hold every one of them as it moves.
FieldRenderer createFieldRenderer(Context& context, std::span<const Mesh> meshes,
                                  std::span<const gpu::GpuInstance> instances, const RgbaImage& atlas,
                                  const FieldScenery& scenery);
void destroyFieldRenderer(Context& context, FieldRenderer& renderer);

// Writes the frame's uniform block. Call only when the previous frame's commands completed.
void updateFrameUniforms(FieldRenderer& renderer, const gpu::GpuFrame& frame);

// Records one frame into `targets`. At the end the HDR and LDR images are in GENERAL layout and
// the statistics are on their way to statsReadback. `timer` may be null.
void recordFieldFrame(Context& context, FieldRenderer& renderer, VkCommandBuffer cmd, const RenderTargets& targets,
                      GpuTimer* timer);

// The statistics of the last completed frame.
FieldStats readFieldStats(const FieldRenderer& renderer);

} // namespace meadow
