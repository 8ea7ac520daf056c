#include "vk/spirv_reflect.h"

#include "vk/vk_check.h"

#include <algorithm>
#include <unordered_map>
#include <vector>

namespace meadow {
namespace {

// The few SPIR-V opcodes and enumerants this parser reads (SPIR-V specification, section 3).
enum : uint32_t {
    kOpEntryPoint = 15,
    kOpExecutionMode = 16,
    kOpTypeInt = 21,
    kOpTypeFloat = 22,
    kOpTypeVector = 23,
    kOpTypeMatrix = 24,
    kOpTypeImage = 25,
    kOpTypeSampler = 26,
    kOpTypeSampledImage = 27,
    kOpTypeArray = 28,
    kOpTypeRuntimeArray = 29,
    kOpTypeStruct = 30,
    kOpTypePointer = 32,
    kOpConstant = 43,
    kOpSpecConstant = 50,
    kOpVariable = 59,
    kOpDecorate = 71,
    kOpMemberDecorate = 72,
    kOpExecutionModeId = 331,

    kDecorationBlock = 2,
    kDecorationArrayStride = 6,
    kDecorationMatrixStride = 7,
    kDecorationBufferBlock = 3,
    kDecorationBinding = 33,
    kDecorationDescriptorSet = 34,
    kDecorationOffset = 35,
    kDecorationSpecId = 1,
    kDimBuffer = 5, // OpTypeImage's Dim for texel buffers

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
    uint32_t specId = ~0u; // OpSpecConstant: its SpecId decoration
    uint32_t sampled = 0;  // OpTypeImage: 1 sampled, 2 storage
    uint32_t dim = 0;      // OpTypeImage: its Dim (kDimBuffer: a texel buffer)
    uint32_t width = 0;    // OpTypeInt, OpTypeFloat: bits
    uint32_t count = 0;    // OpTypeVector: components; OpTypeMatrix: columns; OpTypeArray: the length's id
    uint32_t arrayStride = 0;
    bool block = false;
    bool bufferBlock = false;
    struct Member {
        uint32_t type = 0, offset = 0, matrixStride = 0;
    };
    std::vector<Member> members; // OpTypeStruct
};

// The bytes a value of `typeId` spans in an explicitly laid out block (push constants): scalars,
// vectors, matrices, arrays and structs, by their Offset, ArrayStride and MatrixStride.
uint32_t typeBytes(const std::vector<Id>& ids, uint32_t typeId, uint32_t matrixStride, int depth,
                   const std::string& name) {
    if (typeId >= ids.size() || depth > 16)
        throw Error("shader " + name + ": malformed push-constant type");
    const Id& t = ids[typeId];
    switch (t.opcode) {
    case kOpTypeInt:
    case kOpTypeFloat: return t.width / 8;
    case kOpTypeVector: return t.count * typeBytes(ids, t.typeId, 0, depth + 1, name);
    case kOpTypeMatrix: return t.count * (matrixStride ? matrixStride : typeBytes(ids, t.typeId, 0, depth + 1, name));
    case kOpTypeArray: {
        uint32_t length = t.count < ids.size() ? ids[t.count].constant : 0;
        return length * (t.arrayStride ? t.arrayStride : typeBytes(ids, t.typeId, 0, depth + 1, name));
    }
    case kOpTypeStruct: {
        uint32_t end = 0;
        for (const Id::Member& m : t.members)
            end = std::max(end, m.offset + typeBytes(ids, m.type, m.matrixStride, depth + 1, name));
        return end;
    }
    default: throw Error("shader " + name + ": a push constant of a type meadow does not lay out");
    }
}

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
            if (w[2] == kDecorationArrayStride && words >= 4)
                id(1).arrayStride = w[3];
            if (w[2] == kDecorationSpecId && words >= 4)
                id(1).specId = w[3];
            break;
        case kOpMemberDecorate:
            if (words >= 5 && (w[3] == kDecorationOffset || w[3] == kDecorationMatrixStride)) {
                // Decorations come before the types: the struct's member types fill in later.
                std::vector<Id::Member>& members = id(1).members;
                if (w[2] >= 4096)
                    throw Error("shader " + name + ": a member decoration names member " + std::to_string(w[2]));
                if (w[2] >= members.size())
                    members.resize(w[2] + 1);
                (w[3] == kDecorationOffset ? members[w[2]].offset : members[w[2]].matrixStride) = w[4];
            }
            break;
        case kOpTypeInt:
        case kOpTypeFloat:
            id(1).opcode = opcode;
            id(1).width = words >= 3 ? w[2] : 0;
            break;
        case kOpTypeVector:
        case kOpTypeMatrix:
            id(1).opcode = opcode;
            id(1).typeId = words >= 4 ? w[2] : 0;
            id(1).count = words >= 4 ? w[3] : 0;
            break;
        case kOpTypeImage:
            id(1).opcode = opcode;
            id(1).dim = words >= 4 ? w[3] : 0;
            id(1).sampled = words >= 8 ? w[7] : 0;
            break;
        case kOpTypeSampler: id(1).opcode = opcode; break;
        case kOpTypeSampledImage:
            id(1).opcode = opcode;
            id(1).typeId = words >= 3 ? w[2] : 0; // the image type
            break;
        case kOpTypeStruct:
            id(1).opcode = opcode;
            if (id(1).members.size() > words - 2)
                throw Error("shader " + name + ": a member decoration names a member the struct lacks");
            id(1).members.resize(words - 2);
            for (uint32_t m = 2; m < words; ++m)
                id(1).members[m - 2].type = w[m];
            break;
        case kOpTypeArray:
        case kOpTypeRuntimeArray:
            id(1).opcode = opcode;
            id(1).typeId = w[2];
            id(1).count = opcode == kOpTypeArray && words >= 4 ? w[3] : 0;
            break;
        case kOpTypePointer:
            id(1).opcode = opcode;
            id(1).storageClass = w[2];
            id(1).typeId = w[3];
            break;
        case kOpConstant:
        case kOpSpecConstant: // its default value
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

    // local_size_x_id = 0: LocalSizeId's x (SPIR-V 1.4 and later, what meadow builds) is the
    // specialization constant with SpecId 0.
    if (haveLocalSizeIds && localSizeIds[0] < bound && ids[localSizeIds[0]].opcode == kOpSpecConstant &&
        ids[localSizeIds[0]].specId == 0)
        out.localSizeXSpecialized = true;

    for (uint32_t i = 0; i < bound; ++i) {
        const Id& var = ids[i];
        if (var.opcode != kOpVariable)
            continue;
        if (var.storageClass == kStoragePushConstant) {
            uint32_t pointee = var.typeId < bound ? ids[var.typeId].typeId : bound;
            out.pushConstantBytes = std::max(out.pushConstantBytes, typeBytes(ids, pointee, 0, 0, name));
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
        else if (type.opcode == kOpTypeImage && type.dim == kDimBuffer)
            descriptor =
                type.sampled == 2 ? VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
        else if (type.opcode == kOpTypeImage && type.sampled == 2)
            descriptor = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
        else if (type.opcode == kOpTypeImage)
            descriptor = VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
        else if (type.opcode == kOpTypeSampledImage && type.typeId < bound && ids[type.typeId].dim == kDimBuffer)
            descriptor = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER; // GLSL's samplerBuffer
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
