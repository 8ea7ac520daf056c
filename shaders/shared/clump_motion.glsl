// A clump vertex's displacement from its mean pose for an instance's motion-graph state,
// d = sum over its modes k of U_k q_k (docs/ARCHITECTURE.md, Motion), read from texel buffers:
// shared by instance.vert (the mesh pass), near_vertices.comp (the near raster's vertices) and
// far_splat.comp (the far field's samples, which move with their last-LOD vertex). Needs
// draw_instance.h (GpuDrawInstance), and two views of the motion data declared before
// it is included: `motionData`, a samplerBuffer of floats (the coordinates), and `motionRows`, one
// of RGBA32F texels (the basis rows, one texel each: field_packing.cpp).

// `motion` is the vertex's GpuLodVertex::motion: its first basis row (x, a motionRows texel), its
// block's first coordinate in a frame (y) and its rank (w's low 16 bits). Across a motion-graph
// jump (inst.pose.z > 0) the coordinates of the two frames (inst.offsets.x and .y) are blended.
vec3 clumpVertexDisplacement(uvec4 motion, GpuDrawInstance inst) {
    uint rank = motion.w & 0xffffu;
    uint q0 = inst.offsets.x + motion.y, q1 = inst.offsets.y + motion.y;
    bool blending = inst.pose.z > 0.0;
    vec3 d = vec3(0.0);
    for (uint k = 0u; k < rank; ++k) {
        float q = texelFetch(motionData, int(q0 + k)).r;
        if (blending)
            q = mix(q, texelFetch(motionData, int(q1 + k)).r, inst.pose.z);
        d += texelFetch(motionRows, int(motion.x + k)).xyz * q;
    }
    return d;
}
