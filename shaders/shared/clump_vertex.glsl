// A clump vertex as the instances draw it, shared by instance.vert (the draw pass) and
// near_vertices.comp (the near raster), which read its data from different kinds of buffer.
// Needs common.glsl (kPi) and draw_instance.h (GpuDrawInstance).

// Its irradiance / pi on both sides, to first order in its displacement d, from its light variant's
// three texels: (E, gradient) per side and channel as half floats (light.comp).
void clumpVertexLight(uvec4 w0, uvec4 w1, uvec4 w2, vec3 d, out vec3 front, out vec3 back) {
    vec4 l0 = vec4(unpackHalf2x16(w0.x), unpackHalf2x16(w0.y)), l1 = vec4(unpackHalf2x16(w0.z), unpackHalf2x16(w0.w));
    vec4 l2 = vec4(unpackHalf2x16(w1.x), unpackHalf2x16(w1.y)), l3 = vec4(unpackHalf2x16(w1.z), unpackHalf2x16(w1.w));
    vec4 l4 = vec4(unpackHalf2x16(w2.x), unpackHalf2x16(w2.y)), l5 = vec4(unpackHalf2x16(w2.z), unpackHalf2x16(w2.w));
    front = max(vec3(l0.x + dot(l0.yzw, d), l1.x + dot(l1.yzw, d), l2.x + dot(l2.yzw, d)), 0.0) / kPi;
    back = max(vec3(l3.x + dot(l3.yzw, d), l4.x + dot(l4.yzw, d), l5.x + dot(l5.yzw, d)), 0.0) / kPi;
}

// Its world position for the instance: p (x̄ + d, clump space) and its normal n reflected about the
// vertical mirror plane (xz: `mirror`) for a mirrored instance, then yawed, scaled and moved to the
// instance's base; n comes back in world space (yawed, not normalised).
vec3 clumpVertexWorld(GpuDrawInstance inst, vec3 p, inout vec3 n, vec2 mirror) {
    if (inst.positionScale.w < 0.0) {
        vec3 m = vec3(mirror.x, 0.0, mirror.y);
        p -= 2.0 * dot(p, m) * m;
        n -= 2.0 * dot(n, m) * m;
    }
    float c = inst.pose.x, s = inst.pose.y;
    mat3 yaw = mat3(c, 0.0, -s, 0.0, 1.0, 0.0, s, 0.0, c);
    n = yaw * n;
    return inst.positionScale.xyz + yaw * (p * abs(inst.positionScale.w));
}
