// The lavapipe settings meadow adjusts or refuses (engine/vk/driver_workarounds.h). The renders
// under each setting are tests/system/driver/lavapipe_settings.sh.
#include "vk/driver_workarounds.h"

#include <cstdlib>
#include <gtest/gtest.h>
#include <string>

using namespace meadow;

namespace {
using Environment = std::vector<std::pair<std::string, std::string>>;

LavapipeSettings settings(unsigned width, const char* caps = "") {
    LavapipeSettings s;
    if (width != 0) // 0: LP_NATIVE_VECTOR_WIDTH unset
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

// LP_NATIVE_VECTOR_WIDTH read as Mesa 22.3 reads it (strtoll in base 0, what follows the digits
// ignored, the driver's own width when there is no digit); any width but 128 and 256 is refused on
// lavapipe, which crashes compiling the first compute pipeline at 512, 384, 64 or 0 bits.
TEST(DriverWorkarounds, ReadsTheVectorWidthAsMesaDoesAndRefusesWidthsItCannotCompileFor) {
    const char* saved = std::getenv("LP_NATIVE_VECTOR_WIDTH");
    const std::string before = saved ? saved : "";
    const auto read = [](const char* value) {
        setenv("LP_NATIVE_VECTOR_WIDTH", value, 1);
        return lavapipeSettingsFromEnvironment();
    };
    struct Case {
        const char* value;
        bool set;
        unsigned width; // the width meadow keeps a shader cache for; 0: none
        bool refused;
    };
    for (const Case& c : {Case{"128", true, 128, false}, Case{"256", true, 256, false}, Case{"0x80", true, 128, false},
                          Case{"0400", true, 256, false}, Case{"256bits", true, 256, false},
                          Case{"abc", false, 0, false}, Case{"", false, 0, false}, Case{"512", true, 0, true},
                          Case{"64", true, 0, true}, Case{"0", true, 0, true}, Case{"-128", true, 0, true}}) {
        LavapipeSettings s = read(c.value);
        s.shaderCacheDir = s.xdgCacheHome = ""; // the cache's place as in settings(), whatever this process's
        s.home = "/home/u";
        EXPECT_EQ(s.vectorWidth.has_value(), c.set) << c.value;
        // A shader cache of its own for the widths lavapipe runs (as it reads them), none otherwise.
        const Environment cache = lavapipeEnvironment(s);
        if (c.width != 0) {
            EXPECT_EQ(cache, (Environment{{"MESA_SHADER_CACHE_DIR",
                                           "/home/u/.cache/meadow-lavapipe-" + std::to_string(c.width)}}))
                << c.value;
        } else {
            EXPECT_TRUE(cache.empty()) << c.value;
        }
        const std::string reason = lavapipeUnsupportedReason(s);
        if (c.refused) {
            EXPECT_EQ(reason.rfind(std::string("LP_NATIVE_VECTOR_WIDTH=") + c.value + ": lavapipe", 0), 0u) << reason;
        } else {
            EXPECT_EQ(reason, "") << c.value;
        }
    }
    if (saved)
        setenv("LP_NATIVE_VECTOR_WIDTH", before.c_str(), 1);
    else
        unsetenv("LP_NATIVE_VECTOR_WIDTH");
}
