// The memory check against a real device (lavapipe in the tests): a field larger than the device's
// memory is refused before anything is allocated, with both figures in the message; one that fits
// passes, and the figures describe the heap the allocator uses.
#include "core/error.h"
#include "vk/context.h"
#include "vk/memory.h"
#include "vk/memory_budget.h"

#include <gtest/gtest.h>

namespace meadow {
namespace {

class DeviceMemoryBudget : public ::testing::Test {
  protected:
    void SetUp() override {
        ContextOptions options;
        options.validation = true; // the extension query must be valid usage too
        createContext(context_, options);
    }
    void TearDown() override {
        if (context_.validation) {
            EXPECT_EQ(context_.validation->total(), 0u) << "validation messages";
        }
        destroyContext(context_);
    }
    Context context_;
};

TEST_F(DeviceMemoryBudget, FiguresDescribeTheDeviceLocalHeap) {
    const DeviceMemoryFigures figures = deviceMemoryFigures(context_);
    EXPECT_EQ(figures.deviceName, context_.deviceName());
    ASSERT_LT(figures.heapIndex, context_.memoryProperties.memoryHeapCount);
    EXPECT_EQ(figures.heapBytes, context_.memoryProperties.memoryHeaps[figures.heapIndex].size);
    EXPECT_GT(figures.availableBytes, 0u);
    EXPECT_LE(figures.availableBytes, figures.heapBytes);
}

TEST_F(DeviceMemoryBudget, FieldLargerThanTheDeviceIsRefusedWithBothFigures) {
    const DeviceMemoryFigures figures = deviceMemoryFigures(context_);
    const uint64_t needed = 2 * figures.heapBytes;
    try {
        checkFieldMemory(context_, needed);
        FAIL() << "twice the heap was accepted";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("the field needs " + formatMiB(needed) + " of GPU memory; the device has " +
                               formatMiB(figures.heapBytes)),
                  std::string::npos)
            << message;
    }
    EXPECT_NO_THROW(checkFieldMemory(context_, 64ull << 20)); // 64 MiB: any Vulkan device has that
}

// MEADOW_GPU_MEMORY_MIB caps what meadow counts on, so the refusal can be seen on any machine.
TEST_F(DeviceMemoryBudget, EnvironmentLimitCapsWhatIsAvailable) {
    setenv("MEADOW_GPU_MEMORY_MIB", "100", 1);
    const DeviceMemoryFigures figures = deviceMemoryFigures(context_);
    try {
        checkFieldMemory(context_, 200ull << 20);
        ADD_FAILURE() << "200 MiB passed a limit of 100 MiB";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("the field needs 200.0 MiB of GPU memory"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("MEADOW_GPU_MEMORY_MIB allowing 100.0 MiB"), std::string::npos)
            << e.what();
    }
    setenv("MEADOW_GPU_MEMORY_MIB", "lots", 1);
    EXPECT_THROW(deviceMemoryFigures(context_), Error);
    unsetenv("MEADOW_GPU_MEMORY_MIB");
    EXPECT_EQ(figures.limitBytes, 100ull << 20);
    EXPECT_LE(figures.availableBytes, 100ull << 20);
}

// What meadow's allocator already holds counts against what is left.
TEST_F(DeviceMemoryBudget, AllocationsReduceWhatIsAvailable) {
    const DeviceMemoryFigures before = deviceMemoryFigures(context_);
    Buffer buffer = createBuffer(context_, 256ull << 20, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::Device);
    const DeviceMemoryFigures after = deviceMemoryFigures(context_);
    destroyBuffer(context_, buffer);
    // Without a budget, exactly the allocation; with one, what the driver reports (at least the
    // allocation less its rounding, as lavapipe and GPU drivers account whole blocks).
    EXPECT_LE(after.availableBytes + (255ull << 20), before.availableBytes);
}

} // namespace
} // namespace meadow
