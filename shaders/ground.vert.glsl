#version 460
// The ground: one large quad generated from gl_VertexIndex (two triangles), centred under the
// field.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

MEADOW_FRAME_BLOCK(0, 0)
layout(push_constant) uniform GroundParams { vec4 centerHalfSize; };

layout(location = 0) out vec3 outWorld;

void main() {
    const vec2 corners[6] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
    vec2 p = corners[gl_VertexIndex] * centerHalfSize.w + centerHalfSize.xz;
    outWorld = vec3(p.x, centerHalfSize.y, p.y);
    gl_Position = frame.viewProj * vec4(outWorld, 1.0);
}
