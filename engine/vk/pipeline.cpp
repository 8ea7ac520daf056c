#include "vk/pipeline.h"

#include "vk/context.h"
#include "vk/memory.h"
#include "vk/shader_registry.h"
#include "vk/spirv_reflect.h"
#include "vk/vk_check.h"

#include <algorithm>
#include <map>

namespace meadow {
namespace {

// A shader module for the time a pipeline is being made; destroyed when it goes out of scope, so
// that a pipeline refused for a mismatch leaves nothing behind on the device.
struct LoadedShader {
    VkDevice device = VK_NULL_HANDLE;
    VkShaderModule module = VK_NULL_HANDLE;
    ShaderReflection reflection;
    explicit LoadedShader(VkDevice d) : device(d) {}
    LoadedShader(LoadedShader&& o) noexcept : device(o.device), module(o.module), reflection(std::move(o.reflection)) {
        o.module = VK_NULL_HANDLE;
    }
    LoadedShader(const LoadedShader&) = delete;
    LoadedShader& operator=(const LoadedShader&) = delete;
    LoadedShader& operator=(LoadedShader&&) = delete;
    ~LoadedShader() {
        if (module != VK_NULL_HANDLE)
            vkDestroyShaderModule(device, module, nullptr);
    }
};

LoadedShader loadShader(Context& ctx, std::string_view name) {
    std::span<const uint32_t> code = findShader(name);
    if (code.empty())
        throw Error("shader " + std::string(name) + " is not built into this meadow executable");
    LoadedShader shader(ctx.device);
    shader.reflection = reflectShader(code, std::string(name));
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = code.size_bytes();
    info.pCode = code.data();
    VK_CHECK(vkCreateShaderModule(ctx.device, &info, nullptr, &shader.module));
    return shader;
}

// Merges the shaders' bindings into one push-descriptor set layout and a pipeline layout.
void createLayouts(Context& ctx, Pipeline& p, const std::vector<const LoadedShader*>& shaders, uint32_t pushSize) {
    std::map<uint32_t, std::pair<VkDescriptorType, VkShaderStageFlags>> merged;
    uint32_t declared = 0; // the largest push-constant block of the stages
    for (const LoadedShader* s : shaders) {
        p.stages |= s->reflection.stage;
        declared = std::max(declared, s->reflection.pushConstantBytes);
        if (s->reflection.pushConstantBytes > 0)
            p.pushConstantStages |= s->reflection.stage;
        for (auto [binding, type] : s->reflection.bindings) {
            auto it = merged.find(binding);
            if (it != merged.end() && it->second.first != type)
                throw Error("pipeline " + p.name + ": binding " + std::to_string(binding) +
                            " has different types in different stages");
            merged[binding].first = type;
            merged[binding].second |= s->reflection.stage;
        }
    }
    if (pushSize != declared)
        throw Error("pipeline " + p.name + ": push constant size " + std::to_string(pushSize) +
                    (declared ? " but the shaders' block is " + std::to_string(declared) + " bytes"
                              : " but the shaders declare none"));

    std::vector<VkDescriptorSetLayoutBinding> bindings;
    uint32_t expected = 0;
    for (auto& [binding, typeStages] : merged) {
        if (binding != expected)
            throw Error("pipeline " + p.name + ": bindings must be dense from 0; binding " + std::to_string(expected) +
                        " is missing");
        ++expected;
        bindings.push_back({binding, typeStages.first, 1, typeStages.second, nullptr});
        p.bindingTypes.push_back(typeStages.first);
    }
    VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
    setInfo.bindingCount = static_cast<uint32_t>(bindings.size());
    setInfo.pBindings = bindings.data();
    VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &setInfo, nullptr, &p.setLayout));

    p.pushConstantSize = pushSize;
    VkPushConstantRange range{p.pushConstantStages, 0, pushSize};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &p.setLayout;
    layoutInfo.pushConstantRangeCount = pushSize > 0 ? 1 : 0;
    layoutInfo.pPushConstantRanges = &range;
    VK_CHECK(vkCreatePipelineLayout(ctx.device, &layoutInfo, nullptr, &p.layout));
}

} // namespace

