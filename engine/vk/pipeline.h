// Compute and graphics pipelines built from the embedded SPIR-V (vk/shader_registry.h).
// Descriptor set layouts come from reflecting the modules (vk/spirv_reflect.h); resources are
// bound with push descriptors, so there are no descriptor pools or sets to manage.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>
#include <vulkan/vulkan.h>

namespace meadow {

struct Context;
struct Buffer;

struct Pipeline {
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineBindPoint bindPoint = VK_PIPELINE_BIND_POINT_COMPUTE;
    std::vector<VkDescriptorType> bindingTypes; // index = binding; dense from 0
    VkShaderStageFlags stages = 0;
    VkShaderStageFlags pushConstantStages = 0;
    uint32_t pushConstantSize = 0;
    uint32_t localSize[3] = {1, 1, 1};
    std::string name;
};

// `pushConstantSize` must be the size of the shader's push-constant block as its SPIR-V lays it out
// (0 when it declares none); anything else throws, naming both. `localSizeX` > 0 sets the
// workgroup's width through specialization constant 0, for a shader that declares it
// (`layout(local_size_x = DEFAULT, local_size_x_id = 0) in;`); a shader that does not, throws.
// `constants` set specialization constants 1, 2, ... in order, each 32 bits (a bool is 0 or 1); the
// shader keeps its defaults for those not given.
Pipeline createComputePipeline(Context& context, std::string_view shader, uint32_t pushConstantSize = 0,
                               uint32_t localSizeX = 0, std::initializer_list<uint32_t> constants = {});

struct GraphicsPipelineDesc {
    std::string_view vertexShader;
    std::string_view fragmentShader;
    VkFormat colorFormat = VK_FORMAT_UNDEFINED;
    VkFormat depthFormat = VK_FORMAT_UNDEFINED; // UNDEFINED: no depth attachment
    bool depthTest = true;
    bool depthWrite = true;
    VkCompareOp depthCompare = VK_COMPARE_OP_GREATER; // meadow uses reversed Z
    VkCullModeFlags cullMode = VK_CULL_MODE_NONE;
    uint32_t pushConstantSize = 0;
};

Pipeline createGraphicsPipeline(Context& context, const GraphicsPipelineDesc& desc);

// Records the pipeline's push constants (all its block, to the stages that declare it); the bytes
// count in Context::hostBytesWritten.
void pushConstants(Context& context, VkCommandBuffer cmd, const Pipeline& pipeline, const void* data, uint32_t size);
void destroyPipeline(Context& context, Pipeline& pipeline);

// One resource for one binding, in binding order.
struct Binding {
    VkDescriptorBufferInfo buffer{};
    VkDescriptorImageInfo image{};
    VkBufferView texelView = VK_NULL_HANDLE; // a texel buffer's view (createTexelBufferView)
    bool isImage = false;
    Binding(const Buffer& b);
    Binding(VkImageView view, VkImageLayout layout, VkSampler sampler = VK_NULL_HANDLE);
    explicit Binding(VkBufferView view);
};

// Binds the pipeline and pushes its descriptors: `bindings` must list every binding the
// pipeline's shaders declare, in order from 0.
void bindPipeline(Context& context, VkCommandBuffer cmd, const Pipeline& pipeline,
                  std::initializer_list<Binding> bindings);

// Dispatches enough workgroups to cover `x` by `y` items with the pipeline's workgroup size.
void dispatchCovering(VkCommandBuffer cmd, const Pipeline& pipeline, uint32_t x, uint32_t y = 1);

} // namespace meadow
