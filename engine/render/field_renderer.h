// Draws a field of instances the GPU-driven way (docs/ARCHITECTURE.md, The run time). Per frame the
// CPU writes one uniform block (camera, wind, sky frames); everything per instance happens in
// compute passes:
//
//   reset counters -> animate.comp (motion-graph steps at the wind level of each instance)
//   -> cull.comp (frustum, LOD, compaction into per-(clump, LOD) draws)
//   -> light.comp (only when the sky changed: every clump vertex's transfer onto the sky's SH)
//   -> sky_blend.comp (this frame's sky backdrop: the two sky frames around the hour blended)
//   -> one multi-draw-indirect of the clumps, the terrain, the sky backdrop
//   -> far_splat.comp (with a far field: far instances as surface samples)
//   -> tonemap.comp, or with a far field far_resolve.comp (the splats' winners resolved against the
//      meshes' depth, then the tone map, in one pass).
//
// GPU timestamps bracket "animate", "cull", "light", "groundMap" (the ground light map's gather),
// "sky", "draw", "farSplat" (with a far field: the visibility buffer's fill and the splat pass) and
// "tonemap" (with a far field, the resolve pass).
#pragma once

#include <array>

#include "draw_instance.h"
#include "gpu_types.h"
#include "library/far_samples.h"
#include "library/mesh.h"
#include "library/motion_basis.h"
#include "library/motion_graph.h"
#include "library/sky_day.h"
#include "lod_select.h"
#include "render/camera.h"
#include "render/render_targets.h"
#include "vk/memory.h"
#include "vk/pipeline.h"

#include <memory>
#include <span>
#include <vector>

