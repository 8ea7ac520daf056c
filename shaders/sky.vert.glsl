#version 460
// Sky backdrop: a full-screen triangle infinitely far (depth 0 with reversed Z), drawn last where
// the depth test finds nothing nearer.
layout(location = 0) out vec2 outClip;

void main() {
    vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2) * 2.0 - 1.0;
    outClip = p;
    gl_Position = vec4(p, 0.0, 1.0);
}
