// A clump vertex's displacement from its mean pose for an instance's motion-graph state,
// d = sum over its modes k of U_k q_k (docs/ARCHITECTURE.md, Motion), read from texel buffers:
// shared by near_vertices.comp (the near raster's vertices) and far_splat.comp (the far field's
// samples, which move with their last-LOD vertex). instance.vert sums the same from storage
// buffers. Needs draw_instance.h (GpuDrawInstance), and the motion data declared before it is
// included as `motionData`, a samplerBuffer of RGBA32F texels (field_packing.cpp, packMotion): a
// basis row per texel, and each block's coordinates in a frame four to a texel from a texel's start.

// `motion` is the vertex's GpuLodVertex::motion: its first basis row (x, a texel), its block's
// first coordinate in a frame (y, in floats, a multiple of 4) and its rank (w's low 16 bits).
// Across a motion-graph jump (inst.pose.z > 0) the coordinates of the two frames (inst.offsets.x
// and .y, multiples of 4) are blended. The coordinates are fetched four at a time, in an outer loop
// of their own: llvmpipe runs an `if`'s body whatever the lanes decide, so a fetch every fourth
// mode behind one would cost a fetch every mode (docs/BENCHMARKS.md).
vec3 clumpVertexDisplacement(uvec4 motion, GpuDrawInstance inst) {
    uint rank = motion.w & 0xffffu;
    uint q0 = (inst.offsets.x + motion.y) >> 2u, q1 = (inst.offsets.y + motion.y) >> 2u;
    bool blending = inst.pose.z > 0.0;
    vec3 d = vec3(0.0);
    for (uint k = 0u; k < rank; k += 4u) {
        vec4 q = texelFetch(motionData, int(q0 + (k >> 2u)));
        if (blending)
            q = mix(q, texelFetch(motionData, int(q1 + (k >> 2u))), inst.pose.z);
        uint modes = min(rank - k, 4u);
        for (uint j = 0u; j < modes; ++j)
            d += texelFetch(motionData, int(motion.x + k + j)).xyz * q[j];
    }
    return d;
}
