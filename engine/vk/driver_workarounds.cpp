#include "vk/driver_workarounds.h"

#include <cstdlib>
#include <string_view>

namespace meadow {

LavapipeSettings lavapipeSettingsFromEnvironment() {
    LavapipeSettings s;
    if (const char* width = std::getenv("LP_NATIVE_VECTOR_WIDTH")) {
        char* end = nullptr;
        unsigned long value = std::strtoul(width, &end, 10);
        if (end != width && *end == '\0' && value <= 4096)
            s.vectorWidth = unsigned(value);
    }
    if (const char* caps = std::getenv("GALLIUM_OVERRIDE_CPU_CAPS"))
        s.cpuCapsOverride = caps;
#if defined(__x86_64__) || defined(__i386__)
    __builtin_cpu_init();
    s.cpuHasAvx = __builtin_cpu_supports("avx");
    s.cpuHasAvx512 = __builtin_cpu_supports("avx512f");
#endif
    return s;
}

namespace {
// The values of GALLIUM_OVERRIDE_CPU_CAPS that Mesa 22.3 acts on (util/u_cpu_detect.c); it
// ignores any other. All but the last hide AVX.
constexpr std::string_view kCapsValues[] = {"nosse", "sse", "sse2", "sse3", "ssse3", "sse4.1", "avx"};
constexpr std::string_view kCapsAvx = "avx";

bool mesaActsOn(const std::string& caps) {
    for (std::string_view value : kCapsValues)
        if (caps == value)
            return true;
    return false;
}
} // namespace

std::string lavapipeCapsWorkaround(const LavapipeSettings& s) {
    // 128-bit vectors with AVX-512 left visible to LLVM: the vertex loop overruns its buffer.
    if (s.cpuHasAvx512 && s.vectorWidth != 0 && s.vectorWidth <= 128 && !mesaActsOn(s.cpuCapsOverride))
        return std::string(kCapsAvx);
    return {};
}

std::string lavapipeUnsupportedReason(const LavapipeSettings& s) {
    if (s.cpuHasAvx && mesaActsOn(s.cpuCapsOverride) && s.cpuCapsOverride != kCapsAvx)
        return "GALLIUM_OVERRIDE_CPU_CAPS=" + s.cpuCapsOverride +
               ": lavapipe (Mesa 22.3) hides this CPU's AVX from LLVM but still runs meadow's compute passes "
               "into an illegal instruction; unset it or set it to 'avx' (docs/ROBUSTNESS.md)";
    return {};
}

std::string applyLavapipeWorkarounds() {
    LavapipeSettings settings = lavapipeSettingsFromEnvironment();
    std::string caps = lavapipeCapsWorkaround(settings);
    if (caps.empty())
        return {};
    setenv("GALLIUM_OVERRIDE_CPU_CAPS", caps.c_str(), 1); // replaces only a value Mesa would ignore
    return "LP_NATIVE_VECTOR_WIDTH=" + std::to_string(settings.vectorWidth) +
           " on an AVX-512 CPU: set GALLIUM_OVERRIDE_CPU_CAPS=" + caps +
           " (lavapipe's vertex loop overruns its buffer otherwise; docs/ROBUSTNESS.md)";
}

} // namespace meadow
