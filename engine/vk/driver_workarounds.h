// Driver faults meadow works around, each found, measured and reproduced (docs/ROBUSTNESS.md,
// "lavapipe and the CPU it compiles for"; reproducers in tests/driver/).
//
// lavapipe (Mesa 22.3, LLVM 15) compiles shaders for the CPU it finds, as modified by two
// environment variables it reads once, when the driver loads: LP_NATIVE_VECTOR_WIDTH (128 or 256
// bits) and GALLIUM_OVERRIDE_CPU_CAPS (hide instruction sets). Two combinations are broken:
//  - 128-bit vectors on an AVX-512 CPU: for meadow's instance vertex shader the driver's
//    vertex loop stores 8 shaded vertices per step into a buffer sized for steps of 4, writing
//    past the end of a heap block (glibc aborts a few draws later). Hiding AVX-512
//    (GALLIUM_OVERRIDE_CPU_CAPS=avx) makes the same width safe.
//  - CPU features set below AVX on a CPU that has AVX (GALLIUM_OVERRIDE_CPU_CAPS=nosse ...
//    sse4.1): every compute pass jumps into an illegal instruction.
#pragma once

#include <string>
#include <vector>

namespace meadow {

// What the environment asks of lavapipe, and what this CPU has.
struct LavapipeSettings {
    unsigned vectorWidth = 0;    // LP_NATIVE_VECTOR_WIDTH, 0 when unset or not a number
    std::string cpuCapsOverride; // GALLIUM_OVERRIDE_CPU_CAPS, empty when unset or empty
    bool cpuHasAvx = false;
    bool cpuHasAvx512 = false;
};
LavapipeSettings lavapipeSettingsFromEnvironment();

// The override to set for `settings` so that lavapipe compiles correct code, or empty when none is
// needed (a GALLIUM_OVERRIDE_CPU_CAPS that Mesa acts on is never replaced).
std::string lavapipeCapsWorkaround(const LavapipeSettings& settings);

// Why lavapipe cannot run meadow with `settings`, or empty when it can.
std::string lavapipeUnsupportedReason(const LavapipeSettings& settings);

// Called before the process's first Vulkan call: sets the workaround's override in the
// environment and returns a line saying so (empty when nothing was set).
std::string applyLavapipeWorkarounds();

} // namespace meadow
