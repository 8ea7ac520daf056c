#version 460
// The ground light map: seen from above, every instance lays its clump's ground grid (a square
// around its base, turned and mirrored as the instance is) over the field, and ground_map.frag
// multiplies in how much light that grid lets through. Runs when the light pass does.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer Instances { GpuInstance instances[]; };
layout(set = 0, binding = 2, std430) readonly buffer Clumps { GpuClump clumps[]; };
layout(push_constant) uniform GroundMapParams { vec4 mirrorNormal; };

layout(location = 0) out vec2 outGrid; // grid coordinates, 0 .. points per side - 1
layout(location = 1) flat out uint outLight; // first vec4 of this instance's variant's ratios
layout(location = 2) flat out uint outResolution;


void main() {
    GpuInstance inst = instances[gl_InstanceIndex];
    GpuClump clump = clumps[inst.mesh];
    uint resolution = clump.ground.z;
    outResolution = resolution;
    if (resolution < 2u) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // no grid: outside the map
        outGrid = vec2(0.0);
        outLight = 0u;
        return;
    }
    // Two triangles: corners (-1,-1) (1,-1) (1,1), (-1,-1) (1,1) (-1,1), from bit masks (lavapipe
    // (Mesa 22.3) at 128-bit vectors corrupts its heap on dynamically indexed local arrays).
    uint i = uint(gl_VertexIndex);
    vec2 corner = vec2(float((0x16u >> i) & 1u), float((0x34u >> i) & 1u)) * 2.0 - 1.0;
    float halfSide = 0.5 * clump.yawBins.w;
    vec3 p = vec3(corner.x * halfSide, 0.0, corner.y * halfSide);
    // The grid point (column, row) sits at x = -size/2 + size column / (resolution - 1), likewise
    // z with the row (transfer.h), so the corners are columns and rows 0 and resolution - 1.
    outGrid = (corner * 0.5 + 0.5) * float(resolution - 1u);
    bool mirrored = inst.positionScale.w < 0.0;
    if (mirrored) {
        vec3 m = vec3(mirrorNormal.x, 0.0, mirrorNormal.z);
        p -= 2.0 * dot(p, m) * m;
    }
    float s = sin(inst.yaw), c = cos(inst.yaw);
    vec2 world = inst.positionScale.xz + vec2(c * p.x + s * p.z, -s * p.x + c * p.z) * abs(inst.positionScale.w);
    vec2 uv = (world - frame.groundMap.xy) * frame.groundMap.zw;
    gl_Position = vec4(uv * 2.0 - 1.0, 0.0, 1.0);

    uint bins = clump.light.y;
    int bin = clamp(int(floor((inst.yaw - clump.yawBins.x) * clump.yawBins.y)), 0, int(bins) - 1);
    uint variant = uint(bin) + (mirrored ? bins : 0u);
    outLight = clump.ground.y + variant * resolution * resolution;
}
