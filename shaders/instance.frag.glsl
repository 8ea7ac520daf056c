#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

MEADOW_FRAME_BLOCK(0, 0)

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec3 inAlbedo;
layout(location = 2) in vec2 inUv;
layout(location = 0) out vec4 outColor;

void main() {
    // Blades are thin and two-sided: light the face the camera sees.
    vec3 n = normalize(inNormal) * (gl_FrontFacing ? 1.0 : -1.0);
    outColor = vec4(inAlbedo * diffuseLight(frame, n), 1.0);
}
