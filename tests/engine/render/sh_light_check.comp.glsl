#version 460
// Build-time check that shaders/shared/sh_light.h compiles as GLSL (the lighting passes will
// include it): one clump-frame sky per invocation. Not a render pass.
#extension GL_GOOGLE_include_directive : require
#include "sh_light.h"

layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) readonly buffer Sky { float sky[kShLightRgbFloats]; };
// Per instance: yaw (radians), mirrored (0 or 1), wind azimuth atan2(wx, wz), unused.
layout(std430, set = 0, binding = 1) readonly buffer Instances { vec4 yawMirroredWind[]; };
layout(std430, set = 0, binding = 2) writeonly buffer ClumpSky { float clumpSky[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= yawMirroredWind.length())
        return;
    vec4 instance = yawMirroredWind[i];
    bool mirrored = instance.y != 0.0;
    float skyIn[kShLightRgbFloats];
    for (uint k = 0u; k < kShLightRgbFloats; ++k)
        skyIn[k] = sky[k];
    float skyOut[kShLightRgbFloats];
    shSkyToClumpFrame(skyIn, shClumpFrameSign(mirrored), shClumpFrameDelta(instance.x, mirrored, instance.z), skyOut);
    for (uint k = 0u; k < kShLightRgbFloats; ++k)
        clumpSky[i * kShLightRgbFloats + k] = skyOut[k];
}