namespace meadow {

struct GpuTimer;
struct CpuDriver;

// One level of detail of a clump: a subset of its vertices and triangles over them.
struct FieldLod {
    std::vector<uint32_t> vertices; // indices into FieldClump::mesh.vertices, in fetch order
    std::vector<uint32_t> indices;  // triangles into `vertices`
};

// One clump (or rock) as the renderer draws it, in its own (clump) space.
struct FieldClump {
    Mesh mesh;                  // every vertex at the mean pose: positions, normals, atlas UVs
    std::vector<FieldLod> lods; // FieldScenery::lodCount of them, LOD 0 first
    MotionBasis motion;         // x̄ + U q per rod block; frames == 0: static
    MotionGraph graph;          // the wind-indexed walk over motion.frames; nodeCount == 0: static
    // Light transfer, SH order 3: per vertex 54 values (2 sides x RGB x 9) each with its gradient
    // in the vertex's displacement, [vertex][value][4] (light/vertex_appearance.h). Empty: the
    // unshadowed transfer of each side's normal (a plain diffuse surface).
    std::vector<float> transfer;
    // The instances' yaws fall in [yawLow, yawHigh]: light is projected for yawBins yaws in it,
    // mirrored and not (2 yawBins variants per vertex), and each instance uses its bin's.
    float yawLow = 0.0f, yawHigh = 0.0f;
    uint32_t yawBins = 1;
    glm::vec4 albedo{0.0f}; // w 1: this rgb instead of the atlas (rocks)
    // The ground around the clump (transfer.h GroundTransfer): groundResolution^2 points over a
    // square of groundSize metres centred on the clump's base, row-major with rows along z, each
    // 3 channels x 9 SH coefficients. Empty (resolution 0): the clump casts no ground shadow.
    std::vector<float> groundTransfer;
    uint32_t groundResolution = 0;
    float groundSize = 0.0f;
    // The far field (far_splat.h): surface samples, shuffled so any run is an unbiased subset,
    // each following a vertex of the last LOD; `farArea` the surface they cover (m^2). Empty: the
    // clump stays a LOD 4 mesh however small it gets.
    std::vector<FarSample> far;
    float farArea = 0.0f;
    bool farClosed = false; // a closed surface (rocks): samples facing away from the camera are hidden
    // The coverage gains on the samples' footprints (FarSamples::gain, far_splat.h); 1 where unmeasured.
    std::array<float, gpu::kFarGainSizes* gpu::kFarGainElevations> farGain = FarSamples{}.gain;
};

// A static clump of one mesh: every LOD the whole mesh, no motion, unshadowed light.
FieldClump staticFieldClump(const Mesh& mesh, uint32_t lodCount);

// What the field stands on, how its mirrored instances reflect, and its sky.
struct FieldScenery {
    Mesh terrain;                        // world space; drawn as is
    glm::vec2 windDirection{1.0f, 0.0f}; // (x, z) the clumps were simulated in
    // Levels of detail: every clump has lodCount; the cull pass picks each instance's with
    // lodSelect; with 1, every instance draws its clump's one mesh.
    uint32_t lodCount = 1;
    gpu::GpuLodParams lod{}; // lod.farRadius > 0: the far field takes over below it (every clump needs samples)
    float farDensity = gpu::kFarDefaultDensity; // far-field samples per pixel of projected surface (far_splat.h)
    // The far field's clumps drawn as LOD 0 meshes instead of splats (its reference: --far-lod0).
    bool farAsLod0 = false;
    // Threads per far instance in the splat pass (gpu_types.h): a power of two up to
    // gpu::kFarMaxLanes; 0: the device's (farSplatLanesFor). The picture is the same with any.
    uint32_t farLanes = 0;
    // The mesh LODs (0 up to the last) of instances below gpu::kNearMaxRadius px drawn by the near
    // raster (near_raster.h) instead of the mesh pass (--near-raster); the CPU-driven path uploads
    // the same list (cpu_driver.h).
    bool nearRaster = false;
    // The near raster's workgroup width (near_raster.h): 1 to 1024; 0: the device's (nearWidthFor).
    // The picture is the same with any.
    uint32_t nearWidth = 0;
    // How the near raster's workgroups share its draws out (near_raster.h): -1 the device's way
    // (nearTakesDraws), 0 dealt in turn, 1 taken by each SIMD row from a counter. The picture is
    // the same either way.
    int nearTakeDraws = -1;
    sky::SkyDay sky; // SH order 3; at least one frame
};

// The wind at run time, in wind levels of the motion graph (0 calm .. levels - 1): waves that
// travel downwind across the field and gusts (shaders/shared/wind_field.h).
struct WindState {
    float baseLevel = 1.2f;
    float waveAmplitude = 0.8f; // levels
    float wavelength = 30.0f;   // m
    float waveSpeed = 6.0f;     // m/s
    float gustAmplitude = 0.9f; // levels, added on top (value noise in [0, 1])
    float gustSize = 8.0f;      // m between gust cells
    float gustSpeed = 4.0f;     // m/s the gusts drift downwind
};

// What the CPU decides each frame.
struct FrameState {
    Camera camera;
    uint32_t width = 0, height = 0;
    double seconds = 0.0; // scene time; motion steps at 30 Hz of it
    double hours = 12.0;  // local solar time: the sky
    WindState wind;
    uint32_t debugView = gpu::kDebugViewNone;
    // Keep the last culled frame's visible lists and LODs (to look at what culling chose from
    // elsewhere; the clumps hold still meanwhile); ignored until one frame has been culled.
    bool freezeCulling = false;
};

struct FieldRenderer {
    Pipeline animate;
    Pipeline cull;
    Pipeline light;
    Pipeline lightGround; // light.comp for the clumps' ground grids (kGroundPoints)
    Pipeline tonemap;
    Pipeline sky;
    Pipeline skyBlend;
    Pipeline ground;
    Pipeline instance;
    Pipeline groundMap;
    Pipeline farSplat;
    Pipeline farSplatLodView;   // the LOD view painted (kLodView): the frames that show it
    Pipeline farResolve;        // the HDR image left holding the frame (HdrContents::Frame)
    Pipeline farResolveLdrOnly; // the far field and the near raster into the LDR image alone (MeshPass)
    Pipeline nearVertices;
    Pipeline nearRaster;
    Pipeline nearRasterLodView; // as farSplatLodView

