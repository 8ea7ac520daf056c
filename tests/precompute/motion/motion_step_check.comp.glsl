#version 460
// Build-time check that shaders/shared/motion_step.h compiles as GLSL: a minimal compute shader
// that steps one motion state per invocation from tables in storage buffers. Not a render pass.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer EdgeStarts { uint edgeStarts[]; };
layout(std430, set = 0, binding = 1) readonly buffer EdgeTargets { uint edgeTargets[]; };
layout(std430, set = 0, binding = 2) readonly buffer EdgeWeights { uint edgeWeights[]; };
layout(std430, set = 0, binding = 3) readonly buffer NaturalNexts { uint naturalNexts[]; };

layout(push_constant) uniform Push {
    uint instanceCount;
    uint edgeCount;
    uint levelCount;
    uint blendFrames;
    uint targetLevel;
} push;

uint motionEdgeStart(uint node) { return edgeStarts[node]; }
uint motionEdgeTarget(uint edge) { return edgeTargets[edge]; }
uint motionEdgeWeight(uint level, uint edge) { return edgeWeights[level * push.edgeCount + edge]; }
uint motionNaturalNext(uint frame) { return naturalNexts[frame]; }
uint motionLevelCount() { return push.levelCount; }
uint motionBlendFrames() { return push.blendFrames; }

#include "motion_step.h"

layout(std430, set = 0, binding = 4) buffer States { GpuMotionState states[]; };

void main() {
    uint instance = gl_GlobalInvocationID.x;
    if (instance >= push.instanceCount)
        return;
    GpuMotionState state = states[instance];
    motionStep(state, push.targetLevel, instance);
    states[instance] = state;
}