Pipeline createComputePipeline(Context& ctx, std::string_view shaderName, uint32_t pushConstantSize,
                               uint32_t localSizeX, std::initializer_list<uint32_t> constants) {
    Pipeline p;
    p.name = std::string(shaderName);
    p.bindPoint = VK_PIPELINE_BIND_POINT_COMPUTE;
    LoadedShader shader = loadShader(ctx, shaderName);
    if (shader.reflection.stage != VK_SHADER_STAGE_COMPUTE_BIT)
        throw Error("shader " + p.name + " is not a compute shader");
    for (int i = 0; i < 3; ++i)
        p.localSize[i] = shader.reflection.localSize[i];
    if (localSizeX > 0) {
        if (!shader.reflection.localSizeXSpecialized)
            throw Error("shader " + p.name + " does not take its workgroup width from specialization constant 0");
        if (localSizeX > ctx.properties.limits.maxComputeWorkGroupSize[0] ||
            localSizeX * p.localSize[1] * p.localSize[2] > ctx.properties.limits.maxComputeWorkGroupInvocations)
            throw Error("shader " + p.name + ": a workgroup " + std::to_string(localSizeX) +
                        " wide is beyond the device's limits");
        p.localSize[0] = localSizeX;
    }
    createLayouts(ctx, p, {&shader}, pushConstantSize);

    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = shader.module;
    info.stage.pName = "main";
    info.layout = p.layout;
    // Constant 0 is the width (when given), then constants 1, 2, ...: one 32-bit value each.
    std::vector<uint32_t> values;
    std::vector<VkSpecializationMapEntry> entries;
    auto add = [&](uint32_t id, uint32_t value) {
        entries.push_back({id, uint32_t(values.size() * sizeof(uint32_t)), sizeof(uint32_t)});
        values.push_back(value);
    };
    if (localSizeX > 0)
        add(0, localSizeX);
    uint32_t id = 1;
    for (uint32_t value : constants)
        add(id++, value);
    const VkSpecializationInfo specialization{uint32_t(entries.size()), entries.data(),
                                              values.size() * sizeof(uint32_t), values.data()};
    if (!entries.empty())
        info.stage.pSpecializationInfo = &specialization;
    VK_CHECK(vkCreateComputePipelines(ctx.device, VK_NULL_HANDLE, 1, &info, nullptr, &p.pipeline));
    return p;
}

Pipeline createGraphicsPipeline(Context& ctx, const GraphicsPipelineDesc& desc) {
    Pipeline p;
    p.name = std::string(desc.vertexShader) + "+" + std::string(desc.fragmentShader);
    p.bindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    LoadedShader vs = loadShader(ctx, desc.vertexShader);
    LoadedShader fs = loadShader(ctx, desc.fragmentShader);
    if (vs.reflection.stage != VK_SHADER_STAGE_VERTEX_BIT || fs.reflection.stage != VK_SHADER_STAGE_FRAGMENT_BIT)
        throw Error("pipeline " + p.name + ": expected a vertex and a fragment shader");
    createLayouts(ctx, p, {&vs, &fs}, desc.pushConstantSize);

    VkPipelineShaderStageCreateInfo stages[2] = {};
    stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                 nullptr,
                 0,
                 VK_SHADER_STAGE_VERTEX_BIT,
                 vs.module,
                 "main",
                 nullptr};
    stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                 nullptr,
                 0,
                 VK_SHADER_STAGE_FRAGMENT_BIT,
                 fs.module,
                 "main",
                 nullptr};

    // Vertices are pulled from storage buffers: no vertex input state.
    VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    VkPipelineInputAssemblyStateCreateInfo inputAssembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    inputAssembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = desc.cullMode;
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = desc.depthTest;
    depth.depthWriteEnable = desc.depthWrite;
    depth.depthCompareOp = desc.depthCompare;
    VkPipelineColorBlendAttachmentState blendAttachment{};
    blendAttachment.colorWriteMask =
        VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blend.attachmentCount = 1;
    blend.pAttachments = &blendAttachment;
    VkDynamicState dynamicStates[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamicStates;

    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachmentFormats = &desc.colorFormat;
    rendering.depthAttachmentFormat = desc.depthFormat;

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
    info.stageCount = 2;
    info.pStages = stages;
    info.pVertexInputState = &vertexInput;
    info.pInputAssemblyState = &inputAssembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = p.layout;
    VK_CHECK(vkCreateGraphicsPipelines(ctx.device, VK_NULL_HANDLE, 1, &info, nullptr, &p.pipeline));
    return p;
}