    Buffer frameUniforms; // host-written each frame: the only per-frame upload
    Buffer instances;
    Buffer motionStates;  // per instance gpu::GpuMotionState
    Buffer lodState;      // per instance: its LOD coordinate, kept from frame to frame (lod_select.h)
    Buffer drawInstances; // per instance, written while visible: what its vertices need (draw_instance.h)
    Buffer clumps;        // gpu::GpuClump
    Buffer lodVertices;
    Buffer indices;
    Buffer motionData;          // floats: per clump its basis rows, then its coordinates frame by frame
    Buffer motionGraph;         // uints: per clump edgeStart, edgeTarget, edgeWeight, naturalNext
    Buffer transfer;            // vec4: per clump vertex 54 x (T, dT/dx, dT/dy, dT/dz)
    Buffer vertexLight;         // vec4: per clump vertex and light variant, kLightVec4sPerVertex
    Buffer skyData;             // floats: per sky frame SH, sun and backdrop (field_renderer.cpp)
    Buffer drawCommands;        // one per (clump, LOD)
    Buffer drawCommandTemplate; // the same with instanceCount 0: copied over them every frame
    Buffer visibleList;
    Buffer farSamples; // gpu::GpuFarSample, per clump its shuffled samples
    Buffer farMotion;  // gpu::GpuFarMotion, per GpuLodVertex (set for the last LODs' vertices)
    // Buffers seen as texel buffers, as the shaders read them: transfer and vertexLight (the light
    // pass, light.comp, and the ground light map, ground_map.comp); visibleList, drawInstances,
    // clumps, lodVertices, motionData and vertexLight (the mesh pass's vertex shader, instance.vert;
    // the near raster's vertex pass and the splat pass read the last four so too); with the far field
    // farSamples and farMotion (far_splat.comp).
    VkBufferView transferTexels = VK_NULL_HANDLE;
    VkBufferView farSampleTexels = VK_NULL_HANDLE;
    VkBufferView farMotionTexels = VK_NULL_HANDLE;
    VkBufferView visibleTexels = VK_NULL_HANDLE;
    VkBufferView drawInstanceTexels = VK_NULL_HANDLE;
    VkBufferView clumpTexels = VK_NULL_HANDLE;
    VkBufferView lodVertexTexels = VK_NULL_HANDLE;
    VkBufferView motionTexels = VK_NULL_HANDLE;
    VkBufferView motionRowTexels = VK_NULL_HANDLE; // the same buffer's basis rows, RGBA32F
    VkBufferView vertexLightTexels = VK_NULL_HANDLE;
    Buffer farList;     // per far instance this frame: (visible-list entry, samples to draw)
    Buffer farDispatch; // gpu::GpuFarDispatch: the splat pass's indirect dispatch, written by cull
    // The near raster (near_raster.h): the LOD draws it takes this frame, its dispatch (both written
    // by cull), where each bucket's mesh lies, and its shaded vertices.
    Buffer nearList;
    Buffer nearDispatch; // gpu::GpuNearDispatch
    Buffer nearMeshes;
    Buffer nearShaded;
    Buffer nearTaken; // the two passes' counters of draws taken (near_raster.h), zeroed each frame
    VkBufferView indexTexels = VK_NULL_HANDLE; // the LOD meshes' indices, as the near raster reads them
    VkBufferView nearShadedTexels = VK_NULL_HANDLE;
    Buffer stats;
    Buffer statsReadback;

    Image atlas;
    VkSampler sampler = VK_NULL_HANDLE;
    VkSampler atlasSampler = VK_NULL_HANDLE; // trilinear, stopping at the mip level whose parts stay apart
    VkSampler pointSampler = VK_NULL_HANDLE; // the depth, read by the splat pass
    // This frame's sky backdrop (sky_blend.comp): the two sky frames around the hour blended, half
    // floats, the sky's lat-long size; sky.frag reads it bilinear, wrapping around in azimuth.
    Image skyImage;
    VkSampler skySampler = VK_NULL_HANDLE;

    // The field's ground light map (render/ground_light_map.h): the share of open-ground light
    // reaching each point of the ground, multiplied over every instance's grid; made again by
    // ground_map.comp with the light pass, from static per-texel lists of grid cells.
    Image groundLight;
    Buffer groundTexelStart; // uint per texel of the map, then the end: its range of groundEntries
    Buffer groundEntries;    // uvec2 per listed grid cell, texel by texel (gpu_types.h)
    VkBufferView groundTexelStartTexels = VK_NULL_HANDLE;
    VkBufferView groundEntryTexels = VK_NULL_HANDLE;
    glm::vec4 groundRect{0.0f, 0.0f, 1.0f, 1.0f}; // GpuFrame::groundMap

    Buffer terrainVertices;
    Buffer terrainIndices;

    uint32_t instanceCount = 0;
    uint32_t clumpCount = 0;
    uint32_t meshCount = 0; // draw buckets: clumps x lodCount, clump-major
    uint32_t lodCount = 1;
    gpu::GpuLodParams lodParams{};
    float farDensity = gpu::kFarDefaultDensity;
    bool farAsLod0 = false;
    bool farField = false;               // lodParams.farRadius > 0: the splat and resolve passes run
    bool nearRasterOn = false;           // FieldScenery::nearRaster (the resolve pass runs with it too)
    std::vector<uint32_t> meshTriangles; // per draw bucket
    std::vector<uint32_t> drawCapacity;  // per draw bucket: the instances its visible range holds
    uint64_t lodVertexCount = 0;
    uint64_t visibleCount = 0;
    std::vector<uint32_t> lightVertices;     // per clump: vertices (light.comp's threads)
    std::vector<uint32_t> lightGroundPoints; // per clump: ground grid points (lightGround's threads)
    uint32_t terrainIndexCount = 0;
    glm::vec4 mirrorNormal{0.0f, 0.0f, 1.0f, 0.0f}; // push constant of the instance pipeline
    float windAzimuth = 0.0f;

