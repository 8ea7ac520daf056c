#version 460
// Animate pass: one thread per instance. Steps the instance's motion-graph walk once per motion
// tick that passed since the last frame (frame.motion), each step heading for the wind level at
// the instance's position at that tick (wind_field.h). The walk is motion_step.h's pure integer
// function, the one the CPU reference runs, so the two agree bit for bit.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(local_size_x = kAnimateGroupSize) in;

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer Instances { GpuInstance instances[]; };
layout(set = 0, binding = 2, std430) readonly buffer Clumps { GpuClump clumps[]; };
layout(set = 0, binding = 3, std430) readonly buffer MotionGraph { uint motionGraph[]; };

// The tables of the clump being stepped (motion_step.h's accessors).
GpuClump gClump;
uint motionEdgeStart(uint node) { return motionGraph[gClump.graph.x + node]; }
uint motionEdgeTarget(uint edge) { return motionGraph[gClump.graph.y + edge]; }
uint motionEdgeWeight(uint level, uint edge) { return motionGraph[gClump.graph.z + level * gClump.graphSizes.x + edge]; }
uint motionNaturalNext(uint frame) { return motionGraph[gClump.graph.w + frame]; }
uint motionLevelCount() { return gClump.graphSizes.y; }
uint motionBlendFrames() { return gClump.graphSizes.z; }

#include "motion_step.h"
#include "wind_field.h"

layout(set = 0, binding = 4, std430) buffer MotionStates { GpuMotionState states[]; };

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= frame.counts.x)
        return;
    GpuInstance inst = instances[index];
    gClump = clumps[inst.mesh];
    GpuMotionState state = states[index];
    uint steps = min(frame.motion.y, kMaxMotionStepsPerFrame);
    // Ticks first .. first + steps - 1 lead up to frame.motion.x + steps - 1; the last is this frame.
    for (uint s = 0u; s < steps; ++s) {
        uint tick = frame.motion.x + s;
        float level = windLevelAt(frame, inst.positionScale.x, inst.positionScale.z, tick);
        motionStep(state, windTargetLevel(level, gClump.graphSizes.y), index);
    }
    states[index] = state;
}
