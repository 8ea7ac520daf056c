#version 460
// unpackHalf2x16 (half -> float) is all it takes: with GALLIUM_OVERRIDE_CPU_CAPS=nosse .. sse4.1
// (no AVX, so no F16C) lavapipe's JIT code jumps into the middle of a libLLVM function (SIGILL).
// packHalf2x16, atomics, loops, sin/cos, floor, int <-> float do not.
layout(local_size_x = 1) in;
layout(set = 0, binding = 0, std430) buffer Data { uint words[]; };

void main() {
    words[1] = floatBitsToUint(unpackHalf2x16(words[0]).x);
}
