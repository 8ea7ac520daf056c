// The lavapipe settings meadow adjusts or refuses (engine/vk/driver_workarounds.h). The renders
// under each setting are tests/system/driver/lavapipe_settings.sh.
#include "vk/driver_workarounds.h"

#include <gtest/gtest.h>

using namespace meadow;

namespace {
using Environment = std::vector<std::pair<std::string, std::string>>;

LavapipeSettings settings(unsigned width, const char* caps = "") {
    LavapipeSettings s;
    s.vectorWidth = width;
    s.cpuCapsOverride = caps;
    s.home = "/home/u";
    s.cpuHasAvx = true;
    return s;
}
} // namespace

TEST(DriverWorkarounds, EachVectorWidthGetsAShaderCacheOfItsOwn) {
    EXPECT_EQ(lavapipeEnvironment(settings(128)),
              (Environment{{"MESA_SHADER_CACHE_DIR", "/home/u/.cache/meadow-lavapipe-128"}}));
    EXPECT_EQ(lavapipeEnvironment(settings(256)),
              (Environment{{"MESA_SHADER_CACHE_DIR", "/home/u/.cache/meadow-lavapipe-256"}}));
    // Under the folder Mesa itself would use: the user's, then XDG_CACHE_HOME, then ~/.cache.
    LavapipeSettings s = settings(128);
    s.xdgCacheHome = "/xdg";
    EXPECT_EQ(lavapipeEnvironment(s), (Environment{{"MESA_SHADER_CACHE_DIR", "/xdg/meadow-lavapipe-128"}}));
    s.shaderCacheDir = "/mine";
    EXPECT_EQ(lavapipeEnvironment(s), (Environment{{"MESA_SHADER_CACHE_DIR", "/mine/meadow-lavapipe-128"}}));
    // Nowhere to put one: no cache.
    s = settings(128);
    s.home.clear();
    EXPECT_EQ(lavapipeEnvironment(s), (Environment{{"MESA_SHADER_CACHE_DISABLE", "true"}}));
}

TEST(DriverWorkarounds, TheDriversOwnWidthNeedsNothing) {
    EXPECT_TRUE(lavapipeEnvironment(settings(0)).empty()); // LP_NATIVE_VECTOR_WIDTH unset
}

TEST(DriverWorkarounds, RefusesCapsBelowAvxOnAnAvxCpu) {
    for (const char* caps : {"nosse", "sse", "sse2", "sse3", "ssse3", "sse4.1"}) {
        std::string reason = lavapipeUnsupportedReason(settings(256, caps));
        EXPECT_NE(reason.find(std::string("GALLIUM_OVERRIDE_CPU_CAPS=") + caps + ":"), std::string::npos) << reason;
    }
    EXPECT_EQ(lavapipeUnsupportedReason(settings(256, "avx")), "");
    EXPECT_EQ(lavapipeUnsupportedReason(settings(256, "")), "");
    EXPECT_EQ(lavapipeUnsupportedReason(settings(256, "avx2")), ""); // a value Mesa ignores
    LavapipeSettings noAvx = settings(128, "sse4.1");
    noAvx.cpuHasAvx = false;
    EXPECT_EQ(lavapipeUnsupportedReason(noAvx), ""); // nothing hidden that the CPU has
}
