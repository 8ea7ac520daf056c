// The embedded shaders reflect to the layouts the host binds; no device needed.
#include "core/error.h"
#include "gpu_types.h"
#include "near_raster.h"
#include "vk/shader_registry.h"
#include "vk/spirv_reflect.h"

#include <gtest/gtest.h>

using namespace meadow;

TEST(SpirvReflect, CullPassLayout) {
    ShaderReflection r = reflectShader(findShader("cull.comp"), "cull.comp");
    EXPECT_EQ(r.stage, VK_SHADER_STAGE_COMPUTE_BIT);
    EXPECT_EQ(r.localSize[0], gpu::kCullGroupSize);
    EXPECT_EQ(r.localSize[1], 1u);
    // Frame; instances, draws, visible list, statistics, LOD state, clumps, motion states, draw records,
    // the far list and the far dispatch, the near list, its dispatch and the near meshes.
    ASSERT_EQ(r.bindings.size(), 14u);
    EXPECT_EQ(r.bindings.at(0), VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
    for (uint32_t b = 1; b <= 13; ++b)
        EXPECT_EQ(r.bindings.at(b), VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) << b;
    EXPECT_EQ(r.pushConstantBytes, 0u);
}

TEST(SpirvReflect, NearRasterPassesLayout) {
    ShaderReflection vertices = reflectShader(findShader("near_vertices.comp"), "near_vertices.comp");
    EXPECT_EQ(vertices.localSize[0], gpu::kNearGroupSize);
    EXPECT_TRUE(vertices.localSizeXSpecialized); // the width is the device's
    // Frame; near list, dispatch, draw records, near meshes; LOD vertices, motion, light as texel
    // buffers; the shaded vertices; the motion's basis rows as a texel buffer; the counters of draws
    // taken. The mirror plane as a push constant.
    ASSERT_EQ(vertices.bindings.size(), 11u);
    EXPECT_EQ(vertices.bindings.at(0), VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
    for (uint32_t b = 1; b <= 4; ++b)
        EXPECT_EQ(vertices.bindings.at(b), VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) << b;
    for (uint32_t b = 5; b <= 7; ++b)
        EXPECT_EQ(vertices.bindings.at(b), VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER) << b;
    EXPECT_EQ(vertices.bindings.at(8), VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    EXPECT_EQ(vertices.bindings.at(9), VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER);
    EXPECT_EQ(vertices.bindings.at(10), VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    EXPECT_EQ(vertices.pushConstantBytes, 16u);
    ShaderReflection raster = reflectShader(findShader("near_raster.comp"), "near_raster.comp");
    EXPECT_EQ(raster.localSize[0], gpu::kNearGroupSize);
    EXPECT_TRUE(raster.localSizeXSpecialized);
    // Frame; near list, dispatch, draw records, clumps, near meshes; indices and shaded vertices as
    // texel buffers; the atlas; the visibility buffer; the counters of draws taken.
    ASSERT_EQ(raster.bindings.size(), 11u);
    EXPECT_EQ(raster.bindings.at(0), VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
    for (uint32_t b = 1; b <= 5; ++b)
        EXPECT_EQ(raster.bindings.at(b), VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) << b;
    for (uint32_t b = 6; b <= 7; ++b)
        EXPECT_EQ(raster.bindings.at(b), VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER) << b;
    EXPECT_EQ(raster.bindings.at(8), VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
    EXPECT_EQ(raster.bindings.at(9), VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    EXPECT_EQ(raster.bindings.at(10), VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    EXPECT_EQ(raster.pushConstantBytes, 0u);
}

TEST(SpirvReflect, FarPassesLayout) {
    ShaderReflection splat = reflectShader(findShader("far_splat.comp"), "far_splat.comp");
    EXPECT_EQ(splat.localSize[0], gpu::kFarGroupSize);
    EXPECT_TRUE(splat.localSizeXSpecialized); // the threads per instance are the device's
    // Frame; far list, dispatch, draw records, clumps; samples, motion coordinates, light as texel
    // buffers (samplerBuffer: a sampled image of Dim Buffer); the visibility buffer; the instances
    // (their bounding spheres bound the coverage coin); the last LOD's vertices' motion as far
    // samples read it (GpuFarMotion: every row the far field plays) as a texel buffer. The mirror
    // plane as a push constant. (The meshes' depth is the resolve's: far_splat.h, farWordShows.)
    ASSERT_EQ(splat.bindings.size(), 11u);
    EXPECT_EQ(splat.bindings.at(0), VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
    for (uint32_t b = 1; b <= 4; ++b)
        EXPECT_EQ(splat.bindings.at(b), VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) << b;
    for (uint32_t b = 5; b <= 7; ++b)
        EXPECT_EQ(splat.bindings.at(b), VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER) << b;
    EXPECT_EQ(splat.bindings.at(8), VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    EXPECT_EQ(splat.bindings.at(9), VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    EXPECT_EQ(splat.bindings.at(10), VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER);
    EXPECT_EQ(splat.pushConstantBytes, 16u);
    ShaderReflection resolve = reflectShader(findShader("far_resolve.comp"), "far_resolve.comp");
    EXPECT_EQ(resolve.localSize[0], gpu::kRowRunWidth); // a run of one row's pixels
    EXPECT_EQ(resolve.localSize[1], 1u);
    EXPECT_FALSE(resolve.localSizeXSpecialized);
    // Frame, visibility buffer (as a texel buffer), HDR image, the meshes' depth, and the LDR image
    // it tone maps into.
    ASSERT_EQ(resolve.bindings.size(), 5u);
    EXPECT_EQ(resolve.bindings.at(1), VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER);
    EXPECT_EQ(resolve.bindings.at(2), VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    EXPECT_EQ(resolve.bindings.at(3), VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
    EXPECT_EQ(resolve.bindings.at(4), VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
}

// The ground light map's pass: a thread per texel, its lists and the vertex light read as texel
// buffers, the map written as a storage image.
TEST(SpirvReflect, GroundMapReadsTexelsAndWritesTheMap) {
    ShaderReflection r = reflectShader(findShader("ground_map.comp"), "ground_map.comp");
    EXPECT_EQ(r.stage, VK_SHADER_STAGE_COMPUTE_BIT);
    EXPECT_EQ(r.localSize[0], gpu::kRowRunWidth); // a run of one row's texels
    EXPECT_EQ(r.localSize[1], 1u);
    ASSERT_EQ(r.bindings.size(), 4u);
    for (uint32_t b = 0; b < 3; ++b)
        EXPECT_EQ(r.bindings.at(b), VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER) << "binding " << b;
    EXPECT_EQ(r.bindings.at(3), VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    EXPECT_EQ(r.pushConstantBytes, 0u);
}

TEST(SpirvReflect, TonemapUsesStorageImages) {
    ShaderReflection r = reflectShader(findShader("tonemap.comp"), "tonemap.comp");
    EXPECT_EQ(r.localSize[0], gpu::kTonemapGroupSize);
    EXPECT_EQ(r.localSize[1], gpu::kTonemapGroupSize);
    EXPECT_EQ(r.bindings.at(1), VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    EXPECT_EQ(r.bindings.at(2), VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
}

TEST(SpirvReflect, GraphicsStagesAndPushConstants) {
    EXPECT_EQ(reflectShader(findShader("instance.vert"), "v").stage, VK_SHADER_STAGE_VERTEX_BIT);
    EXPECT_EQ(reflectShader(findShader("instance.frag"), "f").stage, VK_SHADER_STAGE_FRAGMENT_BIT);
    // The push-constant blocks' sizes as the SPIR-V lays them out: a vec4, a uint, none.
    EXPECT_EQ(reflectShader(findShader("instance.vert"), "v").pushConstantBytes, 16u);
    EXPECT_EQ(reflectShader(findShader("light.comp"), "l").pushConstantBytes, 4u);
    EXPECT_EQ(reflectShader(findShader("ground.vert"), "g").pushConstantBytes, 0u);
    // The sky's vertex shader reads the frame block alone (the sun's cosine, once per vertex).
    const ShaderReflection sky = reflectShader(findShader("sky.vert"), "s");
    ASSERT_EQ(sky.bindings.size(), 1u);
    EXPECT_EQ(sky.bindings.at(0), VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
}

TEST(SpirvReflect, EveryEmbeddedShaderParses) {
    EXPECT_GE(shaderNames().size(), 8u);
    for (std::string_view name : shaderNames())
        EXPECT_NO_THROW(reflectShader(findShader(name), std::string(name))) << name;
    EXPECT_TRUE(findShader("no-such.comp").empty());
}

TEST(SpirvReflect, RejectsGarbage) {
    std::vector<uint32_t> junk = {1, 2, 3, 4, 5, 6};
    EXPECT_THROW(reflectShader(junk, "junk"), Error);
    std::span<const uint32_t> cull = findShader("cull.comp");
    std::vector<uint32_t> truncated(cull.begin(), cull.begin() + 7);
    truncated[5] = (100u << 16) | 17u; // an instruction claiming 100 words
    EXPECT_THROW(reflectShader(truncated, "truncated"), Error);
}