    // Host state carried from frame to frame.
    sky::SkyDay skyDay; // CPU copy for the blend, exposure and horizon colour
    float brightestIrradiance = 1.0f;
    int64_t lastTick = -1;       // the motion tick the states show
    bool lightValid = false;     // vertexLight holds the current sky
    gpu::uvec4 litSky{0u};       // the sky frames it was projected for
    float litWeight = -1.0f;     // and their weight
    bool lightThisFrame = false; // the sky moved by 1/32 of a sky frame since the last light pass
    // The sky image (sky_blend.comp) holds the blend of these frames at this weight (-1 before the
    // first blend: no frame's weight); blended again only when the frame asks for another.
    gpu::uvec4 blendedSky{0u};
    float blendedWeight = -1.0f;
    bool skyBlendThisFrame = false;
    bool cullThisFrame = true;
    bool culledOnce = false;
    gpu::GpuFrame lastFrame{}; // the uniforms updateFrame wrote last: the frame being recorded
    // Set by enableCpuDriver (render/cpu_driver.h): the CPU steps, culls and uploads instead.
    std::shared_ptr<CpuDriver> cpuDriver;
};

struct FieldStats {
    uint32_t visibleInstances = 0;
    uint32_t testedInstances = 0;
    uint32_t farInstances = 0;            // drawn as the far field (a crossfading one counts here and in a LOD)
    uint32_t farSamples = 0;              // splats they drew
    uint32_t nearInstances = 0;           // LOD draws the near raster took (a crossfading instance may have two)
    uint64_t nearTriangles = 0;           // their triangles (not in trianglesDrawn)
    uint64_t trianglesDrawn = 0;          // instances + terrain + sky
    std::vector<uint32_t> visiblePerMesh; // the draw pass's, per draw bucket; a crossfading instance counts in two
    std::vector<uint32_t> nearPerLod;     // the near raster's per LOD (lodCount of them), one per draw
    // Draws per LOD (lodCount of them), the draw pass's and the near raster's together: a crossfading
    // instance counts in both of its LODs.
    std::vector<uint32_t> drawsPerLod() const;
};

// The near raster's workgroup width on a device (FieldScenery::nearWidth = 0): gpu::kNearGroupSize
// on a GPU, two SIMD rows (twice the subgroup size) on a CPU.
uint32_t nearWidthFor(const Context& context);
// The entries the near list holds for a field of `instances` (near_raster.h: two draws an instance,
// and the parts of up to gpu::kNearMaxSplitDraws draws listed in parts).
size_t nearListCapacity(size_t instances);
// Whether the near raster's SIMD rows take their draws from a counter on a device
// (FieldScenery::nearTakeDraws = -1): on a CPU (near_raster.h).
bool nearTakesDraws(const Context& context);

// The splat pass's threads per far instance on a device (FieldScenery::farLanes = 0): 2 on a CPU
// (lavapipe's SIMD halves), gpu::kFarMaxLanes on a GPU (measured in docs/BENCHMARKS.md).
uint32_t farSplatLanesFor(const VkPhysicalDeviceProperties& device);

// Every instance's `mesh` names a clump; its boundingRadius must hold every LOD of it as it moves.
// Throws meadow::Error on inconsistent content (naming what).
FieldRenderer createFieldRenderer(Context& context, std::span<const FieldClump> clumps,
                                  std::span<const gpu::GpuInstance> instances, const RgbaImage& atlas,
                                  const FieldScenery& scenery);
void destroyFieldRenderer(Context& context, FieldRenderer& renderer);

// Writes the frame's uniform block from the camera, time, wind and sky (and the renderer's own
// counts and LOD parameters), and decides whether the light pass runs. Call only when the
// previous frame's commands completed.
void updateFrame(Context& context, FieldRenderer& renderer, const FrameState& state);

// Plays the motion forward to state.seconds without drawing (animate passes only, waiting for
// each): a first frame then shows the clumps already moving in the wind of `state`.
void advanceMotion(Context& context, FieldRenderer& renderer, const FrameState& state);

// The uniform block updateFrame would write (no side effects): for CPU references.
gpu::GpuFrame frameUniforms(const FieldRenderer& renderer, const FrameState& state);

// Records one frame into `targets`. At the end the HDR and LDR images are in GENERAL layout and
// the statistics are on their way to statsReadback. `timer` may be null.
void recordFieldFrame(Context& context, FieldRenderer& renderer, VkCommandBuffer cmd, const RenderTargets& targets,
                      GpuTimer* timer);

// The statistics of the last completed frame.
FieldStats readFieldStats(const FieldRenderer& renderer);

// The ground light map as the last light pass left it: RGB per texel, row by row (for tests and
// tools; waits for the device).
std::vector<glm::vec3> readGroundLightMap(Context& context, const FieldRenderer& renderer);

// The sky backdrop the last frame drew (sky_blend.comp): RGB per texel of the sky's lat-long
// image, row by row (for tests; waits for the device).
std::vector<glm::vec3> readSkyImage(Context& context, const FieldRenderer& renderer);

} // namespace meadow
