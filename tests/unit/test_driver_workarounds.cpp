// The lavapipe settings meadow corrects or refuses (engine/vk/driver_workarounds.h). The renders
// under each setting are tests/driver/lavapipe_settings.sh.
#include "vk/driver_workarounds.h"

#include <gtest/gtest.h>

using namespace meadow;

namespace {
LavapipeSettings avx512Cpu(unsigned width, const char* caps) {
    LavapipeSettings s;
    s.vectorWidth = width;
    s.cpuCapsOverride = caps;
    s.cpuHasAvx = true;
    s.cpuHasAvx512 = true;
    return s;
}
} // namespace

TEST(DriverWorkarounds, HidesAvx512At128BitVectors) {
    EXPECT_EQ(lavapipeCapsWorkaround(avx512Cpu(128, "")), "avx");
    // A value Mesa ignores is no choice of the user's: it is replaced too.
    EXPECT_EQ(lavapipeCapsWorkaround(avx512Cpu(128, "avx2")), "avx");
}

TEST(DriverWorkarounds, LeavesEverythingElseAlone) {
    EXPECT_EQ(lavapipeCapsWorkaround(avx512Cpu(256, "")), "");    // the width lavapipe picks itself
    EXPECT_EQ(lavapipeCapsWorkaround(avx512Cpu(0, "")), "");      // LP_NATIVE_VECTOR_WIDTH unset
    EXPECT_EQ(lavapipeCapsWorkaround(avx512Cpu(128, "avx")), ""); // already what the workaround sets
    LavapipeSettings avx2 = avx512Cpu(128, "");
    avx2.cpuHasAvx512 = false;
    EXPECT_EQ(lavapipeCapsWorkaround(avx2), "");
}

TEST(DriverWorkarounds, RefusesCapsBelowAvxOnAnAvxCpu) {
    for (const char* caps : {"nosse", "sse", "sse2", "sse3", "ssse3", "sse4.1"}) {
        std::string reason = lavapipeUnsupportedReason(avx512Cpu(256, caps));
        EXPECT_NE(reason.find(std::string("GALLIUM_OVERRIDE_CPU_CAPS=") + caps + ":"), std::string::npos) << reason;
    }
    EXPECT_EQ(lavapipeUnsupportedReason(avx512Cpu(256, "avx")), "");
    EXPECT_EQ(lavapipeUnsupportedReason(avx512Cpu(256, "")), "");
    LavapipeSettings noAvx = avx512Cpu(128, "sse4.1");
    noAvx.cpuHasAvx = noAvx.cpuHasAvx512 = false;
    EXPECT_EQ(lavapipeUnsupportedReason(noAvx), ""); // nothing hidden that the CPU has
}