void pushConstants(Context& ctx, VkCommandBuffer cmd, const Pipeline& p, const void* data, uint32_t size) {
    if (size != p.pushConstantSize)
        throw Error("pipeline " + p.name + ": " + std::to_string(size) + " bytes of push constants for a block of " +
                    std::to_string(p.pushConstantSize));
    ctx.hostBytesWritten += size;
    vkCmdPushConstants(cmd, p.layout, p.pushConstantStages, 0, size, data);
}

void destroyPipeline(Context& ctx, Pipeline& p) {
    if (p.pipeline)
        vkDestroyPipeline(ctx.device, p.pipeline, nullptr);
    if (p.layout)
        vkDestroyPipelineLayout(ctx.device, p.layout, nullptr);
    if (p.setLayout)
        vkDestroyDescriptorSetLayout(ctx.device, p.setLayout, nullptr);
    p = Pipeline{};
}

Binding::Binding(const Buffer& b) : buffer{b.buffer, 0, b.size} {}
Binding::Binding(VkImageView view, VkImageLayout layout, VkSampler sampler)
    : image{sampler, view, layout}, isImage(true) {}
Binding::Binding(VkBufferView view) : texelView(view) {}

void bindPipeline(Context& ctx, VkCommandBuffer cmd, const Pipeline& p, std::initializer_list<Binding> bindings) {
    if (bindings.size() != p.bindingTypes.size())
        throw Error("pipeline " + p.name + " declares " + std::to_string(p.bindingTypes.size()) + " bindings but " +
                    std::to_string(bindings.size()) + " were given");
    vkCmdBindPipeline(cmd, p.bindPoint, p.pipeline);
    if (bindings.size() == 0)
        return;
    std::vector<VkWriteDescriptorSet> writes;
    uint32_t index = 0;
    for (const Binding& b : bindings) {
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstBinding = index;
        w.descriptorCount = 1;
        w.descriptorType = p.bindingTypes[index];
        bool wantsImage = w.descriptorType == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE ||
                          w.descriptorType == VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE ||
                          w.descriptorType == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        bool wantsTexels = w.descriptorType == VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER ||
                           w.descriptorType == VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
        bool isTexels = b.texelView != VK_NULL_HANDLE;
        if (wantsImage != b.isImage || wantsTexels != isTexels)
            throw Error("pipeline " + p.name + ": binding " + std::to_string(index) + " expects " +
                        (wantsImage    ? "an image"
                         : wantsTexels ? "a texel buffer's view"
                                       : "a buffer"));
        if (b.isImage)
            w.pImageInfo = &b.image;
        else if (isTexels)
            w.pTexelBufferView = &b.texelView;
        else
            w.pBufferInfo = &b.buffer;
        writes.push_back(w);
        ++index;
    }
    ctx.cmdPushDescriptorSet(cmd, p.bindPoint, p.layout, 0, static_cast<uint32_t>(writes.size()), writes.data());
}

void dispatchCovering(VkCommandBuffer cmd, const Pipeline& p, uint32_t x, uint32_t y) {
    uint32_t gx = (x + p.localSize[0] - 1) / p.localSize[0];
    uint32_t gy = (y + p.localSize[1] - 1) / p.localSize[1];
    if (gx > 0 && gy > 0)
        vkCmdDispatch(cmd, gx, gy, 1);
}

} // namespace meadow
