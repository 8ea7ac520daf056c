#version 460
layout(location = 0) in vec4 inValues[10];
layout(location = 0) out vec4 outColor;

void main() {
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 10; ++i)
        sum += inValues[i];
    outColor = fract(sum * 0.001);
}
