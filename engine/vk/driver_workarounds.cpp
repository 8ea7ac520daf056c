#include "vk/driver_workarounds.h"

#include <cstdlib>
#include <filesystem>
#include <string_view>

namespace meadow {
namespace {

std::string environment(const char* name) {
    const char* value = std::getenv(name);
    return value ? value : "";
}

// The vector widths lavapipe (Mesa 22.3) compiles shaders at without crashing.
bool lavapipeCompilesAt(long long width) {
    return width == 128 || width == 256;
}

} // namespace

LavapipeSettings lavapipeSettingsFromEnvironment() {
    LavapipeSettings s;
    // As Mesa 22.3's debug_get_num_option reads it (util/u_debug.c): strtoll in base 0, the
    // default when no digit was read.
    s.vectorWidthText = environment("LP_NATIVE_VECTOR_WIDTH");
    char* end = nullptr;
    const long long value = std::strtoll(s.vectorWidthText.c_str(), &end, 0);
    if (end != s.vectorWidthText.c_str())
        s.vectorWidth = value;
    s.cpuCapsOverride = environment("GALLIUM_OVERRIDE_CPU_CAPS");
    s.shaderCacheDir = environment("MESA_SHADER_CACHE_DIR");
    s.xdgCacheHome = environment("XDG_CACHE_HOME");
    s.home = environment("HOME");
#if defined(__x86_64__) || defined(__i386__)
    __builtin_cpu_init();
    s.cpuHasAvx = __builtin_cpu_supports("avx");
#endif
    return s;
}

std::vector<std::pair<std::string, std::string>> lavapipeEnvironment(const LavapipeSettings& s) {
    if (!s.vectorWidth || !lavapipeCompilesAt(*s.vectorWidth))
        return {}; // lavapipe picks its width from the CPU and caps, which Mesa's cache key holds (or
                   // it is refused: lavapipeUnsupportedReason)
    // Mesa's own choice of folder (util/disk_cache_os.c), one level down.
    std::string base = s.shaderCacheDir;
    if (base.empty() && !s.xdgCacheHome.empty())
        base = s.xdgCacheHome;
    if (base.empty() && !s.home.empty())
        base = s.home + "/.cache";
    if (base.empty())
        return {{"MESA_SHADER_CACHE_DISABLE", "true"}};
    return {{"MESA_SHADER_CACHE_DIR", base + "/meadow-lavapipe-" + std::to_string(*s.vectorWidth)}};
}

std::string lavapipeUnsupportedReason(const LavapipeSettings& s) {
    // Mesa 22.3's values that hide AVX (util/u_cpu_detect.c); it ignores values it does not know.
    static constexpr std::string_view kBelowAvx[] = {"nosse", "sse", "sse2", "sse3", "ssse3", "sse4.1"};
    if (s.vectorWidth && !lavapipeCompilesAt(*s.vectorWidth))
        return "LP_NATIVE_VECTOR_WIDTH=" + s.vectorWidthText + ": lavapipe (Mesa 22.3) compiles shaders at 128 or " +
               "256 bits only, and crashes compiling them at " + std::to_string(*s.vectorWidth) +
               "; unset it or set 128 or 256 (docs/ROBUSTNESS.md)";
    if (!s.cpuHasAvx)
        return {};
    for (std::string_view caps : kBelowAvx)
        if (s.cpuCapsOverride == caps)
            return "GALLIUM_OVERRIDE_CPU_CAPS=" + s.cpuCapsOverride +
                   ": lavapipe (Mesa 22.3) hides this CPU's AVX and F16C, and its half-float conversion then "
                   "jumps into an illegal instruction; unset it or set it to 'avx' (docs/ROBUSTNESS.md)";
    return {};
}

std::string applyLavapipeWorkarounds() {
    std::string note;
    for (auto [name, value] : lavapipeEnvironment(lavapipeSettingsFromEnvironment())) {
        // Mesa creates only the last folder of MESA_SHADER_CACHE_DIR (and says so on stderr when
        // its parent is missing, as ~/.cache is on a fresh machine): make the whole path here, or
        // turn the cache off when it cannot be made.
        if (name == "MESA_SHADER_CACHE_DIR") {
            std::error_code error;
            std::filesystem::create_directories(value, error);
            if (error || !std::filesystem::is_directory(value, error)) {
                name = "MESA_SHADER_CACHE_DISABLE";
                value = "true";
            }
        }
        setenv(name.c_str(), value.c_str(), 1);
        note += (note.empty() ? "" : " ") + name + "=" + value;
    }
    if (!note.empty())
        note = "lavapipe's shader cache kept apart for LP_NATIVE_VECTOR_WIDTH (Mesa 22.3 would reuse code "
               "compiled for another width): " +
               note;
    return note;
}

} // namespace meadow
