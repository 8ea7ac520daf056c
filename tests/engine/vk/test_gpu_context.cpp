// The Vulkan core on a real device (lavapipe in CI): upload and readback, the memory
// sub-allocator, and the validation plumbing that every GPU test relies on.
// ctest runs these at two lavapipe vector widths (LP_NATIVE_VECTOR_WIDTH=128 and 256).
#include "core/error.h"
#include "gpu_fixture.h"
#include "sh_light.h"
#include "vk/barriers.h"
#include "vk/context.h"
#include "vk/memory.h"
#include "vk/pipeline.h"
#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>
#include <random>

using namespace meadow;
using namespace meadow::test;

TEST_F(Gpu, UploadAndReadbackRoundTrip) {
    std::vector<uint32_t> data(100000);
    for (size_t i = 0; i < data.size(); ++i)
        data[i] = uint32_t(i * 2654435761u);
    Buffer buffer = createBuffer(*context, data.size() * 4,
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                 MemoryUse::Device);
    uploadToBuffer(*context, buffer, data.data(), data.size() * 4);
    std::vector<uint32_t> back(data.size());
    readbackBuffer(*context, buffer, back.data(), back.size() * 4);
    EXPECT_EQ(back, data);
    // A partial range at an offset.
    uint32_t patch[3] = {7, 8, 9};
    uploadToBuffer(*context, buffer, patch, sizeof(patch), 400);
    uint32_t readPatch[4] = {};
    readbackBuffer(*context, buffer, readPatch, sizeof(readPatch), 396);
    EXPECT_EQ(readPatch[0], data[99]);
    EXPECT_EQ(readPatch[1], 7u);
    EXPECT_EQ(readPatch[3], 9u);
    destroyBuffer(*context, buffer);
}

TEST_F(Gpu, SubAllocatorSharesBlocksAndReturnsMemory) {
    VkDeviceSize before = context->memory->bytesInUse();
    std::vector<Buffer> buffers;
    for (int i = 0; i < 64; ++i)
        buffers.push_back(
            createBuffer(*context, 4096 + 17 * VkDeviceSize(i), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::Device));
    // Sixty-four small buffers fit in one block.
    for (const Buffer& b : buffers)
        EXPECT_EQ(b.allocation.memory, buffers[0].allocation.memory);
    for (Buffer& b : buffers)
        destroyBuffer(*context, b);
    EXPECT_EQ(context->memory->bytesInUse(), before);
    // A buffer bigger than a block gets its own.
    Buffer big = createBuffer(*context, MemoryAllocator::kBlockSize + 4096, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              MemoryUse::Device);
    EXPECT_EQ(big.allocation.offset, 0u);
    destroyBuffer(*context, big);
}

// A push-constant size other than the shader's block is refused, naming both, and the refused
// pipeline leaves nothing on the device (the fixture's validation check).
TEST_F(Gpu, PushConstantSizeMustMatchTheShader) {
    auto refusal = [&](std::string_view shader, uint32_t size) {
        try {
            Pipeline p = createComputePipeline(*context, shader, size);
            destroyPipeline(*context, p);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(refusal("light.comp", 8), "pipeline light.comp: push constant size 8 but the shaders' block is 4 bytes");
    EXPECT_EQ(refusal("light.comp", 0), "pipeline light.comp: push constant size 0 but the shaders' block is 4 bytes");
    EXPECT_EQ(refusal("cull.comp", 4), "pipeline cull.comp: push constant size 4 but the shaders declare none");
    EXPECT_EQ(refusal("light.comp", 4), "no error");
}

// The validation plumbing itself: a real hazard must be reported, or the validation tests
// could never fail. Uses its own context so the suite's counter stays clean.
TEST(GpuValidation, SynchronizationHazardIsReported) {
    Context ctx;
    ContextOptions options;
    options.validation = true;
    createContext(ctx, options);
    Buffer buffer = createBuffer(ctx, 1024, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Device);
    testing::internal::CaptureStderr();
    submitAndWait(ctx, [&](VkCommandBuffer cmd) {
        // Two writes to the same range with no barrier between them: a write-after-write hazard.
        vkCmdFillBuffer(cmd, buffer.buffer, 0, 1024, 1);
        vkCmdFillBuffer(cmd, buffer.buffer, 0, 1024, 2);
    });
    std::string messages = testing::internal::GetCapturedStderr();
    EXPECT_GE(ctx.validation->errors.load(), 1u);
    EXPECT_NE(messages.find("SYNC-HAZARD-WRITE-AFTER-WRITE"), std::string::npos) << messages;
    destroyBuffer(ctx, buffer);
    destroyContext(ctx);
}

TEST(GpuContext, UnknownDeviceOverrideIsNamed) {
    Context ctx;
    ContextOptions options;
    options.deviceOverride = "no-such-gpu-model";
    try {
        createContext(ctx, options);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        std::string m = e.what();
        EXPECT_NE(m.find("no-such-gpu-model"), std::string::npos) << m;
        EXPECT_NE(m.find("devices:"), std::string::npos) << m;
    }
    destroyContext(ctx);
}
