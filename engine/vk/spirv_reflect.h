// Reads back from a SPIR-V module what the host would otherwise repeat by hand: the stage, the
// compute workgroup size, the descriptor bindings (set 0 only: meadow uses push descriptors) and
// the size of the push-constant block, so pipeline layouts always match their shaders.
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vulkan/vulkan.h>

namespace meadow {

struct ShaderReflection {
    VkShaderStageFlagBits stage = VK_SHADER_STAGE_ALL;
    uint32_t localSize[3] = {0, 0, 0};             // compute only: the default where specialized
    bool localSizeXSpecialized = false;            // x is specialization constant 0 (local_size_x_id = 0)
    std::map<uint32_t, VkDescriptorType> bindings; // binding index -> type
    uint32_t pushConstantBytes = 0; // the push-constant block's size (last member's offset + size); 0: none
};

// Throws meadow::Error naming `name` when the module is malformed or uses what meadow does not
// support (a descriptor set other than 0, an unknown resource type).
ShaderReflection reflectShader(std::span<const uint32_t> code, const std::string& name);

} // namespace meadow
