// Driver faults meadow works around, each found, measured and reproduced (docs/ROBUSTNESS.md,
// "lavapipe and the CPU it compiles for"; reproducers in tests/system/driver/).
//
// lavapipe (Mesa 22.3, LLVM 15) compiles shaders for the CPU it finds, as modified by two
// environment variables it reads once, when the driver loads: LP_NATIVE_VECTOR_WIDTH (128 or 256
// bits) and GALLIUM_OVERRIDE_CPU_CAPS (hide instruction sets). Three faults follow:
//  - Mesa's on-disk shader cache keys vertex code by the CPU caps but not by the vector width, so
//    a process at 128 bits runs vertex code cached by one at 256: its loop stores 8 shaded
//    vertices per step into a buffer sized for steps of 4, past the end of a heap block (glibc
//    aborts a few draws later). meadow gives each width it is told to use a cache of its own.
//  - CPU caps set below AVX on a CPU that has AVX (GALLIUM_OVERRIDE_CPU_CAPS=nosse ... sse4.1):
//    half-float conversion (unpackHalf2x16, rgba16f loads) jumps into an illegal instruction.
//    meadow refuses to start on lavapipe with them.
//  - Any vector width but 128 and 256 (512 on an AVX-512 CPU, 64, 0, ...): lavapipe crashes
//    while it compiles the first compute pipeline (a segmentation fault in LLVM, or a division by
//    zero). meadow refuses to start on lavapipe with them too.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace meadow {

// What the environment asks of lavapipe and its shader cache, and what this CPU has.
struct LavapipeSettings {
    // LP_NATIVE_VECTOR_WIDTH as Mesa reads it (strtoll, base 0, what follows the digits ignored);
    // none when unset or without a digit, and lavapipe picks its own.
    std::optional<long long> vectorWidth;
    std::string vectorWidthText; // as set
    std::string cpuCapsOverride; // GALLIUM_OVERRIDE_CPU_CAPS, empty when unset or empty
    std::string shaderCacheDir;  // MESA_SHADER_CACHE_DIR, empty when unset
    std::string xdgCacheHome;    // XDG_CACHE_HOME
    std::string home;            // HOME
    bool cpuHasAvx = false;
};
LavapipeSettings lavapipeSettingsFromEnvironment();

// The environment variables to set for `settings` (name, value), in order; empty when none:
// with a vector width given, Mesa's shader cache moves to a folder of that width
// (MESA_SHADER_CACHE_DIR: the user's, else $XDG_CACHE_HOME or ~/.cache, then
// meadow-lavapipe-<width>), or is turned off when there is no place for one.
std::vector<std::pair<std::string, std::string>> lavapipeEnvironment(const LavapipeSettings& settings);

// Why lavapipe cannot run meadow with `settings`, or empty when it can.
std::string lavapipeUnsupportedReason(const LavapipeSettings& settings);

// Called before the process's first Vulkan call: sets lavapipeEnvironment's variables and
// returns a line saying so (empty when nothing was set).
std::string applyLavapipeWorkarounds();

} // namespace meadow
