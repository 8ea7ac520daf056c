#include "vk/spirv_reflect.h"

#include "vk/vk_check.h"

#include <unordered_map>
#include <vector>

namespace meadow {
namespace {

// The few SPIR-V opcodes and enumerants this parser reads (SPIR-V specification, section 3).
enum : uint32_t {
    kOpEntryPoint = 15,
    kOpExecutionMode = 16,
    kOpTypeImage = 25,
    kOpTypeSampler = 26,
    kOpTypeSampledImage = 27,
    kOpTypeArray = 28,
    kOpTypeRuntimeArray = 29,
    kOpTypeStruct = 30,
    kOpTypePointer = 32,
    kOpConstant = 43,
    kOpVariable = 59,
    kOpDecorate = 71,
    kOpExecutionModeId = 331,

    kDecorationBlock = 2,
    kDecorationBufferBlock = 3,
    kDecorationBinding = 33,
    kDecorationDescriptorSet = 34,

    kStorageUniformConstant = 0,
    kStorageUniform = 2,
    kStoragePushConstant = 9,
    kStorageStorageBuffer = 12,

    kModelVertex = 0,
    kModelFragment = 4,
    kModelGLCompute = 5,

    kModeLocalSize = 17,
    kModeLocalSizeId = 38,
};

struct Id {
    uint32_t opcode = 0;
    uint32_t typeId = 0;       // pointee / element type
    uint32_t storageClass = 0; // pointers and variables
    uint32_t set = ~0u;
    uint32_t binding = ~0u;
    uint32_t constant = 0;
    uint32_t sampled = 0; // OpTypeImage: 1 sampled, 2 storage
    bool block = false;
    bool bufferBlock = false;
};

} // namespace

ShaderReflection reflectShader(std::span<const uint32_t> code, const std::string& name) {
    if (code.size() < 5 || code[0] != 0x07230203)
        throw Error("shader " + name + ": not a SPIR-V module");
    uint32_t bound = code[3];
    std::vector<Id> ids(bound);
    ShaderReflection out;
    uint32_t localSizeIds[3] = {0, 0, 0};
    bool haveLocalSizeIds = false;

    for (size_t at = 5; at < code.size();) {
        uint32_t opcode = code[at] & 0xffff;
        uint32_t words = code[at] >> 16;
        if (words == 0 || at + words > code.size())
            throw Error("shader " + name + ": truncated SPIR-V instruction");
        const uint32_t* w = &code[at];
        auto id = [&](uint32_t word) -> Id& {
            if (w[word] >= bound)
                throw Error("shader " + name + ": SPIR-V id out of range");
            return ids[w[word]];
        };
        switch (opcode) {
        case kOpEntryPoint:
            switch (w[1]) {
            case kModelVertex: out.stage = VK_SHADER_STAGE_VERTEX_BIT; break;
            case kModelFragment: out.stage = VK_SHADER_STAGE_FRAGMENT_BIT; break;
            case kModelGLCompute: out.stage = VK_SHADER_STAGE_COMPUTE_BIT; break;
            default: throw Error("shader " + name + ": unsupported execution model " + std::to_string(w[1]));
            }
            break;
        case kOpExecutionMode:
            if (w[2] == kModeLocalSize && words >= 6)
                for (int i = 0; i < 3; ++i)
                    out.localSize[i] = w[3 + i];
            break;
        case kOpExecutionModeId:
            if (w[2] == kModeLocalSizeId && words >= 6) {
                for (int i = 0; i < 3; ++i)
                    localSizeIds[i] = w[3 + i];
                haveLocalSizeIds = true;
            }
            break;
        case kOpDecorate:
            if (w[2] == kDecorationBlock)
                id(1).block = true;
            if (w[2] == kDecorationBufferBlock)
                id(1).bufferBlock = true;
            if (w[2] == kDecorationBinding && words >= 4)
                id(1).binding = w[3];
            if (w[2] == kDecorationDescriptorSet && words >= 4)
                id(1).set = w[3];
            break;
        case kOpTypeImage:
            id(1).opcode = opcode;
            id(1).sampled = words >= 8 ? w[7] : 0;
            break;
        case kOpTypeSampler:
        case kOpTypeSampledImage:
        case kOpTypeStruct: id(1).opcode = opcode; break;
        case kOpTypeArray:
        case kOpTypeRuntimeArray:
            id(1).opcode = opcode;
            id(1).typeId = w[2];
            break;
        case kOpTypePointer:
            id(1).opcode = opcode;
            id(1).storageClass = w[2];
            id(1).typeId = w[3];
            break;
        case kOpConstant:
            id(2).opcode = opcode;
            id(2).constant = words >= 4 ? w[3] : 0;
            break;
        case kOpVariable:
            id(2).opcode = opcode;
            id(2).typeId = w[1];
            id(2).storageClass = w[3];
            break;
        default: break;
        }
        at += words;
    }
    if (haveLocalSizeIds)
        for (int i = 0; i < 3; ++i)
            out.localSize[i] = localSizeIds[i] < bound ? ids[localSizeIds[i]].constant : 0;

    for (uint32_t i = 0; i < bound; ++i) {
        const Id& var = ids[i];
        if (var.opcode != kOpVariable)
            continue;
        if (var.storageClass == kStoragePushConstant) {
            out.usesPushConstants = true;
            continue;
        }
        if (var.storageClass != kStorageUniform && var.storageClass != kStorageUniformConstant &&
            var.storageClass != kStorageStorageBuffer)
            continue;
        if (var.binding == ~0u)
            continue;
        if (var.set != 0)
            throw Error("shader " + name + ": binding " + std::to_string(var.binding) + " is in descriptor set " +
                        std::to_string(var.set) + "; meadow pushes descriptors to set 0 only");
        uint32_t typeId = ids[var.typeId].typeId; // pointer -> pointee
        while (typeId < bound && (ids[typeId].opcode == kOpTypeArray || ids[typeId].opcode == kOpTypeRuntimeArray))
            typeId = ids[typeId].typeId;
        if (typeId >= bound)
            throw Error("shader " + name + ": malformed variable type");
        const Id& type = ids[typeId];
        VkDescriptorType descriptor;
        if (var.storageClass == kStorageStorageBuffer || (var.storageClass == kStorageUniform && type.bufferBlock))
            descriptor = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        else if (var.storageClass == kStorageUniform && type.block)
            descriptor = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        else if (type.opcode == kOpTypeImage && type.sampled == 2)
            descriptor = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
        else if (type.opcode == kOpTypeImage)
            descriptor = VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
        else if (type.opcode == kOpTypeSampledImage)
            descriptor = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        else if (type.opcode == kOpTypeSampler)
            descriptor = VK_DESCRIPTOR_TYPE_SAMPLER;
        else
            throw Error("shader " + name + ": binding " + std::to_string(var.binding) +
                        " has a resource type meadow "
                        "does not support");
        out.bindings[var.binding] = descriptor;
    }
    if (out.stage == VK_SHADER_STAGE_ALL)
        throw Error("shader " + name + ": no entry point");
    return out;
}

} // namespace meadow
