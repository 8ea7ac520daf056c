#version 460
// Any vertex shader will do; 10 outputs make a shaded vertex (4 + 11 * 16 = 180 bytes) big
// enough that 4 vertices more than allocated overrun draw's 512 bytes of padding.
layout(location = 0) out vec4 outValues[10];

void main() {
    uint v = uint(gl_VertexIndex);
    vec2 corner = vec2(float(v % 3u == 1u), float(v % 3u == 2u));
    gl_Position = vec4(-0.9 + 0.1 * corner.x + 0.01 * float(v % 64u), -0.9 + 0.1 * corner.y, 0.5, 1.0);
    for (int i = 0; i < 10; ++i)
        outValues[i] = vec4(float(v), float(i), 0.0, 1.0);
}
